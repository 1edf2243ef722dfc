// Course ends as machine axes and tool points, and the costs of moves and lay-ups
// (sequence_costs.h).
#include "stitchsim/run/sequence_costs.h"

#include "stitchsim/common/units.h"
#include "stitchsim/planner/sequence/offpart.h"
#include "stitchsim/run/sequence_timed.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::run {
namespace {

// A backward end the cell cannot reach sits this far away in every coordinate.
constexpr double kUnreachableCoord = 1e7;

// The cell's IK at a lay-up pose: the rail as the lay-up's E says (or the cell's policy), the
// rotator at its W (0 without an entry).
sim::ToolPoseSolution SolveLayupPose(const sim::CellSetup& cell, const Eigen::Isometry3d& pose,
                                     const program::LayupEntry* entry,
                                     const trace::JointVector* previous) {
  const double rotator_rad =
      (entry != nullptr && entry->rotator_deg) ? *entry->rotator_deg / kRadToDeg : 0.0;
  const std::optional<double> rail = entry != nullptr ? entry->rail_mm : std::nullopt;
  return sim::SolveToolPose(cell, pose, rotator_rad, rail, previous);
}

EndPoint SolveCourseEnd(const sim::CellSetup& cell, const Eigen::Isometry3d& pose,
                        const program::LayupEntry* entry, const trace::JointVector* previous,
                        trace::JointVector* joints = nullptr) {
  EndPoint e;
  const sim::ToolPoseSolution s = SolveLayupPose(cell, pose, entry, previous);
  e.tool = pose.translation();
  e.pose = pose;
  e.q = s.ik.joints;
  e.ok = trace::IkUsable(s.ik.status);
  if (!e.ok)
    e.reason = s.ik.reason.empty() ? std::string(trace::ToString(s.ik.status)) : s.ik.reason;
  if (joints != nullptr) *joints = s.ik.joints;
  e.axes = AxesOf(s.ik.joints);
  return e;
}

// A problem with no points: what MoveCost needs of a measure.
planner::SequenceProblem MeasureOnlyProblem(const MeasureSpec& spec) {
  planner::SequenceProblem p;
  p.dim = static_cast<int>(spec.weights.size());
  p.weights = spec.weights;
  p.norm = spec.norm;
  return p;
}

}  // namespace

const char* MeasureName(Measure m) {
  switch (m) {
    case Measure::kAxes:
      return "axes";
    case Measure::kTime:
      return "time";
    case Measure::kTool:
      return "tool";
    case Measure::kTimed:
      return "timed";
  }
  return "?";
}

const char* MeasureUnit(Measure m) {
  switch (m) {
    case Measure::kAxes:
      return "";
    case Measure::kTime:
    case Measure::kTimed:
      return "s";
    case Measure::kTool:
      return "mm";
  }
  return "";
}

std::vector<double> AxesOf(const trace::JointVector& q) {
  std::vector<double> axes(trace::kNumJoints);
  for (int j = 0; j < trace::kNumJoints; ++j)
    axes[static_cast<std::size_t>(j)] = j == trace::kRailX ? q[j] * 1000.0 : q[j] * kRadToDeg;
  return axes;
}

CourseEnds SolveCourseEnds(const sim::CellSetup& cell, const program::AfpProgram& program,
                           const Eigen::Isometry3d& home, double retract_mm) {
  CourseEnds out;
  const trace::JointVector home_q = sim::HomeJoints(*cell.robot, 0.0);
  out.home = SolveCourseEnd(cell, home, nullptr, &home_q);
  out.ends.reserve(program.courses.size() * 4);
  out.reversible.reserve(program.courses.size());
  for (const auto& c : program.courses) {
    for (const bool rev : {false, true}) {
      const Eigen::Isometry3d a = program::LayupStartPose(c, rev);
      const Eigen::Isometry3d b = program::LayupEndPose(c, rev);
      trace::JointVector qa;
      EndPoint ea = SolveCourseEnd(cell, a, &c.entry, &home_q, &qa);
      EndPoint eb = SolveCourseEnd(cell, b, &c.entry, &qa);
      trace::JointVector qb = eb.q;
      out.raised.push_back(SolveCourseEnd(cell, planner::RaisedPose(a, retract_mm), &c.entry, &qa));
      out.raised.push_back(SolveCourseEnd(cell, planner::RaisedPose(b, retract_mm), &c.entry, &qb));
      out.ends.push_back(std::move(ea));
      out.ends.push_back(std::move(eb));
    }
    const std::size_t k = out.ends.size() - 4;
    for (std::size_t r = k; r < k + 4; ++r) out.ends[r].row = static_cast<int>(r);
    out.approach_feed_mm_per_min.push_back(c.entry.feed_mm_per_min.value_or(
        c.stations.empty() ? 0.0 : c.stations.front().feed_mm_per_min));
    out.reversible.push_back(out.ends[k + 2].ok && out.ends[k + 3].ok);
  }
  return out;
}

