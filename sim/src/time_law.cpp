#include "stitchsim/sim/time_law.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace stitchsim::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Time to cover distance d from speed v at acceleration +acc (acc may be negative), the first
// root of v t + acc t^2 / 2 = d, in the form that stays exact when acc is 0 or v is 0.
double TimeToCover(double v, double acc, double d) {
  if (d <= 0.0) return 0.0;
  const double root = std::sqrt(std::max(0.0, v * v + 2.0 * acc * d));
  const double sum = v + root;
  return sum > 0.0 ? 2.0 * d / sum : 0.0;
}

}  // namespace

LineProfile MakeProfile(int source_line, double v_in, double v_cruise, double v_out, double accel,
                        double dwell_s) {
  LineProfile p;
  p.source_line = source_line;
  p.dwell_s = std::max(0.0, dwell_s);
  if (!(v_cruise > 0.0) || !(accel > 0.0)) {  // no motion: the dwell alone
    p.duration_s = p.dwell_s;
    return p;
  }
  v_in = std::clamp(v_in, 0.0, v_cruise);
  v_out = std::clamp(v_out, 0.0, v_cruise);
  assert(std::abs(v_out * v_out - v_in * v_in) <= 2.0 * accel * (1.0 + 1e-9) + 1e-12);
  p.v_in = v_in;
  p.v_out = v_out;
  p.accel = accel;
  const double s_accel = (v_cruise * v_cruise - v_in * v_in) / (2.0 * accel);
  const double s_decel = (v_cruise * v_cruise - v_out * v_out) / (2.0 * accel);
  double peak = v_cruise;
  double s_cruise = 1.0 - s_accel - s_decel;
  if (s_cruise < 0.0) {  // the ramps do not fit in s = 1: a triangle
    peak = std::sqrt((2.0 * accel + v_in * v_in + v_out * v_out) / 2.0);
    peak = std::clamp(peak, std::max(v_in, v_out), v_cruise);  // rounding only
    s_cruise = 0.0;
  }
  p.v_cruise = peak;
  p.t_accel = (peak - v_in) / accel;
  p.t_decel = (peak - v_out) / accel;
  p.t_cruise = s_cruise / peak;
  p.duration_s = p.t_accel + p.t_cruise + p.t_decel + p.dwell_s;
  return p;
}

PathState StateAtTime(const LineProfile& p, double t) {
  PathState state;
  state.t = std::clamp(t, 0.0, p.duration_s);
  const double t_motion = p.t_accel + p.t_cruise + p.t_decel;
  if (p.v_cruise <= 0.0 || state.t >= t_motion) {  // motion done (or none): s = 1
    state.s = 1.0;
    state.s_dot = p.v_cruise > 0.0 && state.t <= t_motion ? p.v_out : 0.0;  // 0 in the dwell
    return state;
  }
  const double s_accel = p.t_accel * (p.v_in + p.v_cruise) / 2.0;
  const double s_cruise = p.t_cruise * p.v_cruise;
  if (state.t < p.t_accel) {
    const double tau = state.t;
    state.s = p.v_in * tau + p.accel * tau * tau / 2.0;
    state.s_dot = p.v_in + p.accel * tau;
    state.s_ddot = p.accel;
  } else if (state.t < p.t_accel + p.t_cruise) {
    state.s = s_accel + p.v_cruise * (state.t - p.t_accel);
    state.s_dot = p.v_cruise;
  } else {
    const double tau = state.t - p.t_accel - p.t_cruise;
    state.s = s_accel + s_cruise + p.v_cruise * tau - p.accel * tau * tau / 2.0;
    state.s_dot = p.v_cruise - p.accel * tau;
    state.s_ddot = -p.accel;
  }
  state.s = std::clamp(state.s, 0.0, 1.0);
  return state;
}

PathState StateAtFraction(const LineProfile& p, double s) {
  s = std::clamp(s, 0.0, 1.0);
  const double t_motion = p.t_accel + p.t_cruise + p.t_decel;
  if (p.v_cruise <= 0.0 || s >= 1.0) {
    PathState state;
    state.t = t_motion;
    state.s = 1.0;
    state.s_dot = p.v_cruise > 0.0 ? p.v_out : 0.0;
    return state;
  }
  const double s_accel = p.t_accel * (p.v_in + p.v_cruise) / 2.0;
  const double s_cruise = p.t_cruise * p.v_cruise;
  PathState state;
  state.s = s;
  if (s < s_accel) {
    const double tau = TimeToCover(p.v_in, p.accel, s);
    state.t = std::min(tau, p.t_accel);
    state.s_dot = p.v_in + p.accel * state.t;
    state.s_ddot = p.accel;
  } else if (s < s_accel + s_cruise) {
    state.t = p.t_accel + (s - s_accel) / p.v_cruise;
    state.s_dot = p.v_cruise;
  } else {
    const double tau =
        std::min(TimeToCover(p.v_cruise, -p.accel, s - s_accel - s_cruise), p.t_decel);
    state.t = p.t_accel + p.t_cruise + tau;
    state.s_dot = p.v_cruise - p.accel * tau;
    state.s_ddot = p.t_decel > 0.0 ? -p.accel : 0.0;
  }
  return state;
}

TimeLawPlanner::TimeLawPlanner(const AxisLimits& limits, const TimeLawOptions& options)
    : limits_(limits), options_(options) {
  assert(options_.ramp_time_s > 0.0);
  assert(options_.look_ahead_lines >= 1);
  options_.look_ahead_lines = std::max(1, options_.look_ahead_lines);
}

