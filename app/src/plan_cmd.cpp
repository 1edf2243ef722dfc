// `stitchsim plan stitch`: writes the stitching programme of one path of a scene.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "stitchsim/common/files.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/dialect.h"

namespace stitchsim::app {
namespace {

struct PlanStitchArgs {
  std::string scene;
  std::string path;
  std::string mode = "auto";
  double stitch_length_mm = 0.0;
  std::string output;
};

int RunPlanStitch(const PlanStitchArgs& a) {
  DiagnosticSink sink;
  auto scene = scene::LoadScene(a.scene, sink);
  if (PrintDiagnostics(sink) || !scene) return kExitBadInput;
  const scene::PathSpec* path = a.path.empty() ? &scene->paths.front() : scene->FindPath(a.path);
  if (path == nullptr) {
    std::string names;
    for (const auto& p : scene->paths) names += (names.empty() ? "" : ", ") + p.name;
    PrintError("plan-unknown-path", a.scene + ": no path named '" + a.path + "' (paths: " +
                                        names + ")");
    return kExitBadInput;
  }
  planner::StitchPlanOptions options;
  options.mode = *planner::ParseMode(a.mode);
  if (a.stitch_length_mm != 0.0) options.nominal_stitch_length_mm = a.stitch_length_mm;
  auto planner = planner::StitchPathPlanner::Create(*scene, *path, options, sink);
  if (PrintDiagnostics(sink) || !planner) return kExitBadInput;
  // Written to memory first, then to the file whole (temporary file + rename).
  std::ostringstream text;
  const planner::ProgramSummary s =
      planner::WriteStitchProgram(*planner, *scene, path->name, program::Dialect::Default(), text);
  if (std::string err = WriteFileAtomically(a.output, text.str()); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::printf(
      "%s: path '%s' on %s, %s mode: %d stitches of %.4f mm (nominal %.4f mm) over %.3f mm; "
      "%d decoupled, %d coupled; %ld motion lines; estimated cycle time %.1f s "
      "(stitching %.1f s, rotation and settle %.1f s) -> %s\n",
      scene->name.c_str(), path->name.c_str(), scene->head.name.c_str(),
      std::string(planner::ToString(s.mode)).c_str(), s.stitches, s.stitch_length_mm,
      options.nominal_stitch_length_mm.value_or(scene->nominal_stitch_length_mm),
      s.path_length_mm, s.decoupled, s.stitches - s.decoupled, s.motion_lines, s.time.Total(),
      s.time.stitching_s, s.time.rotation_s, a.output.c_str());
  return kExitOk;
}

}  // namespace

void AddPlanCommand(CLI::App& app, int& exit_code) {
  CLI::App* plan = app.add_subcommand("plan", "Write robot programmes from a scene");
  plan->require_subcommand(1);
  auto args = std::make_shared<PlanStitchArgs>();
  CLI::App* cmd = plan->add_subcommand(
      "stitch", "A 3D stitch path (seed 000): coupled, decoupled or auto per stitch");
  cmd->add_option("--scene", args->scene, "Scene YAML file")->required();
  cmd->add_option("--path", args->path, "Path name (default: the scene's first path)");
  cmd->add_option("--mode", args->mode, "coupled | decoupled | auto")
      ->check(CLI::IsMember({"coupled", "decoupled", "auto"}));
  cmd->add_option("--stitch-length", args->stitch_length_mm,
                  "Nominal stitch length in mm (default: the scene's)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("-o,--output", args->output, "Programme file to write")->required();
  cmd->callback([args, &exit_code] { exit_code = RunPlanStitch(*args); });
}

}  // namespace stitchsim::app
