#pragma once
// Surfaces shared by the offset-curve and laminate-family tests.

#include <memory>

#include "stitchsim/geom/surface.h"

namespace stitchsim::planner::testing {

/// z = y^3 / 20 over x in [-half_x, half_x], y in [-12, 12]: one inflection at y = 0, normal
/// radius of curvature down to 2.5 mm (at y = 1.7 mm).
inline std::unique_ptr<geom::Surface> InflectedSurface(double half_x_mm) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(0, 3) = 0.05;
  geom::Domain2 dom;
  dom.min = Eigen::Vector2d(-half_x_mm, -12);
  dom.max = Eigen::Vector2d(half_x_mm, 12);
  return geom::MakePolynomialHeightField(c, dom);
}

}  // namespace stitchsim::planner::testing
