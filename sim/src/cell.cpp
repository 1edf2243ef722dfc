#include "stitchsim/sim/cell.h"

#include <algorithm>
#include <cmath>

#include "stitchsim/common/units.h"
#include "stitchsim/sim/collision.h"

namespace stitchsim::sim {
namespace {

constexpr double kHalfPi = kPi / 2;

Eigen::Isometry3d MmToM(const Eigen::Isometry3d& pose_mm) {
  Eigen::Isometry3d out = pose_mm;
  out.translation() /= 1000.0;
  return out;
}

}  // namespace

CellSetup MakeCellSetup(const RobotModel& robot, const scene::Scene& scene) {
  CellSetup cell;
  cell.robot = &robot;
  cell.flange_to_tool_m = scene.head.flange_to_tool_m;
  cell.mount = scene.mount;
  cell.mount_to_part_m = scene.mount_to_part_m;
  cell.rail_offset_m = scene.rail_offset_mm / 1000.0;
  cell.ik.reference = HomeJoints(robot, 0.0);
  if (cell.mount == scene::Mount::kTable) cell.fixed_part_world_m = PartPoseWorld(cell, 0.0);
  cell.ik.wrist_singularity_rad =
      scene.limits.Value(scene::LimitKey::kSingularityA5MinDeg) * kPi / 180.0;
  return cell;
}

Eigen::Isometry3d PartPoseWorld(const CellSetup& cell, double rotator_rad) {
  if (cell.fixed_part_world_m) return *cell.fixed_part_world_m;
  if (cell.mount == scene::Mount::kRotator) {
    return RotatorCarriedPose(*cell.robot, rotator_rad, cell.mount_to_part_m);
  }
  const int table = cell.robot->LinkIndex("table");
  return LinkPose(*cell.robot, JointVector::Zero(), table) * cell.mount_to_part_m;
}

JointVector HomeJoints(const RobotModel& robot, double rail_m) {
  JointVector q = JointVector::Zero();
  q[kRailX] = std::clamp(rail_m, robot.lower_limits()[kRailX], robot.upper_limits()[kRailX]);
  q[kA2] = -kHalfPi;
  q[kA3] = kHalfPi;
  q[kA5] = kHalfPi;
  return q;
}

ToolPoseSolution SolveToolPose(const CellSetup& cell, const Eigen::Isometry3d& tool_in_part_mm,
                               double rotator_rad, std::optional<double> programmed_rail_mm,
                               const JointVector* previous) {
  ToolPoseSolution out;
  out.tool_world_m = PartPoseWorld(cell, rotator_rad) * MmToM(tool_in_part_mm);
  RailPolicy policy;
  policy.base_offset_along_rail_m = cell.rail_offset_m;
  if (programmed_rail_mm) policy.programmed_rail_m = *programmed_rail_mm / 1000.0;
  out.rail = RailForTarget(*cell.robot, out.tool_world_m, policy);
  const Eigen::Isometry3d flange = FlangeTargetForTool(out.tool_world_m, cell.flange_to_tool_m);
  JointVector seed = previous != nullptr ? *previous : HomeJoints(*cell.robot, out.rail.rail_m);
  seed[kRotator] = rotator_rad;
  IkOptions options = cell.ik;
  options.reference = seed;
  out.ik =
      SolveIk(*cell.robot, flange, out.rail.rail_m, previous != nullptr ? &seed : nullptr, options);
  out.ik.joints[kRotator] = rotator_rad;
  return out;
}

Eigen::Isometry3d ToolPoseInPart(const CellSetup& cell, const JointVector& q) {
  Eigen::Isometry3d tool = PartPoseWorld(cell, q[kRotator]).inverse() * FlangePose(*cell.robot, q) *
                           cell.flange_to_tool_m;
  tool.translation() *= 1000.0;
  return tool;
}

trace::CellDescription DescribeCell(const RobotModel& robot, const CollisionWorld* collision) {
  trace::CellDescription d;
  for (int j = 0; j < kNumJoints; ++j) {
    d.joint_names[static_cast<std::size_t>(j)] =
        std::string(kJointNames[static_cast<std::size_t>(j)]);
  }
  d.lower_limits = robot.lower_limits();
  d.upper_limits = robot.upper_limits();
  d.max_velocities = robot.max_velocities();
  d.max_accelerations = robot.max_accelerations();
  d.max_efforts = robot.efforts();
  d.payload_rated_kg = robot.payload_rating().mass_kg;
  d.payload_rated_lz_m = robot.payload_rating().lz_m;
  d.payload_rated_lxy_m = robot.payload_rating().lxy_m;
  d.wrist_to_flange_m = robot.opw().c4_m;
  d.collision_checked = collision != nullptr;
  if (collision != nullptr) d.bodies = collision->BodyNames();
  return d;
}

}  // namespace stitchsim::sim
