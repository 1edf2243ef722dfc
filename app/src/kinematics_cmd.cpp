// `stitchsim fk` and `stitchsim ik`: the cell's kinematics as JSON, for people debugging a
// cell. Joints in model order [rail_x mm, a1..a6 deg, rotator deg]; tool poses in the part
// frame in the dialect's convention (X Y Z mm, A B C deg, R = Rz(C) Ry(B) Rx(A)).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "cli_options.h"
#include "commands.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/tool_pose.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::app {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Keys in the order written: status first, details after.
using json = nlohmann::ordered_json;

geom::EulerOrder DialectEulerOrder() { return program::EulerOrderOf(program::Dialect::Default()); }

bool AllFinite(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

std::string JoinNumbers(const std::vector<double>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + std::to_string(v);
  return out;
}

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
json PoseJson(const Eigen::Isometry3d& pose, double length_scale) {
  const Eigen::Vector3d t = pose.translation() * length_scale;
  const Eigen::Vector3d abc =
      geom::EulerFromRotation(DialectEulerOrder(), pose.linear()) * kRadToDeg;
  return {{"xyz_mm", {t.x(), t.y(), t.z()}}, {"abc_deg", {abc.x(), abc.y(), abc.z()}}};
}

// Per joint: name, value, limits (CLI units) and whether the value is within them.
json LimitsJson(const sim::RobotModel& robot, const sim::JointVector& q, double tolerance,
                bool& all_within) {
  json out = json::array();
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

json JointNamesJson() {
  json names = json::array();
  for (auto n : sim::kJointNames) names.push_back(std::string(n));
  return names;
}

struct FkArgs {
  std::string scene;
  std::vector<double> joints;
};

int RunFk(const FkArgs& a) {
  if (a.joints.size() != static_cast<std::size_t>(sim::kNumJoints) || !AllFinite(a.joints)) {
    PrintError("kin-bad-joints",
               "--joints needs 8 finite numbers (rail_x mm, a1..a6 deg, "
               "rotator deg); got: " +
                   JoinNumbers(a.joints));
    return kExitBadInput;
  }
  auto ls = LoadSceneAndRobot(a.scene);
  if (!ls) return kExitBadInput;
  const sim::RobotModel& robot = *ls->robot;
  const sim::CellSetup cell = sim::MakeCellSetup(robot, *ls->scene);
  const sim::JointVector q = JointsFromCli(a.joints);

  bool within = true;
  json out;
  out["scene"] = ls->scene->name;
  out["head"] = ls->scene->head.name;
  out["joint_names"] = JointNamesJson();
  out["joints"] = JointsForCli(q);
  out["flange_world"] = PoseJson(sim::FlangePose(robot, q), 1000.0);
  out["tool_in_part"] = PoseJson(sim::ToolPoseInPart(cell, q), 1.0);
  out["euler_order"] = program::Dialect::Default().euler_order;
  out["configuration"] = sim::ToString(sim::ArmConfigurationOf(robot, q));
  out["joint_limits"] = LimitsJson(robot, q, cell.ik.limit_tolerance, within);
  out["within_limits"] = within;
  std::cout << out.dump(2) << '\n';
  return kExitOk;
}

struct IkArgs {
  std::string scene;
  std::vector<double> pose;
  std::optional<double> rail_mm;
  double rotator_deg = 0.0;
};

int RunIk(const IkArgs& a) {
  if (a.pose.size() != 6 || !AllFinite(a.pose)) {
    PrintError("kin-bad-pose",
               "--pose needs 6 finite numbers (X Y Z mm, A B C deg); got: " + JoinNumbers(a.pose));
    return kExitBadInput;
  }
  if ((a.rail_mm && !std::isfinite(*a.rail_mm)) || !std::isfinite(a.rotator_deg)) {
    PrintError("kin-bad-pose", "--rail and --rotator must be finite numbers");
    return kExitBadInput;
  }
  auto ls = LoadSceneAndRobot(a.scene);
  if (!ls) return kExitBadInput;
  const sim::RobotModel& robot = *ls->robot;
  const sim::CellSetup cell = sim::MakeCellSetup(robot, *ls->scene);

  // The pose as a programme line would command it: X Y Z A B C.
  program::MachineState commanded;
  for (program::Axis axis : {program::Axis::kX, program::Axis::kY, program::Axis::kZ,
                             program::Axis::kA, program::Axis::kB, program::Axis::kC}) {
    commanded.axes[static_cast<std::size_t>(axis)] = a.pose[static_cast<std::size_t>(axis)];
  }
  const Eigen::Isometry3d target = *program::ToolPoseOf(commanded, DialectEulerOrder());
  const sim::ToolPoseSolution sol =
      sim::SolveToolPose(cell, target, a.rotator_deg * kDeg, a.rail_mm, nullptr);
  const sim::IkResult& ik = sol.ik;

  json out;
  out["scene"] = ls->scene->name;
  out["head"] = ls->scene->head.name;
  out["status"] = std::string(sim::ToString(ik.status));
  out["reason"] = ik.reason;
  out["target_in_part"] = {{"xyz_mm", {a.pose[0], a.pose[1], a.pose[2]}},
                           {"abc_deg", {a.pose[3], a.pose[4], a.pose[5]}}};
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
  std::cout << out.dump(2) << '\n';
  return ik.ok() ? kExitOk : kExitFindings;
}

}  // namespace

void AddKinematicsCommands(CLI::App& app, int& exit_code) {
  {
    auto args = std::make_shared<FkArgs>();
    CLI::App* cmd = app.add_subcommand(
        "fk", "Forward kinematics: flange and tool-point pose for joint values (JSON)");
    cmd->add_option("--scene", args->scene, "Scene YAML file (cell, head, part mount)")->required();
    cmd->add_option("--joints", args->joints,
                    "rail_x (mm), a1..a6 (deg), rotator (deg), in model order")
        ->required()
        ->expected(sim::kNumJoints);
    AddScenePathFlag(*cmd);
    cmd->callback([args, &exit_code] { exit_code = RunFk(*args); });
  }
  {
    auto args = std::make_shared<IkArgs>();
    CLI::App* cmd = app.add_subcommand(
        "ik",
        "Inverse kinematics: rail and joints for a tool-point pose in the part frame (JSON); "
        "exit 1 when the cell cannot reach it");
    cmd->add_option("--scene", args->scene, "Scene YAML file (cell, head, part mount)")->required();
    cmd->add_option("--pose", args->pose, "X Y Z (mm) A B C (deg), part frame, dialect angles")
        ->required()
        ->expected(6);
    AddLengthOption(
        cmd, "--rail", [args](double mm) { args->rail_mm = mm; }, LengthUnit::kMillimetre,
        LengthRange::kAny, "Rail position", "the rail policy");
    cmd->add_option("--rotator", args->rotator_deg, "Rotator angle in deg (default 0)");
    AddScenePathFlag(*cmd);
    cmd->callback([args, &exit_code] { exit_code = RunIk(*args); });
  }
}

}  // namespace stitchsim::app
