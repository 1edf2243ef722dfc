#include "stitchsim/sim/timing.h"

#include <algorithm>
#include <cmath>

#include "stitchsim/geom/rotation.h"

namespace stitchsim::sim {

AxisLimits AxisLimitsOf(const RobotModel& robot) {
  AxisLimits limits;
  limits.max_velocity = robot.max_velocities();
  limits.max_acceleration = robot.max_accelerations();
  return limits;
}

TimingSink::TimingSink(MujocoCell& mujoco, const RobotModel& robot, const TimingOptions& options,
                       TraceSink& next)
    : mujoco_(mujoco),
      limits_(AxisLimitsOf(robot)),
      options_(options),
      next_(next),
      planner_(limits_, options.law) {}

void TimingSink::OnLine(const LineRecord& line) {
  if (open_) CloseLine();
  if (spare_.empty()) {
    lines_.emplace_back();
  } else {
    lines_.push_back(std::move(spare_.back()));
    spare_.pop_back();
  }
  Line& l = lines_.back();
  l.samples.clear();
  l.node_s.clear();
  l.node_q.clear();
  l.planned = false;
  l.transparent = false;
  l.rec = line;
  if (have_joints_) {
    l.node_s.push_back(0.0);
    l.node_q.push_back(last_joints_);
  }
  open_ = true;
}

void TimingSink::OnSample(const TraceSample& sample) {
  Line& l = lines_.back();
  l.samples.push_back(sample);
  if (!trace::JointsUsable(sample)) return;
  const double s = sample.line_fraction;
  if (!l.node_s.empty() && s <= l.node_s.back() + 1e-15) {
    l.node_q.back() = sample.joints;  // the line's own start sample replaces the carried node
  } else {
    l.node_s.push_back(s);
    l.node_q.push_back(sample.joints);
  }
  last_joints_ = sample.joints;
  have_joints_ = true;
}

void TimingSink::Finish() {
  if (open_) CloseLine();
  open_ = false;
  planner_.Flush();
  PopPlanned();
  while (!lines_.empty() && lines_.front().planned) {
    const std::size_t k = NextMoving(0);
    Emit(lines_.front(), k < lines_.size() && lines_[k].planned ? &lines_[k] : nullptr);
    Recycle();
  }
}

std::size_t TimingSink::NextMoving(std::size_t k) const {
  for (std::size_t i = k + 1; i < lines_.size(); ++i) {
    if (!lines_[i].transparent) return i;
  }
  return lines_.size();
}

// dq/ds at each node: one-sided at the ends, the three-point weighted slope inside; d2q/ds2
// from the neighbouring slopes (0 with fewer than three nodes).
void TimingSink::Derivatives(Line& l) {
  const std::size_t n = l.node_s.size();
  l.node_dq.assign(n, JointVector::Zero());
  l.node_ddq.assign(n, JointVector::Zero());
  if (n < 2) return;
  std::vector<JointVector> slope(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    slope[k] = (l.node_q[k + 1] - l.node_q[k]) / (l.node_s[k + 1] - l.node_s[k]);
  }
  l.node_dq[0] = slope[0];
  l.node_dq[n - 1] = slope[n - 2];
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double h0 = l.node_s[k] - l.node_s[k - 1], h1 = l.node_s[k + 1] - l.node_s[k];
    l.node_dq[k] = (h1 * slope[k - 1] + h0 * slope[k]) / (h0 + h1);
    l.node_ddq[k] = 2.0 * (slope[k] - slope[k - 1]) / (h0 + h1);
  }
  if (n >= 3) {
    l.node_ddq[0] = l.node_ddq[1];
    l.node_ddq[n - 1] = l.node_ddq[n - 2];
  }
}

TimedLineInput TimingSink::InputOf(const Line& l) const {
  TimedLineInput in;
  const LineRecord& r = l.rec;
  in.source_line = r.source_line;
  // The executor's settle time after a pure rotation is a dwell, not motion.
  const bool advancing = r.drive_to_mm - r.drive_from_mm > 1e-12;
  const double dist = (r.to.translation() - r.from.translation()).norm();
  const double angle = geom::AngleBetween(r.from.linear(), r.to.linear());
  if (!advancing && dist <= 1e-9 && angle > 1e-12) in.dwell_s = options_.settle_time_s;
  in.programmed_duration_s = std::max(0.0, r.duration_s - in.dwell_s);
  in.stop_after = in.dwell_s > 0.0 || r.over_sample_limit;
  const std::size_t n = l.node_s.size();
  if (n >= 2) {
    in.dq_ds_start = l.node_dq.front();
    in.dq_ds_end = l.node_dq.back();
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const JointVector chord =
          ((l.node_q[k + 1] - l.node_q[k]) / (l.node_s[k + 1] - l.node_s[k])).cwiseAbs();
      in.dq_ds_max = in.dq_ds_max.cwiseMax(chord);
    }
    for (const JointVector& ddq : l.node_ddq)
      in.d2q_ds2_max = in.d2q_ds2_max.cwiseMax(ddq.cwiseAbs());
  }
  return in;
}

