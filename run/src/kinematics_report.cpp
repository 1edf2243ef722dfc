#include "stitchsim/run/kinematics_report.h"

#include <cmath>
#include <string>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/tool_pose.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::run {
namespace {

static_assert(kCliJointCount == sim::kNumJoints);

// Keys in the order written: status first, details after.
using ordered_json = nlohmann::ordered_json;

geom::EulerOrder DialectEulerOrder() { return program::EulerOrderOf(program::Dialect::Default()); }

// Model order: the rail in mm, every revolute joint in degrees.
sim::JointVector JointsFromCli(const std::vector<double>& values) {
  sim::JointVector q;
  for (int j = 0; j < sim::kNumJoints; ++j) {
    const double v = values[static_cast<std::size_t>(j)];
    q[j] = j == sim::kRailX ? v / 1000.0 : v * kDeg;
  }
  return q;
}

std::vector<double> JointsForCli(const sim::JointVector& q) {
  std::vector<double> out(sim::kNumJoints);
  for (int j = 0; j < sim::kNumJoints; ++j) {
    out[static_cast<std::size_t>(j)] = j == sim::kRailX ? q[j] * 1000.0 : q[j] * kRadToDeg;
  }
  return out;
}

// A pose as the dialect writes it: translation (mm if `pose` is in mm) and A B C degrees.
ordered_json PoseJson(const Eigen::Isometry3d& pose, double length_scale) {
  const Eigen::Vector3d t = pose.translation() * length_scale;
  const Eigen::Vector3d abc =
      geom::EulerFromRotation(DialectEulerOrder(), pose.linear()) * kRadToDeg;
  return {{"xyz_mm", {t.x(), t.y(), t.z()}}, {"abc_deg", {abc.x(), abc.y(), abc.z()}}};
}

// Per joint: name, value, limits (CLI units) and whether the value is within them.
ordered_json LimitsJson(const sim::RobotModel& robot, const sim::JointVector& q, double tolerance,
                        bool& all_within) {
  ordered_json out = ordered_json::array();
  all_within = true;
  const std::vector<double> value = JointsForCli(q);
  const std::vector<double> lower = JointsForCli(robot.lower_limits());
  const std::vector<double> upper = JointsForCli(robot.upper_limits());
  for (int j = 0; j < sim::kNumJoints; ++j) {
    const auto i = static_cast<std::size_t>(j);
    const bool within =
        q[j] >= robot.lower_limits()[j] - tolerance && q[j] <= robot.upper_limits()[j] + tolerance;
    all_within = all_within && within;
    out.push_back({{"name", std::string(sim::kJointNames[i])},
                   {"unit", j == sim::kRailX ? "mm" : "deg"},
                   {"value", value[i]},
                   {"lower", lower[i]},
                   {"upper", upper[i]},
                   {"within_limits", within}});
  }
  return out;
}

ordered_json JointNamesJson() {
  ordered_json names = ordered_json::array();
  for (auto n : sim::kJointNames) names.push_back(std::string(n));
  return names;
}

}  // namespace

KinematicsReport ForwardKinematics(const LoadedScene& ls, const std::vector<double>& joints) {
  const sim::RobotModel& robot = *ls.robot;
  const sim::CellSetup cell = sim::MakeCellSetup(robot, *ls.scene);
  const sim::JointVector q = JointsFromCli(joints);

  bool within = true;
  ordered_json out;
  out["scene"] = ls.scene->name;
  out["head"] = ls.scene->head.name;
  out["joint_names"] = JointNamesJson();
  out["joints"] = JointsForCli(q);
  out["flange_world"] = PoseJson(sim::FlangePose(robot, q), 1000.0);
  out["tool_in_part"] = PoseJson(sim::ToolPoseInPart(cell, q), 1.0);
  out["euler_order"] = program::Dialect::Default().euler_order;
  out["configuration"] = sim::ToString(sim::ArmConfigurationOf(robot, q));
  out["joint_limits"] = LimitsJson(robot, q, cell.ik.limit_tolerance, within);
  out["within_limits"] = within;
  return {out, true};
}

KinematicsReport InverseKinematics(const LoadedScene& ls, const std::vector<double>& pose,
                                   std::optional<double> rail_mm, double rotator_deg) {
  const sim::RobotModel& robot = *ls.robot;
  const sim::CellSetup cell = sim::MakeCellSetup(robot, *ls.scene);

  // The pose as a programme line would command it: X Y Z A B C.
  program::MachineState commanded;
  for (program::Axis axis : {program::Axis::kX, program::Axis::kY, program::Axis::kZ,
                             program::Axis::kA, program::Axis::kB, program::Axis::kC}) {
    commanded.axes[static_cast<std::size_t>(axis)] = pose[static_cast<std::size_t>(axis)];
  }
  const Eigen::Isometry3d target = *program::ToolPoseOf(commanded, DialectEulerOrder());
  const sim::ToolPoseSolution sol =
      sim::SolveToolPose(cell, target, rotator_deg * kDeg, rail_mm, nullptr);
  const sim::IkResult& ik = sol.ik;

  ordered_json out;
  out["scene"] = ls.scene->name;
  out["head"] = ls.scene->head.name;
  out["status"] = std::string(sim::ToString(ik.status));
  out["reason"] = ik.reason;
  out["target_in_part"] = {{"xyz_mm", {pose[0], pose[1], pose[2]}},
                           {"abc_deg", {pose[3], pose[4], pose[5]}}};
  out["euler_order"] = program::Dialect::Default().euler_order;
  out["rail"] = {{"rail_mm", sol.rail.rail_m * 1000.0},
                 {"clamped", sol.rail.clamped},
                 {"programmed", sol.rail.programmed}};
  out["joint_names"] = JointNamesJson();
  // Unreachable: no solution exists, so there are no joints to show (IkResult holds the
  // reference joints). Joint limit: the nearest solution ignoring limits, for diagnosis.
  if (ik.status == sim::IkStatus::kUnreachable) {
    out["joints"] = nullptr;
    out["configuration"] = nullptr;
    out["joint_limits"] = nullptr;
    out["fk_check"] = nullptr;
  } else {
    bool within = true;
    out["joints"] = JointsForCli(ik.joints);
    out["configuration"] = sim::ToString(ik.configuration);
    out["joint_limits"] = LimitsJson(robot, ik.joints, cell.ik.limit_tolerance, within);
    out["within_limits"] = within;
    const Eigen::Isometry3d reached = sim::ToolPoseInPart(cell, ik.joints);
    out["fk_check"] = {
        {"position_error_mm", (reached.translation() - target.translation()).norm()},
        {"rotation_error_deg", geom::AngleBetween(reached.linear(), target.linear()) * kRadToDeg},
        {"tool_in_part", PoseJson(reached, 1.0)}};
  }
  return {out, ik.ok()};
}

}  // namespace stitchsim::run
