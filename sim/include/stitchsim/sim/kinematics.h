#pragma once
// Kinematics of the cell: forward kinematics of every link, analytic inverse kinematics of the
// 6R arm (ortho-parallel base, spherical wrist), the rail policy for the redundant axis and the
// rotator transform. Metres and radians; poses are Eigen::Isometry3d mapping a frame's
// coordinates into the world ("pose of the frame in the world").

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/units.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::sim {

// ---------------------------------------------------------------------------------------------
// Forward kinematics

/// Working data for ForwardKinematics: the world pose of every link.
struct LinkFrames {
  /// world_pose[i]: pose of RobotModel::links()[i] in the world frame (metres). Filled by
  /// ForwardKinematics; sized by MakeLinkFrames.
  std::vector<Eigen::Isometry3d> world_pose;
};

/// Allocates frames sized for `model` (do this once, outside the hot path).
LinkFrames MakeLinkFrames(const RobotModel& model);

/// World pose of every link at joints `q`. Allocation-free; `out` must come from MakeLinkFrames.
void ForwardKinematics(const RobotModel& model, const JointVector& q, LinkFrames& out);

/// World pose of one link at joints `q` (walks only that link's chain).
Eigen::Isometry3d LinkPose(const RobotModel& model, const JointVector& q, int link);

/// World pose of the flange (z out of the flange face) at joints `q`.
Eigen::Isometry3d FlangePose(const RobotModel& model, const JointVector& q);

/// World pose of the rotator link (middle of the turntable top) at joints `q`.
Eigen::Isometry3d RotatorPose(const RobotModel& model, const JointVector& q);

/// World pose of the OPW arm base frame (origin on the a1 axis, z along it) at a rail position.
Eigen::Isometry3d ArmBasePose(const RobotModel& model, double rail_m);

// ---------------------------------------------------------------------------------------------
// Arm configuration

// The arm configuration (shoulder, elbow, wrist) and the IK status are trace types.
using trace::ArmConfiguration;
using trace::Elbow;
using trace::IkStatus;
using trace::Shoulder;
using trace::ToString;
using trace::Wrist;

/// The configuration the arm joints of `q` are in.
ArmConfiguration ArmConfigurationOf(const RobotModel& model, const JointVector& q);

// ---------------------------------------------------------------------------------------------
// Inverse kinematics

/// One analytic arm solution.
struct ArmIkSolution {
  ArmJointVector joints_rad = ArmJointVector::Zero();  // a1..a6, URDF, wrapped to (-pi, pi]
  ArmConfiguration configuration;
  double sin_wrist = 0.0;  // sin of the OPW wrist angle t5 (0 = axes a4 and a6 aligned)
};

/// Every analytic solution for one flange pose: up to 8 (shoulder x elbow x wrist). Joint
/// limits are NOT applied here; a value type without allocation.
struct ArmIkSolutions {
  std::array<ArmIkSolution, 8> solution;
  int count = 0;  // 0: the wrist centre is out of reach
  /// Distance of the wrist centre from the a1 axis, less the lateral offset b (metres); near
  /// zero the shoulder is singular (a1 undetermined).
  double wrist_centre_radius_m = 0.0;
  /// Shoulder (a2 axis) to wrist centre distance for the front and back shoulder, and the
  /// range the upper arm and forearm can span (metres); for unreachable reasons.
  double shoulder_to_wrist_front_m = 0.0;
  double shoulder_to_wrist_back_m = 0.0;
  double min_reach_m = 0.0;
  double max_reach_m = 0.0;
};

/// All analytic solutions placing the flange at `flange_target_world` with the rail at
/// `rail_m`. `hint` (arm joints) fixes the free angle at an exact singularity (a1 when the
/// wrist centre is on the a1 axis, a4 when a5 = 0); without it the free angle is 0.
ArmIkSolutions AllArmIkSolutions(const RobotModel& model,
                                 const Eigen::Isometry3d& flange_target_world, double rail_m,
                                 const ArmJointVector* hint = nullptr);

struct IkOptions {
  /// Wrist singular when |sin(t5)| < sin(this) (t5 = a5 on this cell). Radians.
  double wrist_singularity_rad = kDeg;  // 1 deg
  /// Shoulder singular when the wrist centre is closer than this to the a1 axis. Metres.
  double shoulder_singularity_m = 0.05;
  /// Slack on joint limits (m or rad) so a pose exactly at a limit is accepted; a returned
  /// joint may lie outside its limit by at most this much.
  double limit_tolerance = 1e-9;
  /// Distance used to pick a solution: sum over a1..a6 of (weight * dq / max_velocity)^2,
  /// i.e. by default the squared motion time of each axis at full speed. Unitless weights.
  ArmJointVector joint_weights = ArmJointVector::Ones();
  /// Joints to stay near when SolveIk has no `previous` (default: the URDF zero pose).
  JointVector reference = JointVector::Zero();
};

struct IkResult {
  IkStatus status = IkStatus::kUnreachable;
  /// Model order. rail_x = the rail given; rotator = previous (or reference) rotator.
  /// kOk / singularity / config flip: the chosen solution (within limits; a1, a4, a6 and the
  /// other revolute axes take the 2 pi equivalent nearest the previous joints).
  /// kJointLimit: the nearest solution ignoring limits, for reporting only.
  /// kUnreachable: the previous (or reference) joints.
  JointVector joints = JointVector::Zero();
  ArmConfiguration configuration;  // configuration of `joints`
  std::string reason;              // short, for people; empty when kOk
  bool ok() const { return status == IkStatus::kOk; }
};

/// Solves the arm for a flange pose with the rail at `rail_m`: every analytic solution, each
/// axis moved to its 2 pi equivalent nearest `previous` within limits, the valid one nearest
/// `previous` (or options.reference) chosen. Statuses in the order they are checked: rail
/// outside its limits (kJointLimit), no analytic solution (kUnreachable), none within limits
/// (kJointLimit), kShoulderSingularity, kWristSingularity, kConfigFlip (only with `previous`),
/// else kOk.
IkResult SolveIk(const RobotModel& model, const Eigen::Isometry3d& flange_target_world,
                 double rail_m, const JointVector* previous, const IkOptions& options = {});

/// Flange pose that puts a tool point (e.g. a head's tool point) at `tool_target_world`;
/// `flange_to_tool` is the tool point's pose in the flange frame.
Eigen::Isometry3d FlangeTargetForTool(const Eigen::Isometry3d& tool_target_world,
                                      const Eigen::Isometry3d& flange_to_tool);

// ---------------------------------------------------------------------------------------------
// Rail policy (the redundant axis)
//
// The controller, not the programme, normally places the carriage. Policy: put the arm base
// (the a1 axis) at a fixed signed offset along the rail from the tool target, by default
// directly opposite it (offset 0), which keeps the reach equal to the target's perpendicular
// distance from the rail line and the a1 angle near square to the rail. A rail that only moves
// along its axis cannot change that perpendicular distance; a non-zero offset lengthens the
// reach to sqrt(perpendicular^2 + offset^2). The result is clamped to the rail limits. When
// the programme gives the rail (E word), that value is honoured unchanged (IK then reports
// kJointLimit if it is outside the limits).

struct RailPolicy {
  /// Signed distance (metres) along the rail axis from the tool target to the arm base
  /// (a1 axis): negative puts the base behind the target in rail coordinates.
  double base_offset_along_rail_m = 0.0;
  /// The programme's rail value (E word), metres; honoured as given when set.
  std::optional<double> programmed_rail_m;
};

struct RailPlacement {
  double rail_m = 0.0;      // rail_x joint value, metres
  bool clamped = false;     // the policy's value was outside the rail and was clamped
  bool programmed = false;  // rail_m is the programme's value
};

/// Rail position for a tool target (its position is used) under `policy`.
RailPlacement RailForTarget(const RobotModel& model, const Eigen::Isometry3d& tool_target_world,
                            const RailPolicy& policy = {});

// ---------------------------------------------------------------------------------------------
// Rotator

/// World pose of a frame carried by the rotator (a part mounted on the turntable) when the
/// rotator is at `rotator_rad`; `rotator_to_frame` is its pose in the rotator link frame.
Eigen::Isometry3d RotatorCarriedPose(const RobotModel& model, double rotator_rad,
                                     const Eigen::Isometry3d& rotator_to_frame);

}  // namespace stitchsim::sim
