#pragma once
// Executes a programme on the cell: line by line, position interpolated linearly and
// orientation by slerp, the drive axis U advancing linearly; the stitch-cycle phase and the
// needles' in/out derived from U; rail + arm solved by IK. Streams a Trace.

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/collision.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/trace.h"
#include "stitchsim/trace/trace.h"

namespace stitchsim::sim {

/// Sampling bounds. Between samples the tool moves at most this far, so no rule can miss an
/// event: needle entry/exit are exact events; joint checks run on the coarse grid, the
/// needle rules on the fine in-preform grid.
struct ExecuteOptions {
  double max_step_mm = 20.0;                ///< IK grid: translation per step
  double max_step_rad = 0.034906585;        ///< IK grid: rotation per step (2 deg)
  double in_preform_step_mm = 0.5;          ///< needles in: translation per sample
  double in_preform_step_rad = 0.0017453;   ///< needles in: rotation per sample (0.1 deg)
  double rapid_speed_mm_s = 500.0;          ///< G0 translation speed
  double rotation_speed_rad_s = 0.5235988;  ///< pure-rotation speed (head spec)
  double stitch_rate_per_min = 300.0;       ///< drive revolutions per minute
  double settle_time_s = 0.15;              ///< dwell after a pure rotation line
  /// Look ahead over the whole programme (seekable input only) to start a4 and a6 on the
  /// 2 pi branch that keeps their full travel within limits.
  bool choose_start_branch = true;
  /// When set, the world is queried at every sample with usable joints and its answer written
  /// into the sample (TraceSample::collision: contacts, clearance, query errors), and each
  /// line is subdivided (extra IK samples, event kNone, with joints) until the bound on any
  /// body's motion between consecutive joint samples, MaxPointTravel, is no more than the
  /// clearance measured at the earlier one: no contact can slip between samples.
  /// Null (the default): no collision queries, sampling unchanged.
  CollisionWorld* collision = nullptr;
  /// False: no subdivision, the world is queried at the plain grid's samples only (tests show
  /// with it what the subdivision catches).
  bool collision_subdivide = true;
  /// Smallest step bound (m): where the clearance is below it, steps of this much motion are
  /// taken anyway (so the walk ends); a feature thinner than this could slip between samples
  /// only where the head is already closer than this to something.
  double collision_min_clearance_m = 0.0005;
  /// Cap on the extra samples per line (keeps a pathological line finite).
  int collision_max_extra_samples = 4000;
  /// The head mounted on the cell (the scene's). A tool change (`T<n> M6`) to a tool the
  /// dialect maps to another head is `exec-head-mismatch`, unless `allow_head_mismatch`.
  /// Empty: not checked.
  std::string mounted_head;
  bool allow_head_mismatch = false;
  /// A programme that ends without the programme end code (M30) was cut short:
  /// `exec-missing-program-end` at the last line read.
  bool require_program_end = true;
  /// The cell as MuJoCo runs it (kinematic mode): at every sample with solved joints the
  /// executor sets MuJoCo's qpos to them and takes the tool pose the rules read from MuJoCo's
  /// kinematics (the collision world takes its link frames from the same state, see
  /// CollisionWorld::UseKinematics). Null: the URDF forward kinematics alone (tests).
  MujocoCell* mujoco = nullptr;
  /// Solve the joints at every sample, the fine in-preform grid and the needle events too
  /// (the dynamic mode needs a joint reference there); false: line ends and the coarse grid.
  bool solve_every_sample = false;
};

/// The head's speeds and the mounted head from `scene`; no collision world.
ExecuteOptions ExecuteOptionsFor(const scene::Scene& scene);

struct ExecutionSummary {
  long lines = 0;     ///< programme lines read
  long moves = 0;     ///< motion lines executed
  long stitches = 0;  ///< stitch cycles started (needle entries)
  double time_s = 0.0;
  program::ProgramHeader header;
  bool ok = false;  ///< no input errors (rule findings are the verifier's business)
};

/// A programme opened for execution and read once, front to back (a pipe works): its header
/// can be read before the run (to check it and to size the process model), and the run goes
/// on from there. Only the start-branch look-ahead reads a seekable input a second time.
/// `in`, `dialect` and `diagnostics` must outlive it.
class ProgramInput {
 public:
  ProgramInput(std::istream& in, const program::Dialect& dialect, std::string file_name,
               DiagnosticSink& diagnostics);
  /// The complete STITCHSIM header (reads up to the first block with words).
  const program::ProgramHeader& Header() { return reader_.ReadHeader(); }
  const std::string& FileName() const { return file_name_; }

 private:
  friend ExecutionSummary ExecuteProgram(const CellSetup&, const process::ProcessModel&,
                                         ProgramInput&, const ExecuteOptions&, DiagnosticSink&,
                                         TraceSink&);
  friend struct ScanResult ScanProgram(const CellSetup&, const process::ProcessModel&,
                                       ProgramInput&, const ExecuteOptions&,
                                       const struct ScanOptions&, bool, DiagnosticSink&,
                                       const std::function<void(const struct Chunk&)>&,
                                       const std::function<void(std::uint64_t)>&);
  std::istream& in_;
  std::streampos origin_;  ///< where the programme starts; -1 when `in_` cannot seek
  const program::Dialect& dialect_;
  std::string file_name_;
  program::ProgramReader reader_;
};

/// Runs the programme through the parser, the modal state and the kinematics, sending every
/// line and sample to `sink`. Input errors (malformed programme, incomplete pose, NaN, a head
/// the cell does not carry, no programme end) are reported to `diagnostics`, which must be
/// the sink `input` reports to; execution stops at the first error.
ExecutionSummary ExecuteProgram(const CellSetup& cell, const process::ProcessModel& process,
                                ProgramInput& input, const ExecuteOptions& options,
                                DiagnosticSink& diagnostics, TraceSink& sink);

/// The same for a whole stream (tests, in-memory text).
ExecutionSummary ExecuteProgram(const CellSetup& cell, const process::ProcessModel& process,
                                const program::Dialect& dialect, std::istream& in,
                                const std::string& file_name, const ExecuteOptions& options,
                                DiagnosticSink& diagnostics, TraceSink& sink);

}  // namespace stitchsim::sim
