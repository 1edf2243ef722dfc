#include "stitchsim/sim/dynamics.h"

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"

namespace stitchsim::sim {

DynamicsSink::DynamicsSink(MujocoCell& physics, MujocoCell& kinematics, TraceSink& next)
    : physics_(physics), kinematics_(kinematics), next_(next) {}

void DynamicsSink::OnLine(const LineRecord& line) {
  // The previous line's dwell (a settle after a rotation): the arm holds its last reference
  // until this line starts (nothing to do after a blended junction: no time passes).
  line_start_s_ += line_duration_s_;
  line_duration_s_ = line.timed_duration_s;
  if (started_) physics_.StepTo(line_start_s_ - t0_, last_q_, last_qd_);
  next_.OnLine(line);
}

void DynamicsSink::OnSample(const TraceSample& sample) {
  if (!sample.has_timing || !trace::JointsUsable(sample)) {
    next_.OnSample(sample);  // nothing to track against: the command stands
    return;
  }
  if (!started_) {
    physics_.ResetPhysics(sample.joints);
    t0_ = sample.timed_s;
    started_ = true;
  }
  physics_.StepTo(sample.timed_s - t0_, sample.joints, sample.joint_velocities);
  last_q_ = sample.joints;
  last_qd_ = sample.joint_velocities;
  // The lag at the physics time, in the tool frame: reference pose -> actual pose.
  kinematics_.SetJoints(physics_.ReferenceNow());
  const Eigen::Isometry3d reference = kinematics_.ToolInPartMm();
  kinematics_.SetJoints(physics_.PhysicsJoints());
  const Eigen::Isometry3d actual = kinematics_.ToolInPartMm();
  const Eigen::Isometry3d lag = reference.inverse() * actual;
  TraceSample s = sample;
  s.tool_part = sample.tool_part * lag;
  s.tracked = true;
  s.tracking_error_mm = lag.translation().norm();
  s.tracking_error_deg =
      geom::AngleBetween(Eigen::Matrix3d::Identity(), lag.linear()) * 180.0 / kPi;
  ++figures_.samples;
  figures_.simulated_s = physics_.PhysicsTime();
  if (s.tracking_error_mm > figures_.max_error_mm) {
    figures_.max_error_mm = s.tracking_error_mm;
    figures_.max_error_line = s.source_line;
  }
  next_.OnSample(s);
}

}  // namespace stitchsim::sim
