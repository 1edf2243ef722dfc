// The controller's time law (docs/timing.md): every profile against a hand computation or a
// closed form written here independently of the planner.
#include "stitchsim/sim/time_law.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace stitchsim::sim {
namespace {

using trace::kA1;
using trace::kRailX;

// A line moving only joint `joint` by `delta` (m or rad) in `programmed_s` seconds.
TimedLineInput AxisLine(int source_line, int joint, double delta, double programmed_s) {
  TimedLineInput line;
  line.source_line = source_line;
  line.programmed_duration_s = programmed_s;
  line.dq_ds_start(joint) = delta;
  line.dq_ds_end(joint) = delta;
  line.dq_ds_max(joint) = std::abs(delta);
  return line;
}

AxisLimits Limits(int joint, double vmax, double amax) {
  AxisLimits limits;
  limits.max_velocity(joint) = vmax;
  limits.max_acceleration(joint) = amax;
  return limits;
}

// Plans a whole programme (Flush at the end) and returns the profiles in order.
std::vector<LineProfile> Plan(const AxisLimits& limits, const TimeLawOptions& options,
                              const std::vector<TimedLineInput>& lines) {
  TimeLawPlanner planner(limits, options);
  std::vector<LineProfile> out;
  LineProfile p;
  for (const TimedLineInput& line : lines) {
    planner.Push(line);
    EXPECT_LE(planner.Pending(), static_cast<std::size_t>(options.look_ahead_lines));
    while (planner.Pop(p)) out.push_back(p);
  }
  planner.Flush();
  EXPECT_EQ(planner.Pending(), 0u);
  while (planner.Pop(p)) out.push_back(p);
  EXPECT_EQ(out.size(), lines.size());
  return out;
}

double Total(const std::vector<LineProfile>& profiles) {
  double total = 0.0;
  for (const LineProfile& p : profiles) total += p.duration_s;
  return total;
}

// 1. One rail line of 1000 mm at 6000 mm/min (10 s programmed), rail 1 m/s and 2 m/s^2, ramp
// 0.25 s, alone. v_c = min(1/10, 1/1) = 0.1/s; a = min(0.1/0.25, 2/1) = 0.4/s^2; ramps
// 0.1/0.4 = 0.25 s over 0.1^2/(2 0.4) = 0.0125 of the line each; cruise 0.975/0.1 = 9.75 s.
TEST(TimeLawTest, HandCaseOneRailLine) {
  TimeLawOptions options;
  const std::vector<LineProfile> p =
      Plan(Limits(kRailX, 1.0, 2.0), options, {AxisLine(7, kRailX, 1.0, 10.0)});
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].source_line, 7);
  EXPECT_NEAR(p[0].v_in, 0.0, 1e-12);
  EXPECT_NEAR(p[0].v_cruise, 0.1, 1e-12);
  EXPECT_NEAR(p[0].v_out, 0.0, 1e-12);
  EXPECT_NEAR(p[0].accel, 0.4, 1e-12);
  EXPECT_NEAR(p[0].t_accel, 0.25, 1e-12);
  EXPECT_NEAR(p[0].t_cruise, 9.75, 1e-12);
  EXPECT_NEAR(p[0].t_decel, 0.25, 1e-12);
  EXPECT_NEAR(p[0].duration_s, 10.25, 1e-12);
}

// The same line with the rail capped at 0.2 m/s^2: a = min(0.4, 0.2/1) = 0.2/s^2; ramps
// 0.1/0.2 = 0.5 s over 0.01/0.4 = 0.025 each; cruise 0.95/0.1 = 9.5 s; total 10.5 s.
TEST(TimeLawTest, HandCaseCappedByTheAxis) {
  const std::vector<LineProfile> p =
      Plan(Limits(kRailX, 1.0, 0.2), TimeLawOptions{}, {AxisLine(1, kRailX, 1.0, 10.0)});
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NEAR(p[0].accel, 0.2, 1e-12);
  EXPECT_NEAR(p[0].t_accel, 0.5, 1e-12);
  EXPECT_NEAR(p[0].t_cruise, 9.5, 1e-12);
  EXPECT_NEAR(p[0].t_decel, 0.5, 1e-12);
  EXPECT_NEAR(p[0].duration_s, 10.5, 1e-12);
}

