#pragma once
// Where to draw the robot: a reachable pose for a tool pose on the part (`stitchsim render`,
// the snapshots), and the tool pose at the start of a scene path.

#include <Eigen/Geometry>
#include <string>

#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::run {

/// A reachable pose for the robot to be drawn in (home when IK fails).
struct StartPose {
  bool ok = false;                                     ///< IK reached the tool pose
  std::string reason;                                  ///< why IK failed (empty when ok)
  sim::JointVector joints = sim::JointVector::Zero();  ///< model order, rad (rail m); home if !ok
  Eigen::Isometry3d tool_world_m = Eigen::Isometry3d::Identity();  ///< the tool pose, world, m
};

/// Solves the cell's IK for `tool_in_part_mm` (part frame, mm) at the scene's rotator angle 0.
StartPose SolveStartPose(const LoadedScene& ls, const Eigen::Isometry3d& tool_in_part_mm);

/// Tool pose (part frame, mm) at the start of a scene path: z = normal, y = along the path.
Eigen::Isometry3d PathStartTool(const scene::Scene& scene, const scene::PathSpec& path);

}  // namespace stitchsim::run
