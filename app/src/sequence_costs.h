#pragma once
// The three cost measures of `stitchsim sequence` (docs/sequence.md, "Costs"): every course's
// lay-up start and end, laid forwards and backwards, as machine axes (the cell's IK and rail
// policy), and the tool point. The planner's solvers see only points and weights.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/planner/sequence_solver.h"
#include "stitchsim/program/afp_program.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/cell.h"

namespace stitchsim::app {

enum class Measure { kAxes, kTime, kTool };
inline constexpr Measure kMeasures[] = {Measure::kAxes, Measure::kTime, Measure::kTool};
const char* MeasureName(Measure m);  ///< "axes", "time", "tool"
const char* MeasureUnit(Measure m);  ///< "", "s", "mm"

/// One course end (or home) in every measure: the joints (rail mm, revolute deg) and the tool
/// point (mm).
struct EndPoint {
  std::vector<double> axes;  ///< kNumJoints values: rail mm, a1..a6 and rotator deg
  Eigen::Vector3d tool = Eigen::Vector3d::Zero();
  bool ok = false;     ///< the cell reaches it
  std::string reason;  ///< when not ok: the IK's words
};

/// The four ends of every course (row 4 i + k as in planner::SequenceProblem), and home.
struct CourseEnds {
  std::vector<EndPoint> ends;  ///< 4 per course
  EndPoint home;
  std::vector<bool> reversible;  ///< both backward ends reachable
};

/// IK at every course's lay-up ends (forwards and backwards) and at `home` (part frame, mm).
/// The rail follows the cell's policy (or the lay-up's E), the rotator the lay-up's W.
CourseEnds SolveCourseEnds(const sim::CellSetup& cell, const program::AfpProgram& program,
                           const Eigen::Isometry3d& home);

/// Weights and norm of a measure: axes by the head's `sequence.axis_weights` (per mm, per
/// degree; index by joint), time by 1 / each joint's top speed (norm max), tool Euclidean.
struct MeasureSpec {
  planner::CostNorm norm = planner::CostNorm::kL1;
  std::vector<double> weights;
};
MeasureSpec SpecOf(Measure m, const sim::RobotModel& robot,
                   const std::vector<double>& axis_weights);

/// The problem of one precedence set in measure `m`: the set's courses (indices into
/// program.courses) in the given order, from `start` and, when `finish`, back to it. A course
/// that cannot be laid backwards has its backward ends pushed far away (never chosen).
planner::SequenceProblem SetProblem(const CourseEnds& ends, const std::vector<int>& courses,
                                    const MeasureSpec& spec, Measure m, bool bidirectional,
                                    const EndPoint& start, const EndPoint* finish);

/// The point of an end in measure m.
std::vector<double> PointOf(const EndPoint& e, Measure m);

}  // namespace stitchsim::app
