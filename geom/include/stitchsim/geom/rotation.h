#pragma once
// Euler-angle conventions at the text boundary. Inside, orientations are rotation matrices.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <string_view>

namespace stitchsim::geom {

/// An Euler convention: three axes (0=x, 1=y, 2=z) applied in order about *fixed* axes
/// (extrinsic). "XYZ" means R = Rz(c) * Ry(b) * Rx(a) (the dialect default, = URDF rpy).
struct EulerOrder {
  int axes[3] = {0, 1, 2};
};

/// Parses "XYZ", "ZYX", "ZXZ", ... (upper case, fixed axes; two equal neighbours rejected).
std::optional<EulerOrder> ParseEulerOrder(std::string_view text);
std::string ToString(EulerOrder order);

/// R = R_{axes[2]}(angles[2]) * R_{axes[1]}(angles[1]) * R_{axes[0]}(angles[0]); radians.
Eigen::Matrix3d RotationFromEuler(EulerOrder order, const Eigen::Vector3d& angles_rad);

/// Inverse of RotationFromEuler; the middle angle is chosen in its principal range. Near
/// gimbal lock the first angle is set to 0. `hint_rad`, if given, picks the 2pi-equivalent
/// and the alternate solution closest to it (keeps programmes continuous).
Eigen::Vector3d EulerFromRotation(EulerOrder order, const Eigen::Matrix3d& rotation,
                                  const Eigen::Vector3d* hint_rad = nullptr);

/// Angle of the rotation between two orientations, radians in [0, pi].
double AngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/// Frame with z = normal and y = direction projected orthogonal to normal; x = y cross z.
/// Returns nullopt when direction is (nearly) parallel to normal.
std::optional<Eigen::Matrix3d> FrameFromNormalAndDirection(const Eigen::Vector3d& normal,
                                                           const Eigen::Vector3d& direction);

}  // namespace stitchsim::geom
