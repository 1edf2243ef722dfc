#pragma once
// The `timed` measure of `stitchsim sequence` (docs/sequence.md, "Costs"): an off-part move's
// time through the controller's time law (sim/time_law.h, docs/timing.md) with the executor's
// speeds and the cell's axis limits, the settings `verify` times with. The move is the one
// `sequence` writes (planner/sequence/offpart.h): a rapid retract up the tool z, a rapid
// transfer to above the next start, the approach down onto it at the lay-up's feed; planned
// from rest to rest, each line straight in joint space between the IK of its end points. No
// norm of two points gives this, so a set's problem carries the whole table of its moves.
#include <memory>
#include <vector>

#include "stitchsim/planner/sequence/solver.h"
#include "stitchsim/program/afp_program.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/sequence_costs.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/robot_model.h"
#include "stitchsim/sim/timing.h"

namespace stitchsim::run {

/// What the timed measure needs of the cell, the head and the controller. Owner: the run.
struct TimedModel {
  sim::AxisLimits limits;     ///< the cell's joint speed and acceleration limits (m, rad; URDF)
  sim::TimingOptions timing;  ///< ramp time, blending, look-ahead (the dialect's), settle time
  double rapid_speed_mm_s = 500.0;  ///< G0 tool-point speed, mm/s (the head's, as the executor)
  double rotation_speed_rad_s = 0.5235988;  ///< the executor's tool rotation speed, rad/s
  int threads = 1;  ///< threads computing a set's table (>= 1); the table does not depend on it
};

/// verify's settings: the robot's limits (sim::AxisLimitsOf), the scene's head as the executor
/// reads it (sim::ExecuteOptionsFor), the dialect's trajectory (TimingOptionsFor).
TimedModel TimedModelOf(const sim::RobotModel& robot, const scene::Scene& scene,
                        const program::Dialect& dialect);

/// A visit's cost in the table when it may not be made: a course the cell cannot lay
/// backwards, or any backward visit of a forward-only problem (s).
inline constexpr double kUnreachableSeconds = 1e7;

/// Seconds of the off-part move from row `from_row` of ends.ends (a lay-up end: retract to
/// ends.raised[from_row] first; -1: from home, no retract) to row `to_row` (a lay-up start:
/// transfer to ends.raised[to_row], then the approach at its course's feed; -1: to home, no
/// approach). Rapids and the approach's feed as OffPartPath writes them, planned together from
/// rest to rest. Leaves out the transfer's via points round the part (the straight line) and
/// splits no half turn into two lines (docs/sequence.md, "Costs").
double TimedMoveSeconds(const TimedModel& m, const CourseEnds& ends, int from_row, int to_row);

/// The whole table of one set's moves (the courses' rows of `ends`, node 2 i + reversed as in
/// planner::MoveTable): every move, from_start (from row `start_row`, -1 home) and to_finish
/// (to home when `finish`, else zeros). Backward visits of a forward-only set or of a course
/// that cannot be laid backwards cost kUnreachableSeconds. Computed on m.threads threads.
std::shared_ptr<const planner::MoveTable> TimedMoveTable(const TimedModel& m,
                                                         const CourseEnds& ends,
                                                         const std::vector<int>& courses,
                                                         bool bidirectional, int start_row,
                                                         bool finish);

/// A course's lay-up through the time law from rest to rest (s): one line per step between
/// its stations at the step's feed, joints `q` (one per station, m and rad, the IK's).
double TimedLayupSeconds(const TimedModel& m, const program::AfpCourse& course,
                         const std::vector<trace::JointVector>& q);

}  // namespace stitchsim::run
