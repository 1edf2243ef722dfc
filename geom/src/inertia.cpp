#include "stitchsim/geom/inertia.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cstdio>

namespace stitchsim::geom {
namespace {

// Relative tolerance of the symmetry and triangle-inequality checks, against the trace.
constexpr double kInertiaTolerance = 1e-12;

std::string Num(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace

std::string InertiaProblem(const Eigen::Matrix3d& inertia_kg_m2) {
  const Eigen::Matrix3d& inertia = inertia_kg_m2;
  if (!inertia.allFinite()) return "the inertia is not finite";
  const double scale = std::max(inertia.trace(), 0.0) + 1e-300;
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > kInertiaTolerance * scale) {
    return "the inertia is not symmetric";
  }
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia, Eigen::EigenvaluesOnly)
          .eigenvalues();  // ascending
  if (!(moments(0) > 0.0)) {
    return "the inertia is not positive definite (smallest principal moment " + Num(moments(0)) +
           " kg m^2)";
  }
  if (moments(0) + moments(1) < moments(2) * (1.0 - kInertiaTolerance)) {
    return "the principal moments " + Num(moments(0)) + ", " + Num(moments(1)) + ", " +
           Num(moments(2)) + " kg m^2 break the triangle inequality (a + b >= c)";
  }
  return {};
}

}  // namespace stitchsim::geom
