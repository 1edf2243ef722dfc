#pragma once
// The Trace: what executing a programme on the cell produced, streamed sample by sample to a
// TraceSink (the verifier, a trace file, ...). Everything the rules read is here: the tool
// pose and stitch cycle, the joints and IK status, the contacts and clearance the collision
// world measured, and (CellDescription) the joint limits and body names the producer used.
// Nothing here grows with programme length.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "stitchsim/trace/joints.h"

namespace stitchsim::trace {

/// What the kin.* and collision.* rules need to know of the cell, written by the producer
/// of the trace (sim::DescribeCell) before the first sample.
struct CellDescription {
  /// URDF names of the joints, model order ("rail_x", "a1".."a6", "rotator").
  std::array<std::string, kNumJoints> joint_names;
  JointVector lower_limits = JointVector::Zero();    ///< m (rail), rad
  JointVector upper_limits = JointVector::Zero();    ///< m (rail), rad
  JointVector max_velocities = JointVector::Zero();  ///< m/s (rail), rad/s
  /// Acceleration limits (m/s^2, rad/s^2) and torque/force limits (N, N m) the producer's
  /// time law and inverse dynamics used; 0 = the model gives none (kin.acceleration and
  /// kin.torque skip that joint).
  JointVector max_accelerations = JointVector::Zero();
  JointVector max_efforts = JointVector::Zero();
  /// The arm's load diagram (kin.payload): rated payload (kg, 0 = none given) and the centre
  /// of mass distances from the flange it is rated at (m): along the flange z, off that axis;
  /// and the distance from the a5 axis to the flange face (m), the lever of the a5 moment.
  double payload_rated_kg = 0.0;
  double payload_rated_lz_m = 0.0;
  double payload_rated_lxy_m = 0.0;
  double wrist_to_flange_m = 0.0;
  /// The trace's samples carry the timed trajectory (TraceSample::has_timing); false for a
  /// producer without a time law.
  bool timed = false;
  /// The trace is of a dynamic run (`verify --dynamics`): tool_part is where the arm's
  /// physics put the tool, and samples carry the tracking error.
  bool dynamic = false;
  /// The executor queried a collision world at every sample with usable joints (below);
  /// false under `--no-collision` (the collision.* rules do not run).
  bool collision_checked = false;
  /// Names of the collision world's bodies ("head:presser_foot", "link_3", "constraint:..."):
  /// Contact and SampleCollision refer to bodies by index into this table.
  std::vector<std::string> bodies;
};

/// Which family of bodies a contact belongs to (the verifier's rules split on this).
enum class ContactClass {
  kHeadPart,   ///< head vs mold, preform or a constraint  -> collision.head_mold
  kRobotCell,  ///< arm, carriage or head vs rail, rotator, table, floor, each other
};

/// One contact at a sample (docs/collision.md). Filled by the executor from the collision world.
struct Contact {
  ContactClass kind = ContactClass::kHeadPart;
  int body_a = -1;  ///< index into CellDescription::bodies
  int body_b = -1;
  /// Penetration depth, metres (docs/collision.md, "Depth"); 0 when not measured.
  double depth_m = 0.0;
  /// False against a mesh constraint (FCL's mesh depth is one triangle's, not the body's).
  bool depth_measured = true;
  Eigen::Vector3d point_world_m = Eigen::Vector3d::Zero();  ///< deepest point, world, metres
};

/// The collision world's answer at one sample. Filled by the executor when it was given a
/// collision world and the sample's joints are usable (JointsUsable); else `checked` is false.
struct SampleCollision {
  bool checked = false;
  std::vector<Contact> contacts;  ///< empty = clear (no allocation in the common case)
  /// Smallest distance between bodies that must not touch, metres (0 with contacts), capped at
  /// the world's clearance cutoff; 1e9 when not computed.
  double min_clearance_m = 1e9;
  int clearance_body_a = -1;  ///< the pair at min_clearance_m (indices; -1: none)
  int clearance_body_b = -1;
  std::string error;  ///< non-empty: a pair could not be checked (the sample is not clear)
};

/// Why a sample was taken.
enum class SampleEvent {
  kNone,         ///< an interior sample (step bounded by the executor's tolerances)
  kLineStart,    ///< fraction 0 of a line
  kLineEnd,      ///< fraction 1 of a line
  kNeedleEntry,  ///< the needles enter the preform (cycle phase = phase_in)
  kNeedleExit,   ///< the needles leave the preform (cycle phase = phase_out)
};

/// One sample of the executed programme. Filled by the executor (sim::ExecuteProgram).
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
  /// Contacts and clearance at `joints` (collision.* rules).
  SampleCollision collision;
  /// An extra sample the collision subdivision inserted between the grid's (so no contact
  /// slips between samples): joints and contacts, but no torques (kin.torque reads the grid).
  bool collision_probe = false;
  /// The timed trajectory (sim::TimingSink, the controller's time law): when set, `timed_s` is
  /// the time on it since the first line; with joints, the joint velocities (m/s, rad/s),
  /// accelerations (m/s^2, rad/s^2) and the torques/forces MuJoCo's inverse dynamics needs to
  /// move the cell so (N m, N for the rail; gravity, inertia, Coriolis, joint friction).
  /// In a chunked run (verify --jobs/--shard) `timed_s` counts from the chunk's warm-up start,
  /// not the programme's: rules must not read it (the saved trace, made serially, has it whole).
  bool has_timing = false;
  double timed_s = 0.0;
  JointVector joint_velocities = JointVector::Zero();
  JointVector joint_accelerations = JointVector::Zero();
  JointVector joint_torques = JointVector::Zero();
  /// Dynamic mode only (sim::DynamicsSink): how far the tool point (mm) and its axes (deg) lag
  /// the command at this sample; tool_part is then the actual pose.
  bool tracked = false;
  double tracking_error_mm = 0.0;
  double tracking_error_deg = 0.0;
};

