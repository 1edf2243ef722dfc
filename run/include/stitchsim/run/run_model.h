#pragma once
// One verify run's model and data, split as MuJoCo splits mjModel and mjData: the RunModel is
// made once from the scene and the programme's header and is read-only afterwards (shared by
// every chunk's thread); a RunData is one run's working states, made from it with Share().

#include <memory>
#include <optional>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/collision.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::run {

/// How the cell is run (verify's switches that change the model).
struct RunOptions {
  bool no_collision = false;    ///< no collision world: the collision.* rules are skipped
  bool allow_mismatch = false;  ///< run a programme that mounts another head anyway
  bool dynamics = false;        ///< step MuJoCo's physics (the servos track the timed path)
};

/// What a run is made from; immutable once made, shareable across threads.
struct RunModel {
  LoadedScene loaded;                     ///< owned: the scene and its cell's robot model
  program::Dialect dialect;               ///< the programme's dialect
  double stitch_length_mm = 0.0;          ///< the programme's, else the scene's nominal, mm
  std::optional<long> declared_stitches;  ///< the header's `stitches=N`, if declared
  sim::CellSetup cell;                    ///< IK and rail set-up from the robot and the scene
  std::unique_ptr<process::ProcessModel> process;  ///< owned; the needle cycle at this length
  /// Owned prototype, only Share()d (each RunData queries its own); null with no_collision.
  std::unique_ptr<sim::CollisionWorld> collision;
  std::unique_ptr<sim::MujocoCell> mujoco;  ///< owned prototype, only Share()d; never null
  trace::CellDescription description;       ///< the cell as the rules and the trace see it
  /// The executor's options; collision and mujoco left null (a RunData points them at its own).
  sim::ExecuteOptions execute;
  sim::TimingOptions timing;  ///< the dialect's time law, the executor's settle time
  bool dynamics = false;      ///< RunOptions::dynamics (RunData makes the physics states)

  /// The rules' view of this model (pointers into it: valid while the model lives).
  verify::RuleContext Rules() const;
};

/// One run's working states (one thread's); made by MakeRunData, pointing into the model.
struct RunData {
  /// Owned MuJoCo working states: the executor's kinematics (and the collision world's
  /// frames), the timing sink's inverse dynamics; with dynamics the physics and the poses of
  /// its reference and actual joints (null otherwise).
  std::unique_ptr<sim::MujocoCell> kinematics, timing, physics, physics_poses;
  std::unique_ptr<sim::CollisionWorld> collision;  ///< owned; null with no_collision
  sim::ExecuteOptions execute;  ///< the model's, pointed at this data's kinematics and world
};

/// The time law's settings a run of `dialect` uses (its trajectory section) and the executor's
/// settle time: what verify times with, and `sequence --cost timed` too.
sim::TimingOptions TimingOptionsFor(const program::Dialect& dialect,
                                    const sim::ExecuteOptions& execute);

/// Builds the model from a loaded scene (moved in) and the programme's dialect, stitch length
/// and declared count; errors (collision world, MuJoCo model, no servos for dynamics) into
/// `sink`, nullptr then.
std::unique_ptr<RunModel> MakeRunModel(LoadedScene loaded, const program::Dialect& dialect,
                                       double stitch_length_mm,
                                       std::optional<long> declared_stitches,
                                       const RunOptions& options, DiagnosticSink& sink);

/// A fresh run's working states on `model` (which must outlive them).
RunData MakeRunData(const RunModel& model);

}  // namespace stitchsim::run
