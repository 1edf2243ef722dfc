#pragma once
// The cell's joint vector and the kinematic outcome a trace sample carries: the IK status,
// the arm configuration, and the one predicate that says whether a sample's joints are usable.

#include <Eigen/Core>
#include <string>
#include <string_view>

namespace stitchsim::trace {

inline constexpr int kNumJoints = 8;
inline constexpr int kNumArmJoints = 6;

/// Index of each movable joint in a JointVector (the model joint order).
enum JointIndex : int {
  kRailX = 0,  // prismatic floor rail, metres
  kA1 = 1,     // arm axes a1..a6, radians (URDF convention, KUKA axis signs)
  kA2 = 2,
  kA3 = 3,
  kA4 = 4,
  kA5 = 5,
  kA6 = 6,
  kRotator = 7,  // turntable, radians
};

/// Joint positions in model order: rail_x in metres, a1..a6 and rotator in radians.
using JointVector = Eigen::Matrix<double, kNumJoints, 1>;
/// Arm joints a1..a6 in radians, URDF convention (JointVector entries kA1..kA6).
using ArmJointVector = Eigen::Matrix<double, kNumArmJoints, 1>;

/// Wrist centre in front of the a1 axis (on the side of the a2 offset) or behind it.
enum class Shoulder { kFront, kBack };
/// Forearm bent forward relative to the upper arm (OPW t3 + atan2(a2, c3) >= 0) or backward.
/// With the shoulder in front, kUp is the usual "elbow up".
enum class Elbow { kUp, kDown };
/// Wrist angle t5 (OPW, = a5 on this cell) >= 0: kNoFlip; < 0: kFlip.
enum class Wrist { kNoFlip, kFlip };

/// The 8 IK branches of the arm (KUKA: the Status bits).
struct ArmConfiguration {
  Shoulder shoulder = Shoulder::kFront;
  Elbow elbow = Elbow::kUp;
  Wrist wrist = Wrist::kNoFlip;
  bool operator==(const ArmConfiguration&) const = default;
};

/// "front/up/noflip" and the like.
std::string ToString(const ArmConfiguration& configuration);

/// Outcome of IK. Expected failures are values, never exceptions.
enum class IkStatus {
  kOk,
  kUnreachable,          // no analytic solution: the wrist centre is out of reach
  kJointLimit,           // solutions exist, but every one violates a joint limit (or rail)
  kWristSingularity,     // |sin a5| below the threshold: a4 and a6 nearly aligned
  kShoulderSingularity,  // wrist centre (nearly) on the a1 axis
  kConfigFlip,           // the nearest valid solution changes shoulder/elbow/wrist vs previous
};

/// "ok", "unreachable", "joint-limit", "wrist-singularity", "shoulder-singularity",
/// "config-flip".
std::string_view ToString(IkStatus status);

/// True when joints solved with `status` are a pose the arm can take (the executor continues
/// from them, the collision world is queried at them, joint speeds are measured between them):
/// every status but kUnreachable and kJointLimit.
constexpr bool IkUsable(IkStatus status) {
  return status != IkStatus::kUnreachable && status != IkStatus::kJointLimit;
}

}  // namespace stitchsim::trace
