#pragma once
// The stitchsim subcommands. Each Add*Command registers itself on the CLI11 app and writes
// its exit code into `exit_code` when it runs.

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "stitchsim/render/renderer.h"
#include "stitchsim/sim/kinematics.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {

void AddRenderCommand(CLI::App& app, int& exit_code);
void AddCheckCommand(CLI::App& app, int& exit_code);
void AddPlanCommand(CLI::App& app, int& exit_code);
/// `plan ply` under the `plan` command (ply_cmd.cpp).
void AddPlanPlyCommand(CLI::App& plan, int& exit_code);
void AddVerifyCommand(CLI::App& app, int& exit_code);
/// `report merge` (report_merge_cmd.cpp): the report of a run from its shards' parts.
void AddReportCommand(CLI::App& app, int& exit_code);
void AddKinematicsCommands(CLI::App& app, int& exit_code);
void AddRecheckCommand(CLI::App& app, int& exit_code);
void AddExportStepCommand(CLI::App& app, int& exit_code);
/// `sequence` (sequence_cmd.cpp): off-part course ordering of an AFP programme.
void AddSequenceCommand(CLI::App& app, int& exit_code);
/// `diff` (diff_cmd.cpp): two programmes verified and their reports compared.
void AddDiffCommand(CLI::App& app, int& exit_code);

/// Writes coverage_ply<n>.png into `dir` for each ply afp.coverage measured (afp_snapshot.cpp);
/// kExitOk, or kExitBadInput (printed) when a file cannot be written.
int WriteAfpCoverageSnapshots(const verify::Verifier& verifier, const std::string& dir);

/// A reachable pose for the robot to be drawn in (home when IK fails).
struct StartPose {
  bool ok = false;
  std::string reason;
  sim::JointVector joints = sim::JointVector::Zero();
  Eigen::Isometry3d tool_world_m = Eigen::Isometry3d::Identity();
};
StartPose SolveStartPose(const LoadedScene& ls, const Eigen::Isometry3d& tool_in_part_mm);
/// Tool pose (part frame, mm) at the start of a scene path: z = normal, y = along the path.
Eigen::Isometry3d PathStartTool(const scene::Scene& scene, const scene::PathSpec& path);

struct RenderRequest {
  std::string output;
  int width = 1280;
  int height = 960;
  std::string view = "overview";  ///< overview | head | part (the stitches, from above)
  std::string coverage_json;      ///< if set, write per-class pixel counts here
  sim::JointVector joints = sim::JointVector::Zero();
  Eigen::Isometry3d tool_world_m = Eigen::Isometry3d::Identity();
  /// Points to draw instead of the scene's paths (stitches), part frame, mm.
  struct PointSet {
    std::string label;  ///< coverage class, e.g. "stitch"
    std::vector<Eigen::Vector3d> points_part_mm;
    std::array<float, 4> rgba = {0.1f, 0.9f, 0.2f, 1.0f};
    double radius_scale = 1.0;
    bool polyline = false;  ///< connect the points (else one sphere each)
  };
  std::vector<PointSet> point_sets;
  /// Applied to the picture before it is written (snapshots: title bar and legend).
  std::function<void(render::Image&)> decorate;
};
int RunRenderScene(const LoadedScene& ls, const RenderRequest& req);

/// Stitch points of a programme (part frame, mm) for drawing; nullopt on bad input
/// (diagnostics printed).
struct ProgramOverlay {
  std::vector<Eigen::Vector3d> stitch_points_part_mm;
  std::optional<Eigen::Isometry3d> first_tool_in_part_mm;
};
std::optional<ProgramOverlay> ProgramStitchOverlay(const LoadedScene& ls,
                                                   const std::string& program_file);

}  // namespace stitchsim::app
