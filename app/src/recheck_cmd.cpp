// `stitchsim recheck`: a saved trace (`verify --save-trace`) checked again against the scene's
// (and --limits') limits, without simulating. The same reports as `verify`, byte for byte when
// nothing changed.
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "stitchsim/common/files.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/scene/limits_file.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {
namespace {

struct RecheckArgs {
  std::string trace;
  std::string scene;
  std::string limits;
  std::string report_json;
  std::string junit;
};

// The trace was made on this scene and head, from the same files (limit changes go through
// --limits, never through edited scene files: geometry and IK are baked into the trace).
bool TraceFitsScene(const trace::TraceFileHeader& h, const RecheckArgs& a,
                    const scene::Scene& scene) {
  if (h.scene_name != scene.name || h.head != scene.head.name) {
    PrintError("trace-scene-mismatch",
               a.trace + " was saved on scene '" + h.scene_name + "' with head '" + h.head +
                   "', but " + a.scene + " is scene '" + scene.name + "' with head '" +
                   scene.head.name + "': run `stitchsim verify` on this scene instead");
    return false;
  }
  const std::vector<trace::FileFingerprint> now = SceneFingerprints(scene);
  for (const trace::FileFingerprint& was : h.fingerprints) {
    const trace::FileFingerprint* same_role = nullptr;
    for (const auto& f : now) {
      if (f.role == was.role) same_role = &f;
    }
    if (same_role == nullptr || same_role->fnv1a != was.fnv1a) {
      PrintError("trace-stale",
                 a.trace + ": the " + was.role + " (" +
                     (same_role != nullptr ? same_role->path : was.path) +
                     ") changed since the trace was saved: run `stitchsim verify --save-trace` "
                     "again (to change only limits, keep the files and pass --limits)");
      return false;
    }
  }
  return true;
}

// The IK's singularity band is applied while simulating: a --limits file cannot move it.
bool SimulationLimitsUnchanged(const trace::TraceFileHeader& h, const LoadedScene& ls,
                               const RecheckArgs& a) {
  const sim::CellSetup cell = sim::MakeCellSetup(*ls.robot, *ls.scene);
  if (cell.ik.wrist_singularity_rad == h.ik_wrist_singularity_rad) return true;
  PrintError("trace-simulation-limit",
             "kin.singularity a5_min_deg is applied by the IK while simulating, so " + a.trace +
                 " (saved with another value) cannot be rechecked with it: run `stitchsim "
                 "verify` with the new limit");
  return false;
}

int RunRecheck(const RecheckArgs& a) {
  if (!OutputsDistinct({{"--report", a.report_json}, {"--junit", a.junit}})) return kExitBadInput;
  std::string error;
  const std::unique_ptr<trace::TraceFileReader> reader =
      trace::TraceFileReader::Open(a.trace, error);
  if (!reader) {
    PrintError("trace-bad-file", error);
    return kExitBadInput;
  }
  const trace::TraceFileHeader& h = reader->Header();
  auto ls = LoadSceneAndRobot(a.scene);
  if (!ls || !TraceFitsScene(h, a, *ls->scene)) return kExitBadInput;
  if (!a.limits.empty()) {
    DiagnosticSink sink;
    const bool ok = scene::ApplyLimitsFile(a.limits, *ls->scene, sink);
    if (PrintDiagnostics(sink) || !ok) return kExitBadInput;
  }
  if (!SimulationLimitsUnchanged(h, *ls, a)) return kExitBadInput;
  const process::ProcessModel model = process::MakeProcessModel(*ls->scene, h.stitch_length_mm);
  verify::RuleContext ctx{ls->scene.get(), &h.cell, &model};
  ctx.declared_stitches = h.declared_stitches;
  verify::Verifier verifier(ctx, false);
  trace::TraceFileSummary run;
  if (!reader->Replay(verifier, run, error)) {
    PrintError("trace-bad-file", error);
    return kExitBadInput;
  }
  verify::Report report = RunReport(h.program_file, a.scene, *ls->scene, h.stitch_length_mm, run);
  verifier.Finish(report);
  if (WriteReports(report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  return report.errors == 0 ? kExitOk : kExitFindings;
}

}  // namespace

std::vector<trace::FileFingerprint> SceneFingerprints(const scene::Scene& scene) {
  const std::pair<const char*, const std::filesystem::path*> files[] = {
      {"scene", &scene.file},
      {"head spec", &scene.head.file},
      {"cell URDF", &scene.cell_urdf},
      {"cell MJCF", &scene.cell_mjcf},
      {"head MJCF", &scene.head.mjcf}};
  std::vector<trace::FileFingerprint> out;
  for (const auto& [role, path] : files) {
    if (path->empty()) continue;
    const std::optional<std::string> bytes = ReadFile(*path);
    // An unreadable file fingerprints as 0: it matches nothing a readable file gives.
    out.push_back({role, path->string(), bytes ? trace::Fnv1a64(*bytes) : 0});
  }
  return out;
}

verify::Report RunReport(const std::string& program_file, const std::string& scene_file,
                         const scene::Scene& scene, double stitch_length_mm,
                         const trace::TraceFileSummary& run) {
  verify::Report report;
  report.program_file = program_file;
  report.scene_file = scene_file;
  report.scene_name = scene.name;
  report.head = scene.head.name;
  report.lines = run.lines;
  report.moves = run.moves;
  report.stitch_length_mm = stitch_length_mm;
  report.cycle_time_s = run.cycle_time_s;
  report.cycle_time_timed_s = run.cycle_time_timed_s;
  return report;
}

int WriteReports(const verify::Report& report, const std::string& json, const std::string& junit) {
  // Reports are written whole or not at all, as a set.
  std::vector<std::pair<std::filesystem::path, std::string>> reports;
  if (!json.empty()) reports.emplace_back(json, verify::ReportToJson(report));
  if (!junit.empty()) reports.emplace_back(junit, verify::ReportToJunit(report));
  if (std::string err = WriteFilesAtomically(reports); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::cout << verify::ReportToText(report);
  return kExitOk;
}

void AddRecheckCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RecheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "recheck",
      "Check a saved trace (verify --save-trace) again with the scene's or new limits, without "
      "simulating");
  cmd->add_option("trace", args->trace, "Trace file written by verify --save-trace")->required();
  cmd->add_option("--scene", args->scene, "Scene YAML file the trace was saved on")->required();
  cmd->add_option("--limits", args->limits,
                  "Rule-limit overrides (a YAML file with a `limits:` map, docs/scene-format.md)");
  cmd->add_option("--report", args->report_json, "Write the JSON report here");
  cmd->add_option("--junit", args->junit, "Write a JUnit XML report here");
  AddScenePathFlag(*cmd);
  cmd->callback([args, &exit_code] { exit_code = RunRecheck(*args); });
}

}  // namespace stitchsim::app
