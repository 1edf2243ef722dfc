#pragma once
// The dynamic mode (`verify --dynamics`): a TraceSink behind the timing sink that steps
// MuJoCo's physics with the position servos tracking the timed trajectory (mujoco_cell.h,
// StepTo), and hands on every sample with the tool where the arm actually is: the command's
// pose with the servo's lag applied (the lag measured between the physics pose and the
// reference pose at the same time). The needle rules downstream then see the arm's lag, and
// dyn.tracking reports it.

#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/trace.h"

namespace stitchsim::sim {

struct DynamicsFigures {
  long samples = 0;           ///< samples tracked
  double simulated_s = 0.0;   ///< physics time stepped
  double max_error_mm = 0.0;  ///< largest tool point lag
  int max_error_line = 0;     ///< its line
};

class DynamicsSink final : public TraceSink {
 public:
  /// `physics` steps (its own working state); `kinematics` (another state on the same model,
  /// MujocoCell::Share) poses the reference and the actual joints. All must outlive the sink.
  DynamicsSink(MujocoCell& physics, MujocoCell& kinematics, TraceSink& next);
  void OnLine(const LineRecord& line) override;
  void OnSample(const TraceSample& sample) override;
  const DynamicsFigures& Figures() const { return figures_; }

 private:
  MujocoCell& physics_;
  MujocoCell& kinematics_;
  TraceSink& next_;
  bool started_ = false;
  double t0_ = 0.0;  ///< timed time of the first tracked sample (physics time 0)
  double line_start_s_ = 0.0, line_duration_s_ = 0.0;  ///< the current line, timed
  JointVector last_q_ = JointVector::Zero(), last_qd_ = JointVector::Zero();
  DynamicsFigures figures_;
};

}  // namespace stitchsim::sim