// The axis speed caps the cruise: the same line programmed at 1 s with the rail at 0.5 m/s:
// v_c = min(1, 0.5) = 0.5/s, a = min(0.5/0.25, 2) = 2/s^2; ramps 0.25 s over 0.0625 each.
TEST(TimeLawTest, CruiseCappedByTheAxisSpeed) {
  const std::vector<LineProfile> p =
      Plan(Limits(kRailX, 0.5, 2.0), TimeLawOptions{}, {AxisLine(1, kRailX, 1.0, 1.0)});
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NEAR(p[0].v_cruise, 0.5, 1e-12);
  EXPECT_NEAR(p[0].accel, 2.0, 1e-12);
  EXPECT_NEAR(p[0].duration_s, 0.25 + 0.875 / 0.5 + 0.25, 1e-12);
}

// 2. A short line: 10 mm at 6000 mm/min (0.1 s) with the rail at 0.2 m/s^2. v_c = 10/s,
// a = min(40, 0.2/0.01) = 20/s^2: the ramps need 2.5 lines, so a triangle. Physically: a move
// of d = 0.01 m from rest to rest at 0.2 m/s^2 takes 2 sqrt(d / a) and peaks at sqrt(a d).
TEST(TimeLawTest, ShortLineIsATriangle) {
  const std::vector<LineProfile> p =
      Plan(Limits(kRailX, 1.0, 0.2), TimeLawOptions{}, {AxisLine(1, kRailX, 0.01, 0.1)});
  ASSERT_EQ(p.size(), 1u);
  const double d = 0.01, amax = 0.2;
  EXPECT_NEAR(p[0].duration_s, 2.0 * std::sqrt(d / amax), 1e-12);
  EXPECT_NEAR(p[0].v_cruise * d, std::sqrt(amax * d), 1e-12);  // peak speed in m/s
  EXPECT_NEAR(p[0].t_cruise, 0.0, 1e-15);
  EXPECT_NEAR(p[0].t_accel, p[0].t_decel, 1e-12);
}

// A triangle between unequal end speeds: v_in 1, v_out 2, a 3 (v_c 10 out of reach). The peak
// solves (v_p^2 - 1) / 6 + (v_p^2 - 4) / 6 = 1: v_p^2 = 5.5.
TEST(TimeLawTest, TriangleBetweenUnequalSpeeds) {
  const LineProfile p = MakeProfile(3, 1.0, 10.0, 2.0, 3.0, 0.5);
  const double peak = std::sqrt(5.5);
  EXPECT_NEAR(p.v_cruise, peak, 1e-12);
  EXPECT_NEAR(p.t_accel, (peak - 1.0) / 3.0, 1e-12);
  EXPECT_NEAR(p.t_decel, (peak - 2.0) / 3.0, 1e-12);
  EXPECT_NEAR(p.duration_s, (2.0 * peak - 3.0) / 3.0 + 0.5, 1e-12);
  // The distance under the speed curve is the whole line.
  const double s = (1.0 + peak) / 2.0 * p.t_accel + (peak + 2.0) / 2.0 * p.t_decel;
  EXPECT_NEAR(s, 1.0, 1e-12);
}

// 3. Two collinear equal lines: no velocity jump, so f = 1 and the pair is one line of twice
// the length (0.25 + 19.75 + 0.25 s); in exact stop, two hand-case trapezoids (2 x 10.25 s).
TEST(TimeLawTest, CollinearLinesBlendWithoutSlowdown) {
  const AxisLimits limits = Limits(kRailX, 1.0, 2.0);
  const std::vector<TimedLineInput> lines = {AxisLine(1, kRailX, 1.0, 10.0),
                                             AxisLine(2, kRailX, 1.0, 10.0)};
  const std::vector<LineProfile> blended = Plan(limits, TimeLawOptions{}, lines);
  ASSERT_EQ(blended.size(), 2u);
  EXPECT_NEAR(blended[0].v_out, 0.1, 1e-12);
  EXPECT_NEAR(blended[1].v_in, 0.1, 1e-12);
  EXPECT_NEAR(blended[0].t_decel, 0.0, 1e-12);
  EXPECT_NEAR(Total(blended), 0.25 + 19.75 + 0.25, 1e-12);
  const std::vector<LineProfile> single =
      Plan(limits, TimeLawOptions{}, {AxisLine(1, kRailX, 2.0, 20.0)});
  EXPECT_NEAR(Total(blended), Total(single), 1e-12);

  TimeLawOptions exact;
  exact.continuous = false;
  const std::vector<LineProfile> stopped = Plan(limits, exact, lines);
  EXPECT_NEAR(stopped[0].v_out, 0.0, 1e-12);
  EXPECT_NEAR(stopped[1].v_in, 0.0, 1e-12);
  EXPECT_NEAR(Total(stopped), 2.0 * 10.25, 1e-12);

  // stop_after forces the stop in continuous mode too.
  std::vector<TimedLineInput> with_stop = lines;
  with_stop[0].stop_after = true;
  EXPECT_NEAR(Total(Plan(limits, TimeLawOptions{}, with_stop)), 2.0 * 10.25, 1e-12);
}

