#pragma once
// Private to verify: state appended to a carry (Rule::SaveCarry, Verifier::Carry) as its
// bytes, so equal carries mean bit-equal state (doubles compared bitwise, not by value).

#include <Eigen/Geometry>
#include <cstring>
#include <string>
#include <type_traits>

namespace stitchsim::verify::detail {

/// Appends the bytes of a scalar (no padding: bool, int, long, double, enums).
template <typename T>
void AppendBytes(std::string& out, const T& v) {
  static_assert(std::is_scalar_v<T>, "scalars only (a struct may hold padding)");
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  out.append(bytes, sizeof(T));
}

/// Appends an Eigen matrix's coefficients.
template <typename Derived>
void AppendMatrix(std::string& out, const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i) AppendBytes(out, m.derived().coeff(i));
}

inline void AppendPose(std::string& out, const Eigen::Isometry3d& pose) {
  AppendMatrix(out, pose.matrix());
}

inline void AppendString(std::string& out, const std::string& s) {
  AppendBytes(out, s.size());
  out += s;
}

}  // namespace stitchsim::verify::detail