MeasureSpec SpecOf(Measure m, const sim::RobotModel& robot,
                   const std::vector<double>& axis_weights) {
  MeasureSpec s;
  switch (m) {
    case Measure::kAxes:
      s.norm = planner::CostNorm::kL1;
      s.weights = axis_weights;
      break;
    case Measure::kTime:
      s.norm = planner::CostNorm::kMax;
      for (int j = 0; j < trace::kNumJoints; ++j) {
        const auto& info = robot.joint(j);
        // Speeds in m/s or rad/s; points in mm and degrees.
        const double per_unit = j == trace::kRailX ? 1000.0 : kRadToDeg;
        s.weights.push_back(info.max_velocity > 0.0 ? 1.0 / (info.max_velocity * per_unit) : 0.0);
      }
      break;
    case Measure::kTool:
      s.norm = planner::CostNorm::kL2;
      s.weights = {1.0, 1.0, 1.0};
      break;
    case Measure::kTimed:
      break;
  }
  return s;
}

std::vector<double> PointOf(const EndPoint& e, Measure m) {
  if (m == Measure::kTool) return {e.tool.x(), e.tool.y(), e.tool.z()};
  return e.axes;
}

planner::SequenceProblem SetProblem(const CourseEnds& ends, const std::vector<int>& courses,
                                    const MeasureSpec& spec, Measure m, bool bidirectional,
                                    const EndPoint& start, const EndPoint* finish) {
  planner::SequenceProblem p = MeasureOnlyProblem(spec);
  p.courses = static_cast<int>(courses.size());
  p.bidirectional = bidirectional;
  if (m == Measure::kTimed) {
    p.dim = 0;
    p.table =
        TimedMoveTable(*spec.timed, ends, courses, bidirectional, start.row, finish != nullptr);
    if (finish != nullptr) p.finish = std::vector<double>{};
    return p;
  }
  p.points.reserve(courses.size() * 4 * static_cast<std::size_t>(p.dim));
  for (const int c : courses) {
    const bool rev_ok = ends.reversible[static_cast<std::size_t>(c)];
    for (int k = 0; k < 4; ++k) {
      const std::vector<double> pt = PointOf(ends.ends[static_cast<std::size_t>(4 * c + k)], m);
      for (const double v : pt) p.points.push_back(k >= 2 && !rev_ok ? kUnreachableCoord : v);
    }
  }
  p.start = PointOf(start, m);
  if (finish != nullptr) p.finish = PointOf(*finish, m);
  return p;
}

std::vector<double> MoveCosts(const CourseEnds& ends,
                              const std::vector<program::CourseVisit>& visits,
                              const MeasureSpec& spec, Measure m, bool finish) {
  std::vector<double> out;
  if (m == Measure::kTimed) {
    int from = -1;  // home
    for (const auto& v : visits) {
      const int row = static_cast<int>(StartRowOf(v));
      out.push_back(TimedMoveSeconds(*spec.timed, ends, from, row));
      from = row + 1;
    }
    if (finish) out.push_back(TimedMoveSeconds(*spec.timed, ends, from, -1));
    return out;
  }
  const planner::SequenceProblem p = MeasureOnlyProblem(spec);
  std::vector<double> here = PointOf(ends.home, m);
  for (const auto& v : visits) {
    const std::vector<double> start = PointOf(StartOf(ends, v), m);
    out.push_back(planner::MoveCost(p, here.data(), start.data()));
    here = PointOf(EndOf(ends, v), m);
  }
  if (finish) {
    const std::vector<double> home = PointOf(ends.home, m);
    out.push_back(planner::MoveCost(p, here.data(), home.data()));
  }
  return out;
}

Costs LayupCosts(const sim::CellSetup& cell, const program::AfpProgram& program,
                 const MeasureSpec& axes_spec, const TimedModel& timed) {
  Costs c{};
  const planner::SequenceProblem p = MeasureOnlyProblem(axes_spec);
  trace::JointVector q = sim::HomeJoints(*cell.robot, 0.0);
  for (const auto& course : program.courses) {
    c[2] += course.layup_length_mm;
    std::vector<double> prev;
    std::vector<trace::JointVector> joints;
    for (std::size_t i = 0; i < course.stations.size(); ++i) {
      const auto& st = course.stations[i];
      if (i + 1 < course.stations.size() && st.feed_mm_per_min > 0.0) {
        const double len =
            (course.stations[i + 1].pose.translation() - st.pose.translation()).norm();
        c[1] += len / st.feed_mm_per_min * 60.0;
      }
      q = SolveLayupPose(cell, st.pose, &course.entry, &q).ik.joints;
      joints.push_back(q);
      std::vector<double> pt = AxesOf(q);
      if (!prev.empty()) c[0] += planner::MoveCost(p, prev.data(), pt.data());
      prev = std::move(pt);
    }
    c[3] += TimedLayupSeconds(timed, course, joints);
  }
  return c;
}

}  // namespace stitchsim::run