// 4. A corner between two joints: the rail moves 1 m in 1 s, then a1 turns 1 rad in 1 s; both
// 2 (m or rad)/s^2, ramp 0.25 s. v_c = 1 and a = min(1/0.25, 2) = 2 on both lines. The jumps
// D_rail = |1 x 1 - 0| = 1, D_a1 = 1; T_mid = 1. f <= sqrt(2 x 1 / 1) and f <= 2 x 0.25 / 1:
// f = 0.5. Line 1: 0 -> 1 over 0.25 of s (0.5 s), 1 -> 0.5 over 0.1875 (0.25 s), cruise 0.5625
// (0.5625 s): 1.3125 s; line 2 the mirror image. Exact stop: 0.5 + 0.5 + 0.5 s per line.
TEST(TimeLawTest, CornerBetweenTwoJoints) {
  AxisLimits limits = Limits(kRailX, 2.0, 2.0);
  limits.max_velocity(kA1) = 2.0;
  limits.max_acceleration(kA1) = 2.0;
  const std::vector<TimedLineInput> lines = {AxisLine(1, kRailX, 1.0, 1.0),
                                             AxisLine(2, kA1, 1.0, 1.0)};
  const std::vector<LineProfile> p = Plan(limits, TimeLawOptions{}, lines);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0].v_out, 0.5, 1e-12);
  EXPECT_NEAR(p[1].v_in, 0.5, 1e-12);
  EXPECT_NEAR(p[0].t_accel, 0.5, 1e-12);
  EXPECT_NEAR(p[0].t_cruise, 0.5625, 1e-12);
  EXPECT_NEAR(p[0].t_decel, 0.25, 1e-12);
  EXPECT_NEAR(p[0].duration_s, 1.3125, 1e-12);
  EXPECT_NEAR(p[1].duration_s, 1.3125, 1e-12);
  TimeLawOptions exact;
  exact.continuous = false;
  EXPECT_NEAR(Total(Plan(limits, exact, lines)), 3.0, 1e-12);
}

// The same corner where the blend time T_mid / f binds: lines of 0.25 s (v_c = 4), a long ramp
// of 2 s (a = min(4 / 2, 2) = 2). D = 4 on both axes, T_mid = 0.25: f <= sqrt(2 x 0.25 / 4)
// = sqrt(0.125), f <= 2 x 2 / 4 = 1; braking (sqrt(2 x 2) / 4 = 0.5) does not bind. Over the
// blend time t_b = T_mid / f each axis accelerates by exactly its limit, f D / t_b = 2.
TEST(TimeLawTest, CornerLimitedByTheBlendTime) {
  AxisLimits limits = Limits(kRailX, 10.0, 2.0);
  limits.max_velocity(kA1) = 10.0;
  limits.max_acceleration(kA1) = 2.0;
  TimeLawOptions options;
  options.ramp_time_s = 2.0;
  const std::vector<LineProfile> p =
      Plan(limits, options, {AxisLine(1, kRailX, 1.0, 0.25), AxisLine(2, kA1, 1.0, 0.25)});
  ASSERT_EQ(p.size(), 2u);
  const double f = std::sqrt(0.125);
  EXPECT_NEAR(p[0].v_out, 4.0 * f, 1e-12);
  EXPECT_NEAR(p[1].v_in, 4.0 * f, 1e-12);
  const double t_b = std::min(0.25 / f, 2.0);
  EXPECT_NEAR(f * 4.0 / t_b, 2.0, 1e-12);
  // Line 1 is a triangle from rest to 4 f: peak^2 = (2 x 2 + 0 + 16 f^2) / 2 = 3.
  EXPECT_NEAR(p[0].v_cruise, std::sqrt(3.0), 1e-12);
}

