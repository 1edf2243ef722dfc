#include "stitchsim/geom/rotation.h"

#include <cmath>

#include "stitchsim/common/units.h"

namespace stitchsim::geom {
namespace {

Eigen::Matrix3d AxisRotation(int axis, double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

double WrapNear(double angle, double reference) {
  constexpr double kTwoPi = 2.0 * kPi;
  return angle + kTwoPi * std::round((reference - angle) / kTwoPi);
}

}  // namespace

std::optional<EulerOrder> ParseEulerOrder(std::string_view text) {
  if (text.size() != 3) return std::nullopt;
  EulerOrder order;
  for (int i = 0; i < 3; ++i) {
    const char c = text[static_cast<std::size_t>(i)];
    if (c < 'X' || c > 'Z') return std::nullopt;
    order.axes[i] = c - 'X';
  }
  if (order.axes[0] == order.axes[1] || order.axes[1] == order.axes[2]) return std::nullopt;
  return order;
}

std::string ToString(EulerOrder order) {
  std::string s;
  for (int a : order.axes) s += static_cast<char>('X' + a);
  return s;
}

Eigen::Matrix3d RotationFromEuler(EulerOrder order, const Eigen::Vector3d& angles_rad) {
  return AxisRotation(order.axes[2], angles_rad[2]) * AxisRotation(order.axes[1], angles_rad[1]) *
         AxisRotation(order.axes[0], angles_rad[0]);
}

Eigen::Vector3d EulerFromRotation(EulerOrder order, const Eigen::Matrix3d& rotation,
                                  const Eigen::Vector3d* hint_rad) {
  // Eigen's eulerAngles(a0, a1, a2) returns R = R_a0(e0) R_a1(e1) R_a2(e2) (moving axes),
  // which equals our fixed-axes order reversed.
  const Eigen::Vector3d e = rotation.eulerAngles(order.axes[2], order.axes[1], order.axes[0]);
  Eigen::Vector3d sol1(e[2], e[1], e[0]);
  // The alternate solution of a Tait-Bryan / proper Euler triple.
  const bool proper = order.axes[0] == order.axes[2];
  Eigen::Vector3d sol2 = proper ? Eigen::Vector3d(sol1[0] + kPi, -sol1[1], sol1[2] + kPi)
                                : Eigen::Vector3d(sol1[0] + kPi, kPi - sol1[1], sol1[2] + kPi);
  auto normalise = [&](Eigen::Vector3d s) {
    const Eigen::Vector3d ref = hint_rad != nullptr ? *hint_rad : Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) s[i] = WrapNear(s[i], ref[i]);
    return s;
  };
  sol1 = normalise(sol1);
  sol2 = normalise(sol2);
  const Eigen::Vector3d ref = hint_rad != nullptr ? *hint_rad : Eigen::Vector3d::Zero();
  // Without a hint prefer the solution with the middle angle in [-pi/2, pi/2] (Tait-Bryan)
  // or [0, pi] (proper), which is what people expect to read.
  if (hint_rad == nullptr) {
    const double m1 = sol1[1];
    const bool ok1 = proper ? (m1 >= -1e-12 && m1 <= kPi + 1e-12)
                            : (m1 >= -kPi / 2 - 1e-12 && m1 <= kPi / 2 + 1e-12);
    return ok1 ? sol1 : sol2;
  }
  return (sol1 - ref).squaredNorm() <= (sol2 - ref).squaredNorm() ? sol1 : sol2;
}

double AngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

std::optional<Eigen::Matrix3d> FrameFromNormalAndDirection(const Eigen::Vector3d& normal,
                                                           const Eigen::Vector3d& direction) {
  const Eigen::Vector3d z = normal.normalized();
  Eigen::Vector3d y = direction - direction.dot(z) * z;
  if (y.norm() < 1e-12 * std::max(1.0, direction.norm())) return std::nullopt;
  y.normalize();
  Eigen::Matrix3d r;
  r.col(0) = y.cross(z);
  r.col(1) = y;
  r.col(2) = z;
  return r;
}

}  // namespace stitchsim::geom
