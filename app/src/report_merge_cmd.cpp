// `stitchsim report merge PART...`: the report of one run from the partial results of
// `verify --shard I/N --part FILE` (docs/ci.md).
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "stitchsim/common/files.h"
#include "stitchsim/run/parts.h"
#include "verify_cli.h"

namespace stitchsim::app {
namespace {

struct MergeArgs {
  std::vector<std::string> parts;
  std::string report_json;
  std::string junit;
};

// A programme run in one chunk: its one part's finished reports, written as they are.
int WriteComplete(const run::CompleteReports& c, const MergeArgs& a) {
  std::vector<std::pair<std::filesystem::path, std::string>> reports;
  if (!a.report_json.empty()) reports.emplace_back(a.report_json, c.json);
  if (!a.junit.empty()) reports.emplace_back(a.junit, c.junit);
  if (std::string err = WriteFilesAtomically(reports); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::cout << c.text;
  return c.errors == 0 ? kExitOk : kExitFindings;
}

int RunMerge(const MergeArgs& a) {
  if (!OutputsDistinct({{"--report", a.report_json}, {"--junit", a.junit}})) return kExitBadInput;
  DiagnosticSink sink;
  const run::MergedReport merged = run::MergeParts(a.parts, SceneLoadOptions(), sink);
  PrintDiagnostics(sink);
  if (merged.status == run::RunStatus::kBadInput) return kExitBadInput;
  if (merged.complete) return WriteComplete(*merged.complete, a);
  if (WriteReports(merged.report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  return static_cast<int>(merged.status);
}

}  // namespace

void AddReportCommand(CLI::App& app, int& exit_code) {
  CLI::App* report = app.add_subcommand("report", "Work with verification results");
  report->require_subcommand(1);
  auto args = std::make_shared<MergeArgs>();
  CLI::App* merge = report->add_subcommand(
      "merge",
      "The report of one verify run from the parts of its shards (verify --shard I/N "
      "--part FILE): text on stdout, exit as verify");
  merge->add_option("parts", args->parts, "Part files, one per shard, any order")->required();
  merge->add_option("--report", args->report_json, "Write the JSON report here");
  merge->add_option("--junit", args->junit, "Write a JUnit XML report here");
  merge->callback([args, &exit_code] { exit_code = RunMerge(*args); });
}

}  // namespace stitchsim::app