// A line with neither programmed time nor motion takes only its dwell and stops its neighbours;
// a dwell (settle after a rotation) ends its line at rest.
TEST(TimeLawTest, NoMotionAndDwellStop) {
  const AxisLimits limits = Limits(kRailX, 1.0, 2.0);
  TimedLineInput still;  // no motion
  still.source_line = 2;
  still.dwell_s = 0.3;
  const std::vector<LineProfile> p =
      Plan(limits, TimeLawOptions{},
           {AxisLine(1, kRailX, 1.0, 10.0), still, AxisLine(3, kRailX, 1.0, 10.0)});
  ASSERT_EQ(p.size(), 3u);
  EXPECT_NEAR(p[0].v_out, 0.0, 1e-12);
  EXPECT_NEAR(p[1].duration_s, 0.3, 1e-12);
  EXPECT_NEAR(p[1].v_cruise, 0.0, 1e-12);
  EXPECT_NEAR(p[2].v_in, 0.0, 1e-12);
  EXPECT_NEAR(Total(p), 10.25 + 0.3 + 10.25, 1e-12);

  std::vector<TimedLineInput> dwelling = {AxisLine(1, kRailX, 1.0, 10.0),
                                          AxisLine(2, kRailX, 1.0, 10.0)};
  dwelling[0].dwell_s = 0.5;
  const std::vector<LineProfile> q = Plan(limits, TimeLawOptions{}, dwelling);
  EXPECT_NEAR(q[0].v_out, 0.0, 1e-12);
  EXPECT_NEAR(q[0].duration_s, 10.25 + 0.5, 1e-12);
  EXPECT_NEAR(Total(q), 2.0 * 10.25 + 0.5, 1e-12);
}

// Profiles come out in order once they leave the window: with 3 lines held, the 4th push
// fixes the 1st line.
TEST(TimeLawTest, ProfilesLeaveTheWindowInOrder) {
  TimeLawOptions options;
  options.look_ahead_lines = 3;
  TimeLawPlanner planner(Limits(kRailX, 1.0, 2.0), options);
  LineProfile p;
  for (int i = 1; i <= 3; ++i) planner.Push(AxisLine(i, kRailX, 0.1, 1.0));
  EXPECT_EQ(planner.Pending(), 3u);
  EXPECT_FALSE(planner.Pop(p));
  planner.Push(AxisLine(4, kRailX, 0.1, 1.0));
  EXPECT_EQ(planner.Pending(), 3u);
  ASSERT_TRUE(planner.Pop(p));
  EXPECT_EQ(p.source_line, 1);
  EXPECT_FALSE(planner.Pop(p));
  planner.Flush();
  EXPECT_EQ(planner.Pending(), 0u);
  for (int i = 2; i <= 4; ++i) {
    ASSERT_TRUE(planner.Pop(p));
    EXPECT_EQ(p.source_line, i);
  }
  EXPECT_NEAR(p.v_out, 0.0, 1e-12);  // the programme ends at rest
  EXPECT_FALSE(planner.Pop(p));
}

