// Course ends as machine axes and tool points (sequence_costs.h).
#include "sequence_costs.h"

#include <cmath>

#include "stitchsim/common/units.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::app {
namespace {

// A backward end the cell cannot reach sits this far away in every coordinate.
constexpr double kUnreachableCoord = 1e7;

EndPoint Solve(const sim::CellSetup& cell, const Eigen::Isometry3d& pose,
               const program::LayupEntry* entry, const trace::JointVector* previous,
               trace::JointVector* joints = nullptr) {
  EndPoint e;
  const double rotator_rad =
      (entry != nullptr && entry->rotator_deg) ? *entry->rotator_deg / kRadToDeg : 0.0;
  const std::optional<double> rail = entry != nullptr ? entry->rail_mm : std::nullopt;
  const sim::ToolPoseSolution s = sim::SolveToolPose(cell, pose, rotator_rad, rail, previous);
  e.tool = pose.translation();
  e.ok = trace::IkUsable(s.ik.status);
  if (!e.ok)
    e.reason = s.ik.reason.empty() ? std::string(trace::ToString(s.ik.status)) : s.ik.reason;
  if (joints != nullptr) *joints = s.ik.joints;
  e.axes.resize(trace::kNumJoints);
  for (int j = 0; j < trace::kNumJoints; ++j) {
    const double q = s.ik.joints[j];
    e.axes[static_cast<std::size_t>(j)] = j == trace::kRailX ? q * 1000.0 : q * kRadToDeg;
  }
  return e;
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
  }
  return "?";
}

const char* MeasureUnit(Measure m) {
  switch (m) {
    case Measure::kAxes:
      return "";
    case Measure::kTime:
      return "s";
    case Measure::kTool:
      return "mm";
  }
  return "";
}

CourseEnds SolveCourseEnds(const sim::CellSetup& cell, const program::AfpProgram& program,
                           const Eigen::Isometry3d& home) {
  CourseEnds out;
  const trace::JointVector home_q = sim::HomeJoints(*cell.robot, 0.0);
  out.home = Solve(cell, home, nullptr, &home_q);
  out.ends.reserve(program.courses.size() * 4);
  out.reversible.reserve(program.courses.size());
  for (const auto& c : program.courses) {
    for (const bool rev : {false, true}) {
      const Eigen::Isometry3d a = program::LayupStartPose(c, rev);
      const Eigen::Isometry3d b = program::LayupEndPose(c, rev);
      trace::JointVector qa;
      EndPoint ea = Solve(cell, a, &c.entry, &home_q, &qa);
      EndPoint eb = Solve(cell, b, &c.entry, &qa);
      out.ends.push_back(std::move(ea));
      out.ends.push_back(std::move(eb));
    }
    const std::size_t k = out.ends.size() - 4;
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
  planner::SequenceProblem p;
  p.courses = static_cast<int>(courses.size());
  p.dim = static_cast<int>(spec.weights.size());
  p.weights = spec.weights;
  p.norm = spec.norm;
  p.bidirectional = bidirectional;
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

}  // namespace stitchsim::app