/// The sample carries joints the arm can take (the IK-usable predicate, IkUsable).
inline bool JointsUsable(const TraceSample& s) { return s.has_joints && IkUsable(s.ik_status); }

/// One executed motion line. Filled by the executor before its samples.
struct LineRecord {
  int source_line = 0;
  bool rapid = false;                                      ///< G0
  Eigen::Isometry3d from = Eigen::Isometry3d::Identity();  ///< tool pose, part frame (mm)
  Eigen::Isometry3d to = Eigen::Isometry3d::Identity();
  double drive_from_mm = 0.0, drive_to_mm = 0.0;  ///< U
  double path_from_mm = 0.0, path_to_mm = 0.0;    ///< V
  double duration_s = 0.0;                        ///< at the programmed feed (or head speeds)
  /// On the controller's time law (acceleration ramps, blending; sim::TimingSink), dwell
  /// included; 0 when the trace is not timed. Filled before the line's samples reach a sink
  /// behind the timing sink.
  double timed_duration_s = 0.0;
  double feed_mm_per_min = 0.0;  ///< modal F (0 if none)
  bool stitching = false;        ///< M10 in force
  bool head_retracted = false;   ///< M20 in force
  /// AFP: the tows laying on this line (bit i = tow i + 1; the modal mask once the line's
  /// M62/M63 are applied, so in force during its move), the ply (M70 P, 0 before any) and the
  /// open course (M71 P, 0 outside a course). docs/program-format.md, "Fibre placement".
  std::uint64_t tows = 0;
  int ply = 0;
  int course = 0;
  /// Trace samples the line needs at the executor's steps (grid, in-preform, needle events).
  double samples_needed = 0.0;
  /// samples_needed > limits::kMaxSamplesPerLine: the line was sampled at its ends only and
  /// is a finding of program.line_sampling (not checked further).
  bool over_sample_limit = false;
};

/// Receives the trace as it is produced (or replayed from a file).
class TraceSink {
 public:
  virtual ~TraceSink() = default;
  virtual void OnLine(const LineRecord& line) = 0;
  virtual void OnSample(const TraceSample& sample) = 0;
};

}  // namespace stitchsim::trace
