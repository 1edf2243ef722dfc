#pragma once
// The Trace: what executing a programme on the cell produced, streamed sample by sample to a
// TraceSink (the verifier, a recorder, ...). Nothing here grows with programme length.

#include <Eigen/Geometry>

#include "stitchsim/sim/kinematics.h"

namespace stitchsim::sim {

/// Why a sample was taken.
enum class SampleEvent {
  kNone,         ///< an interior sample (step bounded by the executor's tolerances)
  kLineStart,    ///< fraction 0 of a line
  kLineEnd,      ///< fraction 1 of a line
  kNeedleEntry,  ///< the needles enter the preform (cycle phase = phase_in)
  kNeedleExit,   ///< the needles leave the preform (cycle phase = phase_out)
};

/// One sample of the executed programme. Filled by ExecuteProgram.
struct TraceSample {
  double time_s = 0.0;         ///< programme time since the first line, seconds
  int source_line = 0;         ///< 1-based line of the move being executed
  long stitch = 0;             ///< 1-based stitch cycle the drive is in (0 before the first)
  double line_fraction = 0.0;  ///< 0..1 along the line
  SampleEvent event = SampleEvent::kNone;
  /// Tool-point pose in the part frame: translation mm, rotation from the programme's A B C.
  Eigen::Isometry3d tool_part = Eigen::Isometry3d::Identity();
  double drive_mm = 0.0;         ///< U, interpolated linearly along the line
  double path_mm = 0.0;          ///< V, interpolated linearly along the line
  double phase = 0.0;            ///< stitch-cycle phase in [0, 1)
  bool drive_advancing = false;  ///< this line advances U (a stitch cycle is running)
  bool needles_in = false;       ///< the needles are in the preform
  /// Kinematics, when solved at this sample (line ends, events and a bounded grid).
  bool has_joints = false;
  IkStatus ik_status = IkStatus::kOk;
  JointVector joints = JointVector::Zero();  ///< model order: rail m, angles rad
  ArmConfiguration configuration;
};

/// One executed motion line. Filled by ExecuteProgram before its samples.
struct LineRecord {
  int source_line = 0;
  bool rapid = false;                                      ///< G0
  Eigen::Isometry3d from = Eigen::Isometry3d::Identity();  ///< tool pose, part frame (mm)
  Eigen::Isometry3d to = Eigen::Isometry3d::Identity();
  double drive_from_mm = 0.0, drive_to_mm = 0.0;  ///< U
  double path_from_mm = 0.0, path_to_mm = 0.0;    ///< V
  double duration_s = 0.0;                        ///< at the programmed feed (or head speeds)
  double feed_mm_per_min = 0.0;                   ///< modal F (0 if none)
  bool stitching = false;                         ///< M10 in force
  bool head_retracted = false;                    ///< M20 in force
  /// Trace samples the line needs at the executor's steps (grid, in-preform, needle events).
  double samples_needed = 0.0;
  /// samples_needed > limits::kMaxSamplesPerLine: the line was sampled at its ends only and
  /// is a finding of program.line_sampling (not checked further).
  bool over_sample_limit = false;
};

/// Receives the trace as it is produced.
class TraceSink {
 public:
  virtual ~TraceSink() = default;
  virtual void OnLine(const LineRecord& line) = 0;
  virtual void OnSample(const TraceSample& sample) = 0;
};

}  // namespace stitchsim::sim
