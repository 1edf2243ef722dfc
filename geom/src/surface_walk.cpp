#include "stitchsim/geom/surface_walk.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace stitchsim::geom {

SurfaceFoot ProjectNear(const Surface& s, const Eigen::Vector3d& p, Eigen::Vector2d uv) {
  SurfaceFoot out;
  for (int iter = 0; iter < 200; ++iter) {
    Eigen::Vector3d at;
    Eigen::Matrix<double, 3, 2> j;
    s.PointAndJacobian(uv, at, j);
    const Eigen::Vector2d step = (j.transpose() * j).ldlt().solve(j.transpose() * (p - at));
    if (!step.allFinite()) return out;
    uv += step;
    if (step.norm() < 1e-13 * (1.0 + uv.norm())) {
      out.converged = true;
      break;
    }
  }
  out.uv = uv;
  out.point = s.Point(uv);
  return out;
}

Eigen::Vector3d Tangential(const Eigen::Vector3d& w, const Eigen::Vector3d& n) {
  return (w - w.dot(n) * n).normalized();
}

SurfaceFoot WalkOnSurface(const Surface& s, const Eigen::Vector2d& uv,
                          const Eigen::Vector3d& direction, double length_mm,
                          double max_substep_mm) {
  SurfaceFoot x{uv, s.Point(uv), true};
  if (!(length_mm > 0)) return x;
  const int pieces = std::max(1, static_cast<int>(std::ceil(length_mm / max_substep_mm)));
  const double h = length_mm / pieces;
  Eigen::Vector3d w = Tangential(direction, s.Normal(uv));
  for (int k = 0; k < pieces; ++k) {
    double step = h;
    SurfaceFoot y;
    Eigen::Vector3d chord;
    for (int iter = 0; iter < 4; ++iter) {
      y = ProjectNear(s, x.point + step * w, x.uv);
      if (!y.converged) return y;
      chord = y.point - x.point;
      const double c = chord.norm();
      const double alpha = std::acos(std::clamp(chord.dot(w) / c, -1.0, 1.0));
      const double arc = alpha > 1e-8 ? c * alpha / std::sin(alpha) : c * (1 + alpha * alpha / 6);
      step *= h / arc;
      if (std::abs(arc - h) < 1e-12 * h) break;
    }
    w = Tangential(chord, s.Normal(y.uv));
    x = y;
  }
  return x;
}

}  // namespace stitchsim::geom
