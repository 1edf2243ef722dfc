// `stitchsim diff OLD NEW --scene S`: verifies both programmes as `verify` does and lists the
// findings that appeared, disappeared or changed (verify/report_diff.h), the per-rule counts,
// verdict, cycle time and stitch count; exit 1 when the new programme has an error the old one
// did not.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli_common.h"
#include "cli_options.h"
#include "stitchsim/common/files.h"
#include "stitchsim/verify/report_diff.h"
#include "verify_cli.h"

namespace stitchsim::app {
namespace {

struct DiffArgs {
  std::string old_program, new_program;
  std::string scene;
  std::string dialect;
  std::string report_json;
  std::string junit;
  bool no_collision = false;
  bool allow_mismatch = false;
  bool quiet = false;
  int jobs = 0;  ///< 0: the number of cores
  verify::DiffOptions options;
};

// One programme verified as `stitchsim verify` would (chunked for a file, serial for a pipe);
// nullopt on bad input (diagnostics printed with the programme's file and line).
std::optional<verify::Report> Verified(const DiffArgs& a, const std::string& program) {
  run::VerifyRunOptions o;
  o.program = program;
  o.dialect = a.dialect;
  o.scene = a.scene;
  o.run.no_collision = a.no_collision;
  o.run.allow_mismatch = a.allow_mismatch;
  o.chunks.jobs = a.jobs;
  run::VerifyRun run;
  if (RunVerificationPrinted(o, a.quiet, run) != kExitOk) return std::nullopt;
  return std::move(run.report);
}

int RunDiff(const DiffArgs& a) {
  if (!OutputsDistinct({{"--report", a.report_json}, {"--junit", a.junit}})) return kExitBadInput;
  // The old run's session (cell, MuJoCo, collision world) is released before the new one runs.
  const std::optional<verify::Report> old_report = Verified(a, a.old_program);
  if (!old_report) return kExitBadInput;
  const std::optional<verify::Report> new_report = Verified(a, a.new_program);
  if (!new_report) return kExitBadInput;
  const verify::ReportDiff diff = verify::DiffReports(*old_report, *new_report, a.options);
  // Reports are written whole or not at all, as a set.
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  if (!a.report_json.empty()) files.emplace_back(a.report_json, verify::ReportDiffToJson(diff));
  if (!a.junit.empty()) files.emplace_back(a.junit, verify::ReportDiffToJunit(diff));
  if (std::string err = WriteFilesAtomically(files); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::cout << verify::ReportDiffToText(diff);
  return diff.new_errors ? kExitFindings : kExitOk;
}

}  // namespace

void AddDiffCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DiffArgs>();
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "Verify two programmes on one scene and list the findings that appeared, disappeared or "
      "changed (matched by position on the path, not by line), and the cycle-time change");
  cmd->add_option("old", args->old_program, "The programme before the change")->required();
  cmd->add_option("new", args->new_program, "The programme after the change")->required();
  cmd->add_option("--scene", args->scene, "Scene YAML file")->required();
  cmd->add_option("--report", args->report_json, "Write the JSON diff here");
  cmd->add_option("--junit", args->junit, "Write a JUnit XML diff here");
  cmd->add_option("--dialect", args->dialect,
                  "Dialect YAML file (default: the built-in dialect, models/dialect/default.yaml)");
  AddLengthOption(
      cmd, "--tolerance-mm", [args](double mm) { args->options.position_tolerance_mm = mm; },
      LengthUnit::kMillimetre, LengthRange::kNonNegative,
      "Findings of one rule and subject whose tool points are at most this far apart are one "
      "finding",
      "0.5 mm");
  cmd->add_option("--value-tolerance-pct", args->options.value_tolerance_pct,
                  "A matched finding whose value moved by more than this percentage of the old "
                  "value is listed as changed")
      ->check(CLI::NonNegativeNumber);
  AddScenePathFlag(*cmd);
  cmd->add_flag("--no-collision", args->no_collision,
                "Skip the FCL collision checks (collision.* rules) in both runs");
  cmd->add_option("--jobs,-j", args->jobs,
                  "Worker threads of each run (default: the number of cores)")
      ->check(CLI::Range(0, 256));
  cmd->add_flag("--quiet,-q", args->quiet, "No progress on stderr");
  cmd->add_flag("--allow-mismatch", args->allow_mismatch,
                "Verify programmes whose header names another scene or head anyway");
  cmd->callback([args, &exit_code] { exit_code = RunDiff(*args); });
}

}  // namespace stitchsim::app
