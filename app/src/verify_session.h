#pragma once
// What a verify run builds from the scene before it executes a line (verify; report merge
// builds the same to finish the merged rules exactly as one run would).

#include <memory>
#include <optional>
#include <string>

#include "cli_common.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/collision.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::app {

struct SessionOptions {
  bool no_collision = false;
  bool allow_mismatch = false;
  bool dynamics = false;
};

/// The cell as MuJoCo runs it: one working state for the executor's kinematics (and the
/// collision world's frames), one for the timing sink's inverse dynamics, and with
/// --dynamics two for the physics and the poses of its reference and actual joints.
struct MujocoCells {
  std::unique_ptr<sim::MujocoCell> kinematics, timing, physics, physics_poses;
};

struct VerifySession {
  LoadedScene ls;
  program::Dialect dialect;
  double stitch_length_mm = 0.0;
  std::optional<long> declared_stitches;
  sim::CellSetup cell;
  std::unique_ptr<process::ProcessModel> model;
  std::unique_ptr<sim::CollisionWorld> collision;  ///< null with --no-collision
  MujocoCells mj;
  trace::CellDescription description;
  sim::ExecuteOptions execute;
  sim::TimingOptions timing;
  verify::RuleContext Rules() const;
};

/// Builds the session (diagnostics printed; nullptr on error).
std::unique_ptr<VerifySession> MakeSession(LoadedScene ls, const program::Dialect& dialect,
                                           double stitch_length_mm,
                                           std::optional<long> declared_stitches,
                                           const SessionOptions& options);

}  // namespace stitchsim::app