void TimingSink::CloseLine() {
  Line& l = lines_.back();
  Derivatives(l);
  l.input = InputOf(l);
  open_ = false;
  const TimedLineInput& in = l.input;
  l.transparent = !(in.programmed_duration_s > 0.0) && in.dq_ds_max.isZero(0.0) &&
                  !(in.dwell_s > 0.0) && !in.stop_after;
  if (l.transparent) {
    l.profile = LineProfile{};
    l.profile.source_line = in.source_line;
    l.planned = true;
  } else {
    planner_.Push(in);
  }
  PopPlanned();
}

void TimingSink::PopPlanned() {
  LineProfile p;
  while (planner_.Pop(p)) {
    for (Line& l : lines_) {
      if (l.planned) continue;
      l.profile = p;
      l.planned = true;
      break;
    }
  }
  // A line goes out once the next line that moves is planned too (the line's end sample
  // carries the junction with it).
  while (!lines_.empty() && lines_[0].planned) {
    const std::size_t k = NextMoving(0);
    if (k >= lines_.size() || !lines_[k].planned) break;
    Emit(lines_[0], &lines_[k]);
    Recycle();
  }
}

void TimingSink::Recycle() {
  spare_.push_back(std::move(lines_.front()));
  lines_.pop_front();
}

void TimingSink::Emit(Line& l, const Line* next) {
  l.rec.timed_duration_s = l.profile.duration_s;
  emitting_ = &l.profile;
  next_.OnLine(l.rec);
  emitting_ = nullptr;
  for (TraceSample& s : l.samples) {
    TimeSample(l, next, s);
    next_.OnSample(s);
  }
  line_start_s_ += l.profile.duration_s;
  cycle_time_.Add(l.profile.duration_s);
}

namespace {

template <typename T>
void Put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

std::string TimingSink::InputCarry() const {
  std::string out;
  Put(out, have_joints_);
  Put(out, last_joints_);
  return out;
}

std::string TimingSink::OutputCarry() const {
  std::string out;
  Put(out, carry_velocities_);
  Put(out, carry_accelerations_);
  if (emitting_ != nullptr) {
    const LineProfile& p = *emitting_;
    for (double v : {p.v_in, p.v_cruise, p.v_out, p.accel, p.t_accel, p.t_cruise, p.t_decel,
                     p.duration_s, p.v_nominal}) {
      Put(out, v);
    }
  }
  return out;
}

namespace {

// Linear interpolation of node values at fraction s.
JointVector AtFraction(const std::vector<double>& node_s, const std::vector<JointVector>& v,
                       double s) {
  if (v.empty()) return JointVector::Zero();
  if (s <= node_s.front()) return v.front();
  if (s >= node_s.back()) return v.back();
  const auto it = std::upper_bound(node_s.begin(), node_s.end(), s);
  const std::size_t k = static_cast<std::size_t>(it - node_s.begin());
  const double f = (s - node_s[k - 1]) / (node_s[k] - node_s[k - 1]);
  return v[k - 1] + f * (v[k] - v[k - 1]);
}

}  // namespace

void TimingSink::TimeSample(const Line& l, const Line* next, TraceSample& s) {
  const PathState st = StateAtFraction(l.profile, s.line_fraction);
  s.has_timing = true;
  s.timed_s = line_start_s_ + st.t;
  if (!trace::JointsUsable(s)) return;
  if (l.transparent) {  // passed through at the pace of the lines around it
    s.joint_velocities = carry_velocities_;
    s.joint_accelerations = carry_accelerations_;
    if (options_.torques && !s.collision_probe) {
      s.joint_torques =
          mujoco_.InverseDynamics(s.joints, s.joint_velocities, s.joint_accelerations);
    }
    return;
  }
  const JointVector dq = AtFraction(l.node_s, l.node_dq, s.line_fraction);
  const JointVector ddq = AtFraction(l.node_s, l.node_ddq, s.line_fraction);
  s.joint_velocities = dq * st.s_dot;
  s.joint_accelerations = ddq * st.s_dot * st.s_dot + dq * st.s_ddot;
  // A blended junction: the velocity turns from this line's to the next one's within the
  // blend time the time law allowed for it (time_law.h, JunctionBlendTime).
  if (next != nullptr && s.line_fraction >= 1.0 && l.profile.v_out > 0.0 &&
      !next->node_dq.empty() && !l.node_dq.empty()) {
    const JointVector before = l.node_dq.back() * l.profile.v_out;
    const JointVector after = next->node_dq.front() * next->profile.v_in;
    const double t_blend = JunctionBlendTime(l.profile.v_nominal, next->profile.v_nominal,
                                             l.profile.v_out / l.profile.v_nominal, options_.law);
    if (t_blend > 0.0) s.joint_accelerations = (after - before) / t_blend;
  }
  if (options_.torques && !s.collision_probe) {
    s.joint_torques = mujoco_.InverseDynamics(s.joints, s.joint_velocities, s.joint_accelerations);
  }
  carry_velocities_ = s.joint_velocities;
  carry_accelerations_ = s.joint_accelerations;
}

}  // namespace stitchsim::sim