// 5. Look-ahead: 20 collinear rail lines of 10 mm at 6000 mm/min, rail 1 m/s and 2 m/s^2, then
// the programme end. Per line v_c = 10/s, a = min(10/0.25, 2/0.01) = 40/s^2.
// - 64 lines ahead: the chain is one line of 0.2 m: 0.25 + 0.175/0.1 + 0.25 = 2.25 s.
// - 2 lines ahead: a line may leave only at a speed from which the next can stop within its
//   own length, sqrt(2 x 40) = sqrt(80)/s; every middle line runs sqrt(80) -> 10 -> sqrt(80):
//   ramps of (10 - sqrt(80))/40 s over (100 - 80)/80 = 0.25 of s each, cruise 0.5/10 s.
// - 1 line ahead: every line stops: a triangle of 2 sqrt(1/40) s.
TEST(TimeLawTest, LookAheadWindowLimitsTheSpeed) {
  const AxisLimits limits = Limits(kRailX, 1.0, 2.0);
  std::vector<TimedLineInput> lines;
  for (int i = 0; i < 20; ++i) lines.push_back(AxisLine(i + 1, kRailX, 0.01, 0.1));
  TimeLawOptions wide, narrow, none;
  narrow.look_ahead_lines = 2;
  none.look_ahead_lines = 1;
  const std::vector<LineProfile> p64 = Plan(limits, wide, lines);
  const std::vector<LineProfile> p2 = Plan(limits, narrow, lines);
  const std::vector<LineProfile> p1 = Plan(limits, none, lines);
  EXPECT_NEAR(Total(p64), 2.25, 1e-12);
  const double v2 = std::sqrt(80.0);
  for (int i = 1; i + 1 < 20; ++i) {
    EXPECT_NEAR(p2[i].v_in, v2, 1e-12) << i;
    EXPECT_NEAR(p2[i].v_out, v2, 1e-12) << i;
    EXPECT_NEAR(p2[i].duration_s, 2.0 * (10.0 - v2) / 40.0 + 0.05, 1e-12) << i;
  }
  EXPECT_NEAR(Total(p1), 20.0 * 2.0 * std::sqrt(1.0 / 40.0), 1e-12);
  EXPECT_LT(Total(p64), Total(p2));
  EXPECT_LT(Total(p2), Total(p1));
  for (int i = 0; i < 20; ++i) {
    EXPECT_LE(p2[i].v_out, p64[i].v_out + 1e-12) << i;
    EXPECT_LE(p1[i].v_out, p2[i].v_out + 1e-12) << i;
    for (const std::vector<LineProfile>* run : {&p64, &p2, &p1}) {
      const LineProfile& p = (*run)[i];
      EXPECT_LE(std::abs(p.v_out * p.v_out - p.v_in * p.v_in), 2.0 * p.accel + 1e-12) << i;
    }
  }
}

// A random feasible profile: 0 <= v_in, v_out <= v_c, |v_out^2 - v_in^2| <= 2a, a dwell only
// after a stop.
LineProfile RandomProfile(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double accel = 0.1 + 50.0 * unit(rng);
  const double v_cruise = 0.05 + 20.0 * unit(rng);
  const double v_in = unit(rng) < 0.3 ? 0.0 : v_cruise * unit(rng);
  double v_out = unit(rng) < 0.3 ? 0.0 : v_cruise * unit(rng);
  v_out = std::min(v_out, std::sqrt(v_in * v_in + 2.0 * accel));
  const double v_in_fixed = std::min(v_in, std::sqrt(v_out * v_out + 2.0 * accel));
  const double dwell = v_out > 0.0 || unit(rng) < 0.5 ? 0.0 : unit(rng);  // dwell at rest
  return MakeProfile(1, v_in_fixed, v_cruise, v_out, accel, dwell);
}

