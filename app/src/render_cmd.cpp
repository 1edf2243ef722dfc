// `stitchsim render`: a PNG of the cell, the part and its paths, the robot at a reachable
// start pose, rendered headless through OSMesa (run/scene_render.h).
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "stitchsim/run/program_overlay.h"
#include "stitchsim/run/scene_render.h"
#include "stitchsim/run/start_pose.h"

namespace stitchsim::app {
namespace {

struct RenderArgs {
  std::string scene;
  std::string program;
  std::string output;
  int width = 1280;
  int height = 960;
  std::string view = "overview";
  std::string coverage_json;
};

int RunRender(const RenderArgs& args) {
  if (!OutputsDistinct({{"--output", args.output}, {"--coverage-json", args.coverage_json}})) {
    return kExitBadInput;
  }
  auto ls = LoadSceneAndRobot(args.scene);
  if (!ls) return kExitBadInput;
  run::RenderRequest req;
  req.output = args.output;
  req.width = args.width;
  req.height = args.height;
  req.view = args.view;
  req.coverage_json = args.coverage_json;
  Eigen::Isometry3d start_tool = run::PathStartTool(*ls->scene, ls->scene->paths.front());
  if (!args.program.empty()) {
    DiagnosticSink sink;
    run::ProgramOverlay po = run::ProgramStitchOverlay(args.program, sink);
    if (PrintRunOutcome(sink, po.status) != kExitOk) return kExitBadInput;
    run::RenderRequest::PointSet set;
    set.label = "stitch";
    set.points_part_mm = std::move(po.stitch_points_part_mm);
    req.point_sets.push_back(std::move(set));
    if (po.first_tool_in_part_mm) start_tool = *po.first_tool_in_part_mm;
  }
  // Start pose: the approach point, clear above the first stitch along its normal, as a
  // programme begins; it also keeps the head from hiding the path in the picture.
  constexpr double kApproachMm = 150.0;
  Eigen::Isometry3d approach = start_tool;
  approach.translation() += kApproachMm * start_tool.linear().col(2);
  const run::StartPose start = run::SolveStartPose(*ls, req.view == "head" ? start_tool : approach);
  if (!start.ok) {
    std::cerr << "stitchsim: warning: start pose not reachable (" << start.reason
              << "); drawing the robot at home\n";
  }
  req.joints = start.joints;
  req.tool_world_m = start.tool_world_m;
  DiagnosticSink sink;
  const run::Status status = run::RenderScene(*ls, req, sink);
  return PrintRunOutcome(sink, status);
}

}  // namespace

void AddRenderCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render the cell, the part and its paths (or a programme's stitches) to a PNG");
  cmd->add_option("--scene", args->scene, "Scene YAML file")->required();
  cmd->add_option("--program", args->program, "Draw this programme's stitch points");
  cmd->add_option("-o,--output", args->output, "Output PNG file")->required();
  cmd->add_option("--width", args->width, "Image width in pixels")->check(CLI::Range(16, 8192));
  cmd->add_option("--height", args->height, "Image height in pixels")->check(CLI::Range(16, 8192));
  cmd->add_option("--coverage-json", args->coverage_json,
                  "Also write the pixel coverage of robot, head, mold, preform, paths... (JSON)");
  cmd->add_option("--view", args->view, "overview | head | part")
      ->check(CLI::IsMember({"overview", "head", "part"}));
  AddScenePathFlag(*cmd);
  cmd->callback([args, &exit_code] { exit_code = RunRender(*args); });
}

}  // namespace stitchsim::app
