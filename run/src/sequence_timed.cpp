// The timed measure: off-part moves and lay-ups through the controller's time law
// (sequence_timed.h).
#include "stitchsim/run/sequence_timed.h"

#include <algorithm>
#include <functional>
#include <thread>

#include "stitchsim/geom/rotation.h"
#include "stitchsim/run/run_model.h"
#include "stitchsim/sim/executor.h"

namespace stitchsim::run {
namespace {

// A pose the head passes through and its joints (m, rad).
struct TimedPoint {
  const Eigen::Isometry3d* pose = nullptr;
  const trace::JointVector* q = nullptr;
};

// One straight line from `a` to `b` as the executor times it (executor_core.h: the rotation at
// the rotation speed, a rapid at the rapid speed, a feed move at its feed; a pure rotation
// settles after) and as the timing sink hands it to the planner (timing.cpp, InputOf): joints
// straight from a.q to b.q, so dq/ds is their difference everywhere. A feed move without a
// feed (0) is bounded by its rotation and the axes only, as in the executor. False when the
// line neither moves nor dwells (the timing sink passes it by).
bool TimedLineOf(const TimedModel& m, const TimedPoint& a, const TimedPoint& b, bool rapid,
                 double feed_mm_per_min, sim::TimedLineInput& in) {
  const double dist = (b.pose->translation() - a.pose->translation()).norm();
  const double angle = geom::AngleBetween(a.pose->linear(), b.pose->linear());
  const trace::JointVector chord = *b.q - *a.q;
  double duration = angle / m.rotation_speed_rad_s;
  if (rapid) {
    duration = std::max(duration, dist / m.rapid_speed_mm_s);
  } else if (dist > 0.0 && feed_mm_per_min > 0.0) {
    duration = std::max(duration, dist / (feed_mm_per_min / 60.0));
  }
  in = sim::TimedLineInput{};
  if (dist <= 1e-9 && angle > 1e-12) {
    in.dwell_s = m.timing.settle_time_s;
    in.stop_after = true;
  }
  in.programmed_duration_s = duration;
  in.dq_ds_start = chord;
  in.dq_ds_end = chord;
  in.dq_ds_max = chord.cwiseAbs();
  return duration > 0.0 || !chord.isZero(0.0) || in.dwell_s > 0.0;
}

// One line's input for the planner; `moves` false: it neither moves nor dwells (left out).
struct PlannedLine {
  bool moves = false;
  sim::TimedLineInput in;
};

PlannedLine LineOf(const TimedModel& m, const TimedPoint& a, const TimedPoint& b, bool rapid,
                   double feed_mm_per_min) {
  PlannedLine l;
  l.moves = TimedLineOf(m, a, b, rapid, feed_mm_per_min, l.in);
  return l;
}

// Plans lines in order from rest to rest and sums their durations (s).
class LinesTimer {
 public:
  explicit LinesTimer(const TimedModel& m) : planner_(m.limits, m.timing.law) {}
  void Add(const PlannedLine& l) {
    if (l.moves) planner_.Push(l.in);
  }
  double Finish() {
    planner_.Flush();
    double total = 0.0;
    sim::LineProfile p;
    while (planner_.Pop(p)) total += p.duration_s;
    return total;
  }

