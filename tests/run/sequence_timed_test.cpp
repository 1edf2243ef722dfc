// The timed measure (run/sequence_timed.h): an off-part move's time through the controller's
// time law, checked against the trapezoid and triangle profiles of docs/timing.md worked by
// hand; a case where it ranks two moves the other way round from the `time` measure (no
// acceleration there); the table equals the moves one by one, whatever the thread count; and
// a run minimising it prices its order with the same moves as its report.
#include "stitchsim/run/sequence_timed.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sequence_fixture.h"

namespace stitchsim::run {
namespace {

// A controller and cell for hand computations: the rail and a1 limited, nothing else moves.
// Rapid 500 mm/s, rotation 1 rad/s, ramp 0.25 s.
TimedModel HandModel(bool continuous) {
  TimedModel m;
  m.limits.max_velocity[trace::kRailX] = 1.0;      // m/s
  m.limits.max_acceleration[trace::kRailX] = 1.0;  // m/s^2
  m.limits.max_velocity[trace::kA1] = 1.0;         // rad/s
  m.limits.max_acceleration[trace::kA1] = 1.0;     // rad/s^2
  m.timing.law.ramp_time_s = 0.25;
  m.timing.law.continuous = continuous;
  m.rapid_speed_mm_s = 500.0;
  m.rotation_speed_rad_s = 1.0;
  return m;
}

EndPoint EndAt(double x, double y, double z, double rail_m, double a1_rad) {
  EndPoint e;
  e.pose.translation() = Eigen::Vector3d(x, y, z);
  e.tool = e.pose.translation();
  e.q[trace::kRailX] = rail_m;
  e.q[trace::kA1] = a1_rad;
  e.ok = true;
  return e;
}

// `courses` courses, each end raised as itself (no retract, no approach) unless set below.
CourseEnds Blank(int courses) {
  CourseEnds ends;
  for (int r = 0; r < 4 * courses; ++r) {
    ends.ends.push_back(EndAt(0, 0, 0, 0, 0));
    ends.ends.back().row = r;
    ends.raised.push_back(ends.ends.back());
    ends.raised.back().row = -1;
  }
  ends.approach_feed_mm_per_min.assign(static_cast<std::size_t>(courses), 6000.0);
  ends.reversible.assign(static_cast<std::size_t>(courses), true);
  ends.home = EndAt(0, 0, 0, 0, 0);
  return ends;
}

// Course 0 ends at x = 0 (rail 0); course 1 starts at x = 1000 (rail 1.15 m). Retract and
// approach 100 mm along z. Exact stop (each line from rest to rest), so the move is the sum of
// three profiles, each worked by hand with docs/timing.md's formulas:
// - retract: rapid 100 mm at 500 mm/s (0.2 s programmed), rail 0.1 m: v_c = min(1 / 0.2,
//   1 / 0.1) = 5 /s, a = min(5 / 0.25, 1 / 0.1) = 10 /s^2; the ramps want 2 x 25 / 20 > 1 of s:
//   a triangle, peak sqrt(10), 2 sqrt(10) / 10 = 2 sqrt(0.1) s (bang-bang over 0.1 m at 1 m/s^2);
// - transfer: rapid 1000 mm (2 s), rail 1 m (dominates), a1 0.01 rad: v_c = min(0.5, 1, 100)
//   = 0.5 /s, a = min(2, 1, 100) = 1 /s^2; ramps 0.125 of s and 0.5 s each, cruise
//   0.75 / 0.5 = 1.5 s: 2.5 s;
// - approach: feed 6000 mm/min over 100 mm (1 s), rail 0.05 m: v_c = min(1, 20) = 1 /s,
//   a = min(4, 20) = 4 /s^2; ramps 0.125 of s and 0.25 s each, cruise 0.75 s: 1.25 s.
CourseEnds HandMove() {
  CourseEnds ends = Blank(2);
  ends.ends[1] = EndAt(0, 0, 0, 0.0, 0.0);
  ends.raised[1] = EndAt(0, 0, 100, 0.1, 0.0);
  ends.raised[4] = EndAt(1000, 0, 100, 1.1, 0.01);
  ends.ends[4] = EndAt(1000, 0, 0, 1.15, 0.01);
  ends.ends[1].row = 1;
  ends.ends[4].row = 4;
  return ends;
}

TEST(SequenceTimed, OneMoveByHandWithTrapezoidsAndATriangle) {
  const double expected = 2.0 * std::sqrt(0.1) + 2.5 + 1.25;
  const double t = TimedMoveSeconds(HandModel(false), HandMove(), 1, 4);
  EXPECT_NEAR(t, expected, 1e-6 * expected);
  // Blending at the two junctions can only save time, never cost it.
  const double blended = TimedMoveSeconds(HandModel(true), HandMove(), 1, 4);
  EXPECT_LT(blended, t);
  EXPECT_GT(blended, 2.5);  // the transfer alone, from rest to rest
}

// The `time` measure (max over axes of |difference| / top speed) ranks move B (a1 0.9 rad at
// 1 rad/s: 0.9 s) below move A (rail 1 m at 1 m/s: 1 s). With a1's acceleration limited to
// 0.1 rad/s^2, B cannot reach its top speed: a triangle of 2 sqrt(0.9 / 0.1) = 6 s, while A
// (a = min(1 / 0.25 ... capped by 1 / 1) = 1 /s^2, ramps of 0.5 of s each) takes 2 s. Both
// are rapids of 100 mm (0.2 s programmed: the axes decide).
TEST(SequenceTimed, RanksTwoMovesUnlikeTheTimeMeasure) {
  TimedModel m = HandModel(false);
  m.limits.max_acceleration[trace::kA1] = 0.1;
  CourseEnds ends = Blank(2);
  ends.ends[4] = ends.raised[4] = EndAt(100, 0, 0, 1.0, 0.0);  // A: course 1 forwards
  ends.ends[6] = ends.raised[6] = EndAt(0, 100, 0, 0.0, 0.9);  // B: course 1 backwards
  planner::SequenceProblem time;                               // the `time` measure on the joints
  time.dim = trace::kNumJoints;
  time.norm = planner::CostNorm::kMax;
  time.weights.assign(trace::kNumJoints, 0.0);
  time.weights[trace::kRailX] = 1.0 / m.limits.max_velocity[trace::kRailX];
  time.weights[trace::kA1] = 1.0 / m.limits.max_velocity[trace::kA1];
  const auto time_of = [&](int row) {
    const trace::JointVector& a = ends.ends[1].q;
    const trace::JointVector& b = ends.ends[static_cast<std::size_t>(row)].q;
    return planner::MoveCost(time, a.data(), b.data());
  };
  EXPECT_NEAR(time_of(4), 1.0, 1e-12);
  EXPECT_NEAR(time_of(6), 0.9, 1e-12);
  const double a = TimedMoveSeconds(m, ends, 1, 4), b = TimedMoveSeconds(m, ends, 1, 6);
  EXPECT_NEAR(a, 2.0, 1e-9);
  EXPECT_NEAR(b, 6.0, 1e-9);
  EXPECT_LT(a, b);
}

// A lay-up on the time law, docs/timing.md's worked example: two collinear rail-only lines of
// 1000 mm at 6000 mm/min (10 s each programmed), rail 1 m/s and 2 m/s^2, ramp 0.25 s: one
// ramp up and one down of 0.25 s around 19.75 s of cruise, 20.25 s blended (like one line of
// 2000 mm); with an exact stop, two lines of 10.25 s each.
TEST(SequenceTimed, LayupIsTheWorkedExampleOfTheTimeLaw) {
  program::AfpCourse course;
  std::vector<trace::JointVector> q;
  for (int i = 0; i < 3; ++i) {
    program::LayupStation st;
    st.pose.translation() = Eigen::Vector3d(1000.0 * i, 0, 0);
    st.motion = program::Motion::kFeed;
    st.feed_mm_per_min = 6000.0;
    course.stations.push_back(st);
    q.push_back(EndAt(0, 0, 0, 1.0 * i, 0).q);
  }
  for (const bool continuous : {true, false}) {
    TimedModel m = HandModel(continuous);
    m.limits.max_acceleration[trace::kRailX] = 2.0;
    EXPECT_NEAR(TimedLayupSeconds(m, course, q), continuous ? 20.25 : 20.5, 1e-9) << continuous;
  }
}

// Four courses at scattered places: every entry of the table is the move priced alone, from
// the given start and to home; backward visits of a forward-only set (and of a course that
// cannot be laid backwards) are unreachable; one thread or three give the same bits.
TEST(SequenceTimed, TableIsEveryMoveAndTheSameOnAnyThreadCount) {
  CourseEnds ends = Blank(5);
  for (int r = 0; r < 20; ++r) {
    const double x = 97.0 * ((r * 7) % 11), y = 53.0 * ((r * 5) % 13);
    ends.ends[static_cast<std::size_t>(r)] = EndAt(x, y, 0, x / 1000.0, y / 700.0);
    ends.ends[static_cast<std::size_t>(r)].row = r;
    ends.raised[static_cast<std::size_t>(r)] = EndAt(x, y, 100, x / 1000.0 + 0.02, y / 700.0);
  }
  ends.reversible[3] = false;
  const std::vector<int> courses = {4, 1, 3, 0};  // a set: rows of ends, any order
  TimedModel m = HandModel(true);
  for (const bool bidirectional : {false, true}) {
    m.threads = 1;
    const auto one = TimedMoveTable(m, ends, courses, bidirectional, 9, true);
    m.threads = 3;
    const auto three = TimedMoveTable(m, ends, courses, bidirectional, 9, true);
    EXPECT_EQ(one->move, three->move);
    EXPECT_EQ(one->from_start, three->from_start);
    EXPECT_EQ(one->to_finish, three->to_finish);
    EXPECT_DOUBLE_EQ(one->start_to_finish, TimedMoveSeconds(m, ends, 9, -1));
    for (int u = 0; u < 8; ++u) {
      const int c = courses[static_cast<std::size_t>(u / 2)];
      const bool allowed = u % 2 == 0 || (bidirectional && c != 3);
      const int start = 4 * c + 2 * (u % 2);
      const auto su = static_cast<std::size_t>(u);
      EXPECT_EQ(one->from_start[su],
                allowed ? TimedMoveSeconds(m, ends, 9, start) : kUnreachableSeconds);
      EXPECT_EQ(one->to_finish[su],
                allowed ? TimedMoveSeconds(m, ends, start + 1, -1) : kUnreachableSeconds);
      for (int v = 0; v < 8; ++v) {
        const int d = courses[static_cast<std::size_t>(v / 2)];
        const bool v_allowed = v % 2 == 0 || (bidirectional && d != 3);
        const double want = u / 2 == v / 2 ? 0.0
                            : !(allowed && v_allowed)
                                ? kUnreachableSeconds
                                : TimedMoveSeconds(m, ends, start + 1, 4 * d + 2 * (v % 2));
        EXPECT_EQ(one->move[su * 8 + static_cast<std::size_t>(v)], want) << u << " " << v;
      }
    }
  }
}

// A run minimising the timed measure on seq_plate's pad-ups: its sets' costs on the table (the
// solver's) add up to the report's timed off-part after (MoveCosts, move by move); no set costs
// more than the programme's order of it; the lay-up on the time law takes at least its time at
// the programmed feeds (the law never goes faster than programmed).
TEST(SequenceTimed, RunPricesItsOrderWithTheReportsMoves) {
  const auto file = test::SequenceTestDir() / "timed_pads.nc";
  test::PlanSeqPlate({"pad_0_left", "pad_0_right"}, file);
  SequenceOptions o = test::SeqPlateOptions(file);
  o.measure = Measure::kTimed;
  o.bidirectional = true;
  o.return_home = true;
  const SequenceInputs in = test::LoadOrFail(o);
  std::filesystem::remove(file);
  const SequenceRun run = RunSequence(in, o, nullptr);
  ASSERT_EQ(run.status, SequenceStatus::kOk);
  const SequenceOutcome& out = run.outcome;
  constexpr auto kT = static_cast<std::size_t>(Measure::kTimed);
  double sets = 0.0;
  for (const auto& s : out.sets) {
    sets += s.cost;
    EXPECT_LE(s.cost, s.original_cost);
  }
  EXPECT_NEAR(sets, out.offpart_after[kT], 1e-9 * out.offpart_after[kT]);
  EXPECT_GT(out.offpart_after[kT], 0.0);
  EXPECT_GE(out.layup[kT], out.layup[static_cast<std::size_t>(Measure::kTime)] * (1 - 1e-12));
}

}  // namespace
}  // namespace stitchsim::run
