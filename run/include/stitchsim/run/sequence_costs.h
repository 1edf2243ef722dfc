#pragma once
// The four cost measures of `stitchsim sequence` (docs/sequence.md, "Costs"): every course's
// lay-up start and end, laid forwards and backwards, as machine axes (the cell's IK and rail
// policy), and the tool point. The planner's solvers see points and weights, or (timed,
// sequence_timed.h) a table of every move's time through the controller's time law.
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "stitchsim/planner/sequence/solver.h"
#include "stitchsim/program/afp_program.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/trace/joints.h"

namespace stitchsim::run {

enum class Measure { kAxes, kTime, kTool, kTimed };
inline constexpr Measure kMeasures[] = {Measure::kAxes, Measure::kTime, Measure::kTool,
                                        Measure::kTimed};
const char* MeasureName(Measure m);  ///< "axes", "time", "tool", "timed"
const char* MeasureUnit(Measure m);  ///< "", "s", "mm", "s"

/// One value per measure, kMeasures order: axes (weighted, unitless), time s, tool mm, timed s.
using Costs = std::array<double, 4>;

struct TimedModel;  // sequence_timed.h

/// Joints as the axes measure's point: rail mm, a1..a6 and rotator degrees (model order). The
/// one conversion of joints to axes, for course ends and lay-up stations alike.
std::vector<double> AxesOf(const trace::JointVector& q);

/// One course end (or home) in every measure: the joints (rail mm, revolute deg) and the tool
/// point (mm).
struct EndPoint {
  std::vector<double> axes;                           ///< kNumJoints values: AxesOf the IK joints
  trace::JointVector q = trace::JointVector::Zero();  ///< the IK joints, model order, m / rad
  Eigen::Vector3d tool = Eigen::Vector3d::Zero();     ///< part frame, mm: the pose asked for
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< part frame, mm: that pose
  int row = -1;        ///< its row in CourseEnds::ends (4 course + k); -1: home or a raised end
  bool ok = false;     ///< the cell reaches it
  std::string reason;  ///< when not ok: the IK's words
};

/// The four ends of every course (row 4 i + k as in planner::SequenceProblem), and home.
struct CourseEnds {
  std::vector<EndPoint> ends;  ///< 4 per course: start, end forwards; start, end backwards
  /// 4 per course, as `ends`: each end `retract_mm` up its tool z (planner::RaisedPose), IK'd
  /// from the end's joints: where the retract ends and the approach begins (timed measure).
  /// Not checked for reach: `verify` judges the programme's moves.
  std::vector<EndPoint> raised;
  std::vector<double> approach_feed_mm_per_min;  ///< per course: its approach's (lay-up's) feed
  EndPoint home;                                 ///< the run's home pose
  std::vector<bool> reversible;                  ///< per course: both backward ends reachable
};

/// IK at every course's lay-up ends (forwards and backwards), at each raised `retract_mm`
/// (the head's sequence.retract_mm) and at `home` (part frame, mm). The rail follows the
/// cell's policy (or the lay-up's E), the rotator the lay-up's W.
CourseEnds SolveCourseEnds(const sim::CellSetup& cell, const program::AfpProgram& program,
                           const Eigen::Isometry3d& home, double retract_mm);

/// Weights and norm of a measure: axes by the head's `sequence.axis_weights` (per mm, per
/// degree; index by joint), time by 1 / each joint's top speed (norm max), tool Euclidean;
/// timed by the time law's model (no norm: set `timed`).
struct MeasureSpec {
  planner::CostNorm norm = planner::CostNorm::kL1;
  std::vector<double> weights;              ///< one per coordinate of the measure's points
  std::shared_ptr<const TimedModel> timed;  ///< kTimed: the cell's and controller's settings
};
/// kTimed: an empty spec (the caller sets `timed`, TimedModelOf in sequence_timed.h).
MeasureSpec SpecOf(Measure m, const sim::RobotModel& robot,
                   const std::vector<double>& axis_weights);

/// The problem of one precedence set in measure `m`: the set's courses (indices into
/// program.courses) in the given order, from `start` (home or an entry of ends.ends) and,
/// when `finish`, back to it. A course that cannot be laid backwards has its backward ends
/// pushed far away (never chosen). kTimed: the problem is the table of every move
/// (TimedMoveTable), computed here.
planner::SequenceProblem SetProblem(const CourseEnds& ends, const std::vector<int>& courses,
                                    const MeasureSpec& spec, Measure m, bool bidirectional,
                                    const EndPoint& start, const EndPoint* finish);

/// The row of CourseEnds::ends (and of planner::SequenceProblem::points) where visit v's
/// lay-up starts; it ends on the next row.
inline std::size_t StartRowOf(const program::CourseVisit& v) {
  return 4 * static_cast<std::size_t>(v.course) + (v.reversed ? 2 : 0);
}
/// Where visit v's lay-up starts and where it ends.
inline const EndPoint& StartOf(const CourseEnds& ends, const program::CourseVisit& v) {
  return ends.ends[StartRowOf(v)];
}
inline const EndPoint& EndOf(const CourseEnds& ends, const program::CourseVisit& v) {
  return ends.ends[StartRowOf(v) + 1];
}

/// The point of an end in measure m.
std::vector<double> PointOf(const EndPoint& e, Measure m);

/// The cost of each move of `visits` in one measure: entry i is the move into visit i (from
/// home or the previous visit's end); one more entry, the move home, when `finish`.
std::vector<double> MoveCosts(const CourseEnds& ends,
                              const std::vector<program::CourseVisit>& visits,
                              const MeasureSpec& spec, Measure m, bool finish);

/// Lay-up motion in every measure (the same in any order): the axes' weighted travel between
/// the stations' IK solutions (`axes_spec`, from home), the time at the programmed feeds, the
/// tool path, and each course's lay-up through the time law (`timed`, TimedLayupSeconds).
Costs LayupCosts(const sim::CellSetup& cell, const program::AfpProgram& program,
                 const MeasureSpec& axes_spec, const TimedModel& timed);

}  // namespace stitchsim::run