 private:
  sim::TimeLawPlanner planner_;
};

TimedPoint PointAt(const EndPoint& e) { return {&e.pose, &e.q}; }

const EndPoint& EndAtRow(const CourseEnds& ends, int row) {
  return row < 0 ? ends.home : ends.ends[static_cast<std::size_t>(row)];
}
// Where the head is retracted to from row's end and approaches row's start from (home: home).
const EndPoint& AboveRow(const CourseEnds& ends, int row) {
  return row < 0 ? ends.home : ends.raised[static_cast<std::size_t>(row)];
}

// The retract from a lay-up end at `row` (none from home).
PlannedLine RetractLine(const TimedModel& m, const CourseEnds& ends, int row) {
  if (row < 0) return {};
  return LineOf(m, PointAt(EndAtRow(ends, row)), PointAt(AboveRow(ends, row)), true, 0.0);
}

// The approach onto a lay-up start at `row` at its course's feed (none to home).
PlannedLine ApproachLine(const TimedModel& m, const CourseEnds& ends, int row) {
  if (row < 0) return {};
  const double feed = ends.approach_feed_mm_per_min[static_cast<std::size_t>(row / 4)];
  return LineOf(m, PointAt(AboveRow(ends, row)), PointAt(EndAtRow(ends, row)), false, feed);
}

// The move from row `from_row` to `to_row` given its retract and approach (each the same for
// every move from that end or to that start: the table computes them once).
double MoveSeconds(const TimedModel& m, const CourseEnds& ends, int from_row, int to_row,
                   const PlannedLine& retract, const PlannedLine& approach, LinesTimer& timer) {
  timer.Add(retract);
  timer.Add(
      LineOf(m, PointAt(AboveRow(ends, from_row)), PointAt(AboveRow(ends, to_row)), true, 0.0));
  timer.Add(approach);
  return timer.Finish();
}

double MoveSeconds(const TimedModel& m, const CourseEnds& ends, int from_row, int to_row,
                   LinesTimer& timer) {
  return MoveSeconds(m, ends, from_row, to_row, RetractLine(m, ends, from_row),
                     ApproachLine(m, ends, to_row), timer);
}

// Rows of ends.ends of node u of a set: its start (k = 0 or 2) and its end (1 or 3).
int StartRow(const std::vector<int>& courses, int u) {
  return 4 * courses[static_cast<std::size_t>(u / 2)] + 2 * (u % 2);
}
int EndRow(const std::vector<int>& courses, int u) { return StartRow(courses, u) + 1; }

// Whether node u of a set may be visited at all.
bool NodeAllowed(const CourseEnds& ends, const std::vector<int>& courses, int u,
                 bool bidirectional) {
  if (u % 2 == 0) return true;
  return bidirectional && ends.reversible[static_cast<std::size_t>(courses[u / 2])];
}

// Rows [begin, end) of the table's move matrix; `approach`: the approach line into each node.
void FillMoveRows(const TimedModel& m, const CourseEnds& ends, const std::vector<int>& courses,
                  bool bidirectional, const std::vector<PlannedLine>& approach, int begin, int end,
                  planner::MoveTable& t) {
  LinesTimer timer(m);
  const int nodes = 2 * static_cast<int>(courses.size());
  for (int u = begin; u < end; ++u) {
    const bool u_ok = NodeAllowed(ends, courses, u, bidirectional);
    const PlannedLine retract = RetractLine(m, ends, EndRow(courses, u));
    for (int v = 0; v < nodes; ++v) {
      double& cell = t.move[static_cast<std::size_t>(u) * nodes + v];
      if (u / 2 == v / 2) {
        cell = 0.0;  // the same course: never a move
      } else if (!u_ok || !NodeAllowed(ends, courses, v, bidirectional)) {
        cell = kUnreachableSeconds;
      } else {
        cell = MoveSeconds(m, ends, EndRow(courses, u), StartRow(courses, v), retract,
                           approach[static_cast<std::size_t>(v)], timer);
      }
    }
  }
}

}  // namespace

TimedModel TimedModelOf(const sim::RobotModel& robot, const scene::Scene& scene,
                        const program::Dialect& dialect) {
  TimedModel m;
  m.limits = sim::AxisLimitsOf(robot);
  const sim::ExecuteOptions execute = sim::ExecuteOptionsFor(scene);
  m.timing = TimingOptionsFor(dialect, execute);
  m.rapid_speed_mm_s = execute.rapid_speed_mm_s;
  m.rotation_speed_rad_s = execute.rotation_speed_rad_s;
  return m;
}

double TimedMoveSeconds(const TimedModel& m, const CourseEnds& ends, int from_row, int to_row) {
  LinesTimer timer(m);
  return MoveSeconds(m, ends, from_row, to_row, timer);
}

std::shared_ptr<const planner::MoveTable> TimedMoveTable(const TimedModel& m,
                                                         const CourseEnds& ends,
                                                         const std::vector<int>& courses,
                                                         bool bidirectional, int start_row,
                                                         bool finish) {
  auto t = std::make_shared<planner::MoveTable>();
  const int nodes = 2 * static_cast<int>(courses.size());
  t->move.assign(static_cast<std::size_t>(nodes) * static_cast<std::size_t>(nodes), 0.0);
  t->from_start.assign(static_cast<std::size_t>(nodes), 0.0);
  t->to_finish.assign(static_cast<std::size_t>(nodes), 0.0);
  LinesTimer timer(m);
  for (int u = 0; u < nodes; ++u) {
    const bool ok = NodeAllowed(ends, courses, u, bidirectional);
    t->from_start[static_cast<std::size_t>(u)] =
        ok ? MoveSeconds(m, ends, start_row, StartRow(courses, u), timer) : kUnreachableSeconds;
    if (finish) {
      t->to_finish[static_cast<std::size_t>(u)] =
          ok ? MoveSeconds(m, ends, EndRow(courses, u), -1, timer) : kUnreachableSeconds;
    }
  }
  if (finish) t->start_to_finish = MoveSeconds(m, ends, start_row, -1, timer);
  // Contiguous blocks of rows, one per thread: each entry is a function of its pair alone, so
  // the table is the same whatever the number of threads.
  std::vector<PlannedLine> approach;
  for (int v = 0; v < nodes; ++v) approach.push_back(ApproachLine(m, ends, StartRow(courses, v)));
  const int threads = std::clamp(m.threads, 1, std::max(1, nodes));
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) {
    pool.emplace_back(FillMoveRows, std::cref(m), std::cref(ends), std::cref(courses),
                      bidirectional, std::cref(approach), nodes * k / threads,
                      nodes * (k + 1) / threads, std::ref(*t));
  }
  FillMoveRows(m, ends, courses, bidirectional, approach, 0, nodes / threads, *t);
  for (auto& th : pool) th.join();
  return t;
}

double TimedLayupSeconds(const TimedModel& m, const program::AfpCourse& course,
                         const std::vector<trace::JointVector>& q) {
  LinesTimer timer(m);
  for (std::size_t i = 0; i + 1 < course.stations.size() && i + 1 < q.size(); ++i) {
    const auto& st = course.stations[i];
    timer.Add(LineOf(m, {&st.pose, &q[i]}, {&course.stations[i + 1].pose, &q[i + 1]},
                     st.motion == program::Motion::kRapid, st.feed_mm_per_min));
  }
  return timer.Finish();
}

}  // namespace stitchsim::run
