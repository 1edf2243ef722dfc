// `stitchsim fk` and `stitchsim ik`: the cell's kinematics as JSON, for people debugging a
// cell. Joints in model order [rail_x mm, a1..a6 deg, rotator deg]; tool poses in the part
// frame in the dialect's convention (X Y Z mm, A B C deg, R = Rz(C) Ry(B) Rx(A)).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "cli_options.h"
#include "commands.h"
#include "stitchsim/run/kinematics_report.h"

namespace stitchsim::app {
namespace {

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

struct FkArgs {
  std::string scene;
  std::vector<double> joints;
};

int RunFk(const FkArgs& a) {
  if (a.joints.size() != static_cast<std::size_t>(run::kCliJointCount) || !AllFinite(a.joints)) {
    PrintError("kin-bad-joints",
               "--joints needs 8 finite numbers (rail_x mm, a1..a6 deg, "
               "rotator deg); got: " +
                   JoinNumbers(a.joints));
    return kExitBadInput;
  }
  auto ls = LoadSceneAndRobot(a.scene);
  if (!ls) return kExitBadInput;
  const run::KinematicsReport out = run::ForwardKinematics(*ls, a.joints);
  std::cout << out.json.dump(2) << '\n';
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
  const run::KinematicsReport out = run::InverseKinematics(*ls, a.pose, a.rail_mm, a.rotator_deg);
  std::cout << out.json.dump(2) << '\n';
  return out.reached ? kExitOk : kExitFindings;
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
        ->expected(run::kCliJointCount);
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