// 6. StateAtTime and StateAtFraction invert each other; s(t) is monotone, its slope is s_dot
// and the area under s_dot is the whole line.
TEST(TimeLawTest, TimeAndFractionInvertEachOther) {
  std::mt19937 rng(20240611);
  for (int trial = 0; trial < 300; ++trial) {
    const LineProfile p = RandomProfile(rng);
    const double t_motion = p.t_accel + p.t_cruise + p.t_decel;
    EXPECT_NEAR(StateAtTime(p, 0.0).s, 0.0, 1e-15);
    EXPECT_NEAR(StateAtTime(p, 0.0).s_dot, p.v_in, 1e-12);
    EXPECT_NEAR(StateAtTime(p, t_motion).s, 1.0, 1e-15);
    EXPECT_NEAR(StateAtTime(p, t_motion).s_dot, p.v_out, 1e-12);
    EXPECT_NEAR(StateAtTime(p, p.duration_s).s, 1.0, 1e-15);
    EXPECT_NEAR(StateAtFraction(p, 1.0).t, t_motion, 1e-15);
    constexpr int kSteps = 400;
    const double h = t_motion / kSteps;
    double previous_s = -1.0, area = 0.0;
    for (int i = 0; i <= kSteps; ++i) {
      const double t = i * h;
      const PathState at_t = StateAtTime(p, t);
      EXPECT_GE(at_t.s, previous_s) << trial << " t " << t;
      previous_s = at_t.s;
      const PathState back = StateAtFraction(p, at_t.s);
      EXPECT_NEAR(back.t, t, 1e-6) << trial << " t " << t;
      EXPECT_NEAR(back.s_dot, at_t.s_dot, 1e-6) << trial << " t " << t;
      if (i < kSteps) {
        const PathState next = StateAtTime(p, t + h);
        area += (at_t.s_dot + next.s_dot) / 2.0 * h;
        // s_dot is the slope of s (exact for a quadratic over a step inside one phase).
        const double mid_slope = StateAtTime(p, t + h / 2.0).s_dot;
        EXPECT_NEAR((next.s - at_t.s) / h, mid_slope, 1e-9 + p.accel * h) << trial;
      }
    }
    EXPECT_NEAR(area, 1.0, 1e-9 + p.accel * h * h * 4.0) << trial;
    for (int i = 0; i <= 100; ++i) {
      const double s = i / 100.0;
      const PathState at_s = StateAtFraction(p, s);
      EXPECT_NEAR(StateAtTime(p, at_s.t).s, s, 1e-12) << trial << " s " << s;
    }
    // The dwell is at rest at the end of the line.
    if (p.dwell_s > 0.0) {
      const PathState dwelling = StateAtTime(p, t_motion + p.dwell_s / 2.0);
      EXPECT_EQ(dwelling.s, 1.0);
      EXPECT_EQ(dwelling.s_dot, 0.0);
      EXPECT_EQ(dwelling.s_ddot, 0.0);
    }
  }
}

// A random line: a few joints moving, dq/ds varying along the line (start, end <= max).
TimedLineInput RandomLine(std::mt19937& rng, int source_line) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  TimedLineInput line;
  line.source_line = source_line;
  if (unit(rng) < 0.05) {  // a line without motion, sometimes with a dwell
    line.dwell_s = unit(rng) < 0.5 ? 0.0 : 0.2;
    return line;
  }
  for (int j = 0; j < trace::kNumJoints; ++j) {
    if (unit(rng) < 0.5) continue;
    line.dq_ds_start(j) = 2.0 * unit(rng) - 1.0;
    line.dq_ds_end(j) = unit(rng) < 0.7 ? line.dq_ds_start(j) : 2.0 * unit(rng) - 1.0;
    line.dq_ds_max(j) = std::max(std::abs(line.dq_ds_start(j)), std::abs(line.dq_ds_end(j))) *
                        (1.0 + 0.5 * unit(rng));
  }
  line.programmed_duration_s = unit(rng) < 0.1 ? 0.0 : 0.01 + 2.0 * unit(rng);
  line.stop_after = unit(rng) < 0.05;
  line.dwell_s = unit(rng) < 0.05 ? 0.3 : 0.0;
  return line;
}

// The cruise speed the model gives, computed here on its own: min(1/T, vmax_j / dq_ds_max_j);
// 0 for a line that does not move (or that nothing bounds).
double ExpectedCruise(const AxisLimits& limits, const TimedLineInput& line) {
  double v = line.programmed_duration_s > 0.0 ? 1.0 / line.programmed_duration_s
                                              : std::numeric_limits<double>::infinity();
  for (int j = 0; j < trace::kNumJoints; ++j) {
    if (line.dq_ds_max(j) > 0.0 && limits.max_velocity(j) > 0.0) {
      v = std::min(v, limits.max_velocity(j) / line.dq_ds_max(j));
    }
  }
  return std::isfinite(v) ? v : 0.0;
}

