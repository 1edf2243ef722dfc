// `stitchsim report merge PART...`: the report of one run from the partial results of
// `verify --shard I/N --part FILE` (docs/ci.md).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "chunked_cmd.h"
#include "chunked_verify.h"
#include "commands.h"
#include "stitchsim/common/files.h"

namespace stitchsim::app {
namespace {

struct MergeArgs {
  std::vector<std::string> parts;
  std::string report_json;
  std::string junit;
};

struct Part {
  std::string file;
  nlohmann::json j;
  int lo = -1, hi = -1;  ///< chunk range (-1: none)
};

// The keys every part of one run shares (the programme, the scene, the options, the cut).
constexpr const char* kSameKeys[] = {
    "program",          "program_bytes",     "program_fnv1a",  "scene",  "dialect",
    "scene_files",      "no_collision",      "allow_mismatch", "shards", "chunks_total",
    "chunk_lines",      "warm_lines",        "lines",          "moves",  "cycle_time_s",
    "stitch_length_mm", "declared_stitches", "tool_version"};

bool ReadPart(const std::string& file, Part& part) {
  const std::optional<std::string> text = ReadFile(file);
  if (!text) {
    PrintError("io-missing-file", "cannot read part " + file);
    return false;
  }
  part.file = file;
  part.j = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (part.j.is_discarded() || !part.j.is_object() ||
      part.j.value("format", std::string()) != "stitchsim-verify-part") {
    PrintError("part-bad", file +
                               ": not a whole verify part file (cut short by a killed shard, or "
                               "another file); run its shard again");
    return false;
  }
  if (part.j.value("version", 0) != 1) {
    PrintError("part-bad", file + ": part format version " +
                               std::to_string(part.j.value("version", 0)) + ", expected 1");
    return false;
  }
  for (const char* key : kSameKeys) {
    if (!part.j.contains(key)) {
      PrintError("part-bad", file + ": no '" + key + "'");
      return false;
    }
  }
  if (part.j.contains("chunks") && part.j["chunks"].is_array() && part.j["chunks"].size() == 2) {
    part.lo = part.j["chunks"][0].get<int>();
    part.hi = part.j["chunks"][1].get<int>();
  }
  return true;
}

// Every part from the same run, together covering every chunk once, in order.
bool PartsFit(std::vector<Part>& parts) {
  const Part& first = parts.front();
  for (const Part& p : parts) {
    for (const char* key : kSameKeys) {
      if (p.j[key] != first.j[key]) {
        PrintError("part-mismatch", p.file + " and " + first.file + " differ in '" + key +
                                        "': parts of different programmes, scenes or runs");
        return false;
      }
    }
  }
  std::vector<Part*> with;
  for (Part& p : parts) {
    if (p.lo >= 0) with.push_back(&p);
  }
  std::sort(with.begin(), with.end(), [](const Part* a, const Part* b) { return a->lo < b->lo; });
  const int total = first.j["chunks_total"].get<int>();
  const long lines = first.j["lines"].get<long>();
  int expect = 0;
  const auto missing = [&](int from, int to) {
    PrintError("part-missing",
               "chunks " + std::to_string(from) + ".." + std::to_string(to) + " of " +
                   std::to_string(total) + " (of the programme's " + std::to_string(lines) +
                   " lines) are in no part: a shard was killed or its part is missing; run it "
                   "again (" +
                   std::to_string(first.j["shards"].get<int>()) + " shards)");
  };
  for (const Part* p : with) {
    if (p->lo > expect) {
      missing(expect, p->lo - 1);
      return false;
    }
    if (p->lo < expect) {
      PrintError("part-duplicate", p->file + " repeats chunks another part holds");
      return false;
    }
    expect = p->hi + 1;
  }
  if (expect < total) {
    missing(expect, total - 1);
    return false;
  }
  std::vector<Part> ordered;
  for (Part* p : with) ordered.push_back(std::move(*p));
  parts = std::move(ordered);
  return true;
}

// A programme run in one chunk: its one part holds the finished reports.
int WriteComplete(const Part& part, const MergeArgs& a) {
  const nlohmann::json& c = part.j["complete"];
  if (!c.is_object() || !c.contains("text") || !c.contains("json") || !c.contains("junit")) {
    PrintError("part-bad", part.file + ": bad 'complete'");
    return kExitBadInput;
  }
  std::vector<std::pair<std::filesystem::path, std::string>> reports;
  if (!a.report_json.empty()) reports.emplace_back(a.report_json, c["json"].get<std::string>());
  if (!a.junit.empty()) reports.emplace_back(a.junit, c["junit"].get<std::string>());
  if (std::string err = WriteFilesAtomically(reports); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::cout << c["text"].get<std::string>();
  return c.value("errors", 0L) == 0 ? kExitOk : kExitFindings;
}

int RunMerge(const MergeArgs& a) {
  if (!OutputsDistinct({{"--report", a.report_json}, {"--junit", a.junit}})) return kExitBadInput;
  std::vector<Part> parts(a.parts.size());
  for (std::size_t i = 0; i < a.parts.size(); ++i) {
    if (!ReadPart(a.parts[i], parts[i])) return kExitBadInput;
  }
  if (!PartsFit(parts)) return kExitBadInput;
  const nlohmann::json& head = parts.front().j;
  const std::string scene_file = head["scene"].get<std::string>();
  auto ls = LoadSceneAndRobot(scene_file);
  if (!ls) return kExitBadInput;
  std::size_t k = 0;
  for (const auto& f : SceneFingerprints(*ls->scene)) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.fnv1a));
    if (k >= head["scene_files"].size() || head["scene_files"][k]["fnv1a"] != hex) {
      PrintError("part-stale", "the " + f.role + " (" + f.path +
                                   ") changed since the shards ran: run them again");
      return kExitBadInput;
    }
    ++k;
  }
  if (parts.size() == 1 && parts.front().j.contains("complete"))
    return WriteComplete(parts.front(), a);
  const std::optional<program::Dialect> dialect = DialectOption(head["dialect"]);
  if (!dialect) return kExitBadInput;
  SessionOptions so;
  so.no_collision = head["no_collision"].get<bool>();
  so.allow_mismatch = head["allow_mismatch"].get<bool>();
  std::optional<long> declared;
  if (!head["declared_stitches"].is_null()) declared = head["declared_stitches"].get<long>();
  std::unique_ptr<VerifySession> vs =
      MakeSession(std::move(*ls), *dialect, head["stitch_length_mm"].get<double>(), declared, so);
  if (!vs) return kExitBadInput;
  verify::Verifier merged(vs->Rules(), false);
  ExactSum timed;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const nlohmann::json& j = parts[i].j;
    if (i > 0 && j["start"] != parts[i - 1].j["end"]) {
      PrintError("part-boundary",
                 parts[i].file + " started from a state that differs from where " +
                     parts[i - 1].file +
                     " ended (the arm's branch or the controller's speed at the cut): verify "
                     "with fewer shards, or in one process with --jobs");
      return kExitBadInput;
    }
    ExactSum part_timed;
    if (!ExactSum::FromHex(j.value("timed_sum", std::string()), part_timed)) {
      PrintError("part-bad", parts[i].file + ": bad timed_sum");
      return kExitBadInput;
    }
    timed.Add(part_timed);
    std::string error;
    verify::Verifier v(vs->Rules(), false);
    if (!v.LoadPartial(j["verifier"], error)) {
      PrintError("part-bad", parts[i].file + ": " + error);
      return kExitBadInput;
    }
    merged.Absorb(v);
  }
  const trace::TraceFileSummary summary{head["lines"].get<long>(), head["moves"].get<long>(),
                                        head["cycle_time_s"].get<double>(), timed.Value()};
  verify::Report report = RunReport(head["program"].get<std::string>(), scene_file, *vs->ls.scene,
                                    vs->stitch_length_mm, summary);
  merged.Finish(report);
  if (WriteReports(report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  return report.errors == 0 ? kExitOk : kExitFindings;
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
