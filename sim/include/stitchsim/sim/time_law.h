#pragma once
// The controller's time law (docs/timing.md): per programme line, the path speed sdot = ds/dt
// along the line parameter s in [0, 1], planned as a controller does it: a cruise speed capped
// by the programmed feed and every axis' speed limit, trapezoidal ramps at an acceleration set
// by the controller's ramp time and capped by every axis, continuous-path blending at the
// junctions (or exact stops), and a bounded look-ahead window. Pure: Eigen only.

#include <cstddef>
#include <deque>

#include "stitchsim/trace/joints.h"

namespace stitchsim::sim {

using trace::JointVector;

/// How the controller plans (assumed defaults: docs/timing.md, "Assumptions").
struct TimeLawOptions {
  double ramp_time_s = 0.25;  ///< the controller's acceleration ramp at the programmed speed (s)
  bool continuous = true;     ///< continuous-path blending (G64); false: exact stop (G61)
  int look_ahead_lines = 64;  ///< lines the controller plans ahead (>= 1; 1: stop on every line)
};

/// Axis limits in model order (trace::JointVector): rail in m, the other joints in rad.
struct AxisLimits {
  JointVector max_velocity = JointVector::Zero();      ///< m/s or rad/s; 0 = unlimited
  JointVector max_acceleration = JointVector::Zero();  ///< m/s^2 or rad/s^2; 0 = unlimited
};

/// What the time law needs of one line (joint units, m or rad, per unit of the line parameter s).
/// Filled by the executor from the line's interpolated joints.
struct TimedLineInput {
  int source_line = 0;                 ///< programme line number (carried to the profile)
  double programmed_duration_s = 0.0;  ///< today's estimate at the programmed feed, no dwell (s)
  double dwell_s = 0.0;                ///< at rest after the motion (settle time, s)
  bool stop_after = false;             ///< exact stop at its end whatever the mode
  JointVector dq_ds_start = JointVector::Zero();  ///< dq/ds at s = 0 (m or rad)
  JointVector dq_ds_end = JointVector::Zero();    ///< dq/ds at s = 1 (m or rad)
  JointVector dq_ds_max = JointVector::Zero();    ///< max |dq/ds| over the line, per joint
  /// max |d2q/ds2| over the line, per joint: a curved joint path (a wrist turning fast near a
  /// singularity) needs acceleration even at constant sdot; 0 = straight in joint space.
  JointVector d2q_ds2_max = JointVector::Zero();
};

/// The planned motion of one line: s(t) on [0, duration_s]. A line without motion has all
/// speeds 0 and only its dwell.
struct LineProfile {
  int source_line = 0;    ///< programme line number (from TimedLineInput)
  double v_in = 0;        ///< sdot at entry (1/s)
  double v_cruise = 0;    ///< sdot on the cruise, or the triangle's peak (1/s)
  double v_nominal = 0;   ///< the line's cruise limit v_c (junction fractions refer to it; 1/s)
  double v_out = 0;       ///< sdot at exit (1/s)
  double accel = 0;       ///< |sddot| on the ramps (1/s^2)
  double t_accel = 0;     ///< ramp from v_in to v_cruise (s)
  double t_cruise = 0;    ///< at v_cruise (s)
  double t_decel = 0;     ///< ramp from v_cruise to v_out (s)
  double dwell_s = 0;     ///< at rest after the motion (s)
  double duration_s = 0;  ///< t_accel + t_cruise + t_decel + dwell_s (s)
};

/// The path state of a line at one instant.
struct PathState {
  double t = 0;       ///< time since the line's start (s)
  double s = 0;       ///< line parameter in [0, 1]
  double s_dot = 0;   ///< ds/dt (1/s)
  double s_ddot = 0;  ///< d2s/dt2 (1/s^2): the ramp's, 0 on cruise and dwell
};

/// Evaluate at time t in [0, duration] (clamped to it).
PathState StateAtTime(const LineProfile& p, double t);

/// The inverse: the (first) time the line reaches fraction s (clamped to [0, 1]) and the state
/// there. At s = 1 the time is the end of the motion (before the dwell).
PathState StateAtFraction(const LineProfile& p, double s);

/// The trapezoid from v_in to v_out via v_cruise at +-accel over s = 1, or the triangle with
/// peak sqrt((2 accel + v_in^2 + v_out^2) / 2) when the ramps do not fit; then dwell_s at rest.
/// Expects 0 <= v_in, v_out <= v_cruise, accel > 0, |v_out^2 - v_in^2| <= 2 accel, and v_out = 0
/// when dwell_s > 0 (the dwell is at rest).
/// v_cruise <= 0 makes a line without motion (only the dwell).
LineProfile MakeProfile(int source_line, double v_in, double v_cruise, double v_out, double accel,
                        double dwell_s);

/// The time over which a blended junction turns the joint velocities from one line's to the
/// next's (s): min(T_mid / f, ramp_time) with T_mid = (1/v_c_a + 1/v_c_b) / 2 and f the
/// fraction of cruise the junction is passed at; the planner keeps every axis' velocity jump
/// over this time within its acceleration limit.
double JunctionBlendTime(double v_nominal_a, double v_nominal_b, double fraction,
                         const TimeLawOptions& options);

/// A streaming planner: lines go in in programme order, final profiles come out in the same
/// order once they leave the look-ahead window (or on Flush). Holds at most look_ahead_lines
/// lines; O(look_ahead_lines) per line.
class TimeLawPlanner {
 public:
  TimeLawPlanner(const AxisLimits& limits, const TimeLawOptions& options);
  /// Adds the next line in programme order; when the window is full the oldest line's profile
  /// is fixed first (planned with the held lines, the last of them ending at rest).
  void Push(const TimedLineInput& line);
  /// Programme end: every held line is fixed, the last one ends at rest. Pushing after Flush
  /// starts again from rest.
  void Flush();
  /// The oldest line whose profile is final (left the window, or flushed); false if none yet.
  bool Pop(LineProfile& out);
  /// Lines held in the look-ahead window (not yet final).
  std::size_t Pending() const;

 private:
  // One held line: its speeds and the bound on the junction with its successor.
  struct HeldLine {
    TimedLineInput input;
    bool moves = false;         // false: no motion (duration 0 plus its dwell)
    double v_cruise = 0.0;      // 1/s
    double accel = 0.0;         // 1/s^2
    double junction_max = 0.0;  // largest fraction f at the junction with the next line
  };

  HeldLine Prepare(const TimedLineInput& line) const;
  double JunctionBound(const HeldLine& a, const HeldLine& b) const;
  void FixOldest();

  AxisLimits limits_;
  TimeLawOptions options_;
  std::deque<HeldLine> window_;    // oldest first
  std::deque<LineProfile> ready_;  // final profiles not yet popped
  double entry_fraction_ = 0.0;    // f at the oldest held line's entry (0: at rest)
};

}  // namespace stitchsim::sim
