#pragma once
// Canonical OPW arm kinematics (Brandstoetter, Angerer, Hofbaur 2014) in the OPW base frame and
// OPW angles t1..t6; the mapping to URDF joints and the world lives in kinematics.cpp.

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "stitchsim/common/units.h"
#include "stitchsim/sim/kinematics.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::sim::detail {

inline constexpr double kTwoPi = 2 * kPi;

/// Angle wrapped to (-pi, pi].
inline double WrapToPi(double angle_rad) {
  // Already there (most calls): std::remainder would return it unchanged, at many times the cost.
  if (angle_rad > -kPi && angle_rad <= kPi) return angle_rad;
  double wrapped = std::remainder(angle_rad, kTwoPi);  // [-pi, pi]
  if (wrapped <= -kPi) wrapped += kTwoPi;
  return wrapped;
}

inline Eigen::Matrix3d RotZ(double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  Eigen::Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

inline Eigen::Matrix3d RotY(double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  Eigen::Matrix3d r;
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}

/// OPW angles from URDF arm joints: t_i = sign_i * q_i + offset_i.
inline ArmJointVector OpwFromUrdf(const OpwGeometry& g, const ArmJointVector& q_rad) {
  ArmJointVector t;
  for (int i = 0; i < kNumArmJoints; ++i) t(i) = g.sign[i] * q_rad(i) + g.offset_rad[i];
  return t;
}

/// URDF arm joints from OPW angles, each wrapped to (-pi, pi].
inline ArmJointVector UrdfFromOpw(const OpwGeometry& g, const ArmJointVector& t_rad) {
  ArmJointVector q;
  for (int i = 0; i < kNumArmJoints; ++i) q(i) = WrapToPi(g.sign[i] * (t_rad(i) - g.offset_rad[i]));
  return q;
}

/// Pose of the OPW flange frame in the OPW base frame.
Eigen::Isometry3d OpwForward(const OpwGeometry& g, const ArmJointVector& t_rad);

/// Configuration of a set of OPW angles.
ArmConfiguration OpwConfiguration(const OpwGeometry& g, const ArmJointVector& t_rad);

/// All analytic solutions (OPW angles, not wrapped) for an OPW flange pose in the OPW base
/// frame. `hint_t` (OPW angles) fixes t1 / t4 at exact singularities. Fills `out` (count,
/// configurations, sin_wrist and the reach fields); joints_rad receive OPW angles.
void OpwInverse(const OpwGeometry& g, const Eigen::Isometry3d& base_to_flange,
                const ArmJointVector* hint_t, ArmIkSolutions& out);

}  // namespace stitchsim::sim::detail