// 7. Random programmes, limits and windows: no axis beyond its speed limit, nor on the ramps
// beyond its acceleration limit; every ramp fits its line; both lines of a junction pass it
// at the same fraction of their cruise, and each axis' velocity jump there, f D_j spread over
// t_b = min(T_mid / f, ramp), stays within its acceleration limit; no line beats its
// programmed time; the stops the mode, stop_after and dwell ask for are there.
TEST(TimeLawTest, RandomProgrammesRespectEveryLimit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int run = 0; run < 40; ++run) {
    AxisLimits limits;
    for (int j = 0; j < trace::kNumJoints; ++j) {
      limits.max_velocity(j) = unit(rng) < 0.1 ? 0.0 : 0.5 + 2.5 * unit(rng);
      limits.max_acceleration(j) = unit(rng) < 0.1 ? 0.0 : 0.5 + 9.5 * unit(rng);
    }
    TimeLawOptions options;
    options.ramp_time_s = 0.05 + 0.5 * unit(rng);
    options.continuous = run % 5 != 4;
    options.look_ahead_lines = std::vector<int>{1, 2, 5, 64}[run % 4];
    std::vector<TimedLineInput> lines;
    for (int i = 0; i < 150; ++i) lines.push_back(RandomLine(rng, i + 1));
    const std::vector<LineProfile> p = Plan(limits, options, lines);
    ASSERT_EQ(p.size(), lines.size());
    std::vector<double> cruise(lines.size());
    for (std::size_t k = 0; k < lines.size(); ++k) {
      const TimedLineInput& line = lines[k];
      const LineProfile& q = p[k];
      cruise[k] = ExpectedCruise(limits, line);
      EXPECT_EQ(q.source_line, line.source_line);
      EXPECT_NEAR(q.duration_s, q.t_accel + q.t_cruise + q.t_decel + q.dwell_s, 1e-12);
      EXPECT_EQ(q.dwell_s, line.dwell_s);
      if (cruise[k] == 0.0) {
        EXPECT_EQ(q.duration_s, line.dwell_s) << run << " line " << k;
        continue;
      }
      EXPECT_LE(q.v_cruise, cruise[k] * (1.0 + 1e-12)) << run << " line " << k;
      EXPECT_LE(q.v_in, q.v_cruise * (1.0 + 1e-12));
      EXPECT_LE(q.v_out, q.v_cruise * (1.0 + 1e-12));
      EXPECT_LE(std::abs(q.v_out * q.v_out - q.v_in * q.v_in), 2.0 * q.accel * (1.0 + 1e-12));
      EXPECT_LE(q.accel, cruise[k] / options.ramp_time_s * (1.0 + 1e-12));
      EXPECT_GE(q.t_accel + q.t_cruise + q.t_decel, line.programmed_duration_s - 1e-12);
      for (int j = 0; j < trace::kNumJoints; ++j) {
        if (limits.max_velocity(j) > 0.0) {
          EXPECT_LE(line.dq_ds_max(j) * q.v_cruise, limits.max_velocity(j) * (1.0 + 1e-12));
        }
        if (limits.max_acceleration(j) > 0.0) {
          EXPECT_LE(line.dq_ds_max(j) * q.accel, limits.max_acceleration(j) * (1.0 + 1e-12));
        }
      }
    }
    EXPECT_EQ(p.front().v_in, 0.0);
    EXPECT_EQ(p.back().v_out, 0.0);
    for (std::size_t k = 0; k + 1 < lines.size(); ++k) {
      const TimedLineInput& a = lines[k];
      const TimedLineInput& b = lines[k + 1];
      if (cruise[k] == 0.0 || cruise[k + 1] == 0.0) {
        EXPECT_EQ(p[k].v_out, 0.0);
        EXPECT_EQ(p[k + 1].v_in, 0.0);
        continue;
      }
      const double f = p[k].v_out / cruise[k];
      EXPECT_NEAR(p[k + 1].v_in / cruise[k + 1], f, 1e-12) << run << " junction " << k;
      if (!options.continuous || a.stop_after || a.dwell_s > 0.0 || options.look_ahead_lines == 1) {
        EXPECT_EQ(f, 0.0) << run << " junction " << k;
      }
      if (f == 0.0) continue;
      const double t_mid = (1.0 / cruise[k] + 1.0 / cruise[k + 1]) / 2.0;
      const double t_blend = std::min(t_mid / f, options.ramp_time_s);
      for (int j = 0; j < trace::kNumJoints; ++j) {
        if (!(limits.max_acceleration(j) > 0.0)) continue;
        const double jump = std::abs(a.dq_ds_end(j) * cruise[k] - b.dq_ds_start(j) * cruise[k + 1]);
        EXPECT_LE(f * jump / t_blend, limits.max_acceleration(j) * (1.0 + 1e-9))
            << run << " junction " << k << " joint " << j;
      }
    }
  }
}

}  // namespace
}  // namespace stitchsim::sim
