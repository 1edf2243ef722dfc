#pragma once
// The timed trajectory: a TraceSink between the executor and its consumers that plans each
// line on the controller's time law (time_law.h: acceleration ramps, axis limits, blending,
// look-ahead), then gives every sample its time on it and, where the joints are solved, the
// joint velocities, accelerations and the torques MuJoCo's inverse dynamics needs for them.
// It holds the lines of the look-ahead window (bounded memory) and forwards them in order.

#include <deque>
#include <string>
#include <vector>

#include "stitchsim/common/exact_sum.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/time_law.h"
#include "stitchsim/sim/trace.h"

namespace stitchsim::sim {

struct TimingOptions {
  TimeLawOptions law;
  /// Dwell after a pure rotation line (the executor's settle time): at rest, no motion.
  double settle_time_s = 0.15;
  /// Compute the torques (mj_inverse at every sample with joints); false: velocities and
  /// accelerations only.
  bool torques = true;
};

/// The limits the time law honours: the URDF's speeds and accelerations.
AxisLimits AxisLimitsOf(const RobotModel& robot);

class TimingSink final : public TraceSink {
 public:
  /// `mujoco` (for the torques) and `next` must outlive the sink.
  TimingSink(MujocoCell& mujoco, const RobotModel& robot, const TimingOptions& options,
             TraceSink& next);
  void OnLine(const LineRecord& line) override;
  void OnSample(const TraceSample& sample) override;
  /// The programme has ended: plans the last lines (ending at rest) and forwards everything.
  void Finish();
  /// Cycle time on the time law (s): the sum of the lines' timed durations so far forwarded
  /// (summed exactly: chunked runs add their parts to the same value).
  double CycleTime() const { return cycle_time_.Value(); }
  /// Chunked runs (chunk.h): what the sink carries into the next line it takes in (the last
  /// solved joints), and into the next line it hands on (the carried joint rates and the
  /// profile of the line being handed on, read in the next sink's OnLine), as bytes.
  std::string InputCarry() const;
  std::string OutputCarry() const;

 private:
  struct Line {
    LineRecord rec;
    std::vector<TraceSample> samples;
    // Joint nodes of the line (s, q): the previous line's last solved joints at s = 0, then
    // every usable solved sample; their derivatives dq/ds and d2q/ds2 at each node.
    std::vector<double> node_s;
    std::vector<JointVector> node_q, node_dq, node_ddq;
    TimedLineInput input;
    LineProfile profile;
    bool planned = false;
    /// No motion, no dwell, no stop (a block that repeats the pose, e.g. a decoupled
    /// programme's rotation line where the path does not turn): the controller passes through
    /// it, so it does not go to the planner and the junction is between its neighbours.
    bool transparent = false;
  };
  std::size_t NextMoving(std::size_t k) const;  ///< first non-transparent line after k
  void CloseLine();
  void PopPlanned();
  void Emit(Line& line, const Line* next);
  void Recycle();  ///< the front line, handed on, to the spares
  void Derivatives(Line& line);
  TimedLineInput InputOf(const Line& line) const;
  void TimeSample(const Line& line, const Line* next, TraceSample& s);

  MujocoCell& mujoco_;
  AxisLimits limits_;
  TimingOptions options_;
  TraceSink& next_;
  TimeLawPlanner planner_;
  std::deque<Line> lines_;   ///< pushed, in programme order; front may be planned
  std::vector<Line> spare_;  ///< lines handed on, their buffers kept for reuse (no mallocs)
  bool open_ = false;        ///< the back line is still receiving samples
  bool have_joints_ = false;
  JointVector last_joints_ = JointVector::Zero();  ///< last usable solved joints seen
  double line_start_s_ = 0.0;                      ///< timed time at the front line's start
  /// The last sample handed on with joints: a transparent line's samples carry its motion.
  JointVector carry_velocities_ = JointVector::Zero(), carry_accelerations_ = JointVector::Zero();
  ExactSum cycle_time_;
  const LineProfile* emitting_ = nullptr;  ///< the profile of the line being handed on
};

}  // namespace stitchsim::sim
