// Where to draw the robot: IK at a tool pose on the part, and the start of a scene path.
#include "stitchsim/run/start_pose.h"

#include <algorithm>
#include <optional>

#include "stitchsim/geom/curve.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/sim/cell.h"

namespace stitchsim::run {

StartPose SolveStartPose(const LoadedScene& ls, const Eigen::Isometry3d& tool_in_part_mm) {
  const sim::CellSetup cell = sim::MakeCellSetup(*ls.robot, *ls.scene);
  StartPose out;
  const sim::ToolPoseSolution sol =
      sim::SolveToolPose(cell, tool_in_part_mm, 0.0, std::nullopt, nullptr);
  out.ok = sol.ik.status == sim::IkStatus::kOk;
  out.reason = sol.ik.reason;
  out.joints = out.ok ? sol.ik.joints : sim::HomeJoints(*ls.robot, sol.rail.rail_m);
  out.tool_world_m = sol.tool_world_m;
  return out;
}

Eigen::Isometry3d PathStartTool(const scene::Scene& scene, const scene::PathSpec& path) {
  geom::SurfacePath sp(*scene.surface, *path.curve);
  const geom::PathPoint p0 = sp.AtArcLength(0.0);
  const geom::PathPoint p1 = sp.AtArcLength(std::min(sp.Length(), 1.0));
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.translation() = p0.position;
  tool.linear() = geom::FrameFromNormalAndDirection(p0.normal, p1.position - p0.position)
                      .value_or(Eigen::Matrix3d::Identity());
  return tool;
}

}  // namespace stitchsim::run