TimeLawPlanner::HeldLine TimeLawPlanner::Prepare(const TimedLineInput& line) const {
  HeldLine held;
  held.input = line;
  double v_cruise = line.programmed_duration_s > 0.0 ? 1.0 / line.programmed_duration_s : kInf;
  double accel_axes = kInf;
  for (int j = 0; j < trace::kNumJoints; ++j) {
    const double dq = std::abs(line.dq_ds_max(j));
    if (!(dq > 0.0)) continue;
    if (limits_.max_velocity(j) > 0.0) v_cruise = std::min(v_cruise, limits_.max_velocity(j) / dq);
    // A curved joint path: the curvature term d2q/ds2 sdot^2 may take at most half of the
    // axis' acceleration, the ramps the rest (below).
    const double ddq = std::abs(line.d2q_ds2_max(j));
    if (limits_.max_acceleration(j) > 0.0 && ddq > 0.0) {
      v_cruise = std::min(v_cruise, std::sqrt(0.5 * limits_.max_acceleration(j) / ddq));
    }
  }
  for (int j = 0; j < trace::kNumJoints; ++j) {
    const double dq = std::abs(line.dq_ds_max(j));
    if (!(dq > 0.0) || !(limits_.max_acceleration(j) > 0.0)) continue;
    const double curvature = std::abs(line.d2q_ds2_max(j)) * v_cruise * v_cruise;
    accel_axes = std::min(accel_axes, (limits_.max_acceleration(j) - curvature) / dq);
  }
  // No motion, or nothing bounds the speed (no programmed time, no limit on a moving axis):
  // the line takes no time.
  if (!std::isfinite(v_cruise) || !(v_cruise > 0.0)) return held;
  held.moves = true;
  held.v_cruise = v_cruise;
  held.accel = std::min(v_cruise / options_.ramp_time_s, accel_axes);
  return held;
}

double JunctionBlendTime(double v_nominal_a, double v_nominal_b, double fraction,
                         const TimeLawOptions& options) {
  if (!(v_nominal_a > 0.0 && v_nominal_b > 0.0 && fraction > 0.0)) return 0.0;
  const double t_mid = (1.0 / v_nominal_a + 1.0 / v_nominal_b) / 2.0;
  return std::min(t_mid / fraction, options.ramp_time_s);
}

double TimeLawPlanner::JunctionBound(const HeldLine& a, const HeldLine& b) const {
  if (!options_.continuous || a.input.stop_after || a.input.dwell_s > 0.0 || !a.moves || !b.moves) {
    return 0.0;
  }
  const double t_mid = (1.0 / a.v_cruise + 1.0 / b.v_cruise) / 2.0;
  double f = 1.0;
  for (int j = 0; j < trace::kNumJoints; ++j) {
    const double amax = limits_.max_acceleration(j);
    if (!(amax > 0.0)) continue;
    const double jump =
        std::abs(a.input.dq_ds_end(j) * a.v_cruise - b.input.dq_ds_start(j) * b.v_cruise);
    if (!(jump > 0.0)) continue;
    f = std::min({f, std::sqrt(amax * t_mid / jump), amax * options_.ramp_time_s / jump});
  }
  return f;
}

void TimeLawPlanner::Push(const TimedLineInput& line) {
  if (window_.size() >= static_cast<std::size_t>(options_.look_ahead_lines)) FixOldest();
  HeldLine held = Prepare(line);
  if (!window_.empty()) window_.back().junction_max = JunctionBound(window_.back(), held);
  window_.push_back(held);
}

void TimeLawPlanner::Flush() {
  while (!window_.empty()) FixOldest();
  entry_fraction_ = 0.0;
}

bool TimeLawPlanner::Pop(LineProfile& out) {
  if (ready_.empty()) return false;
  out = ready_.front();
  ready_.pop_front();
  return true;
}

std::size_t TimeLawPlanner::Pending() const { return window_.size(); }

void TimeLawPlanner::FixOldest() {
  assert(!window_.empty());
  // Backward pass from the window's end, where the last held line is assumed to stop: the
  // largest fraction at each junction from which every later held line can still brake.
  double exit_fraction = 0.0;  // at the exit of window_[k], walking k down to 0
  for (std::size_t k = window_.size() - 1; k > 0; --k) {
    const HeldLine& line = window_[k];
    double entry_fraction = 0.0;
    if (line.moves) {
      const double v_out = exit_fraction * line.v_cruise;
      entry_fraction = std::sqrt(v_out * v_out + 2.0 * line.accel) / line.v_cruise;
    }
    exit_fraction = std::min({1.0, entry_fraction, window_[k - 1].junction_max});
  }
  const HeldLine oldest = window_.front();
  window_.pop_front();
  if (window_.empty()) exit_fraction = 0.0;  // the last held line ends at rest
  LineProfile profile;
  if (oldest.moves) {
    // Forward pass from the fixed entry speed.
    const double v_in = entry_fraction_ * oldest.v_cruise;
    const double v_out_max = std::sqrt(v_in * v_in + 2.0 * oldest.accel);
    const double v_out = std::min(exit_fraction * oldest.v_cruise, v_out_max);
    exit_fraction = v_out / oldest.v_cruise;
    profile = MakeProfile(oldest.input.source_line, v_in, oldest.v_cruise, v_out, oldest.accel,
                          oldest.input.dwell_s);
    profile.v_nominal = oldest.v_cruise;
  } else {
    exit_fraction = 0.0;
    profile = MakeProfile(oldest.input.source_line, 0.0, 0.0, 0.0, 0.0, oldest.input.dwell_s);
  }
  entry_fraction_ = exit_fraction;
  ready_.push_back(profile);
}

}  // namespace stitchsim::sim
