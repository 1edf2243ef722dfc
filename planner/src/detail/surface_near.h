#pragma once
// Private helpers of the offset-curve and laminate-family code: the closest surface point
// near a known parameter, and a direction laid into a tangent plane.

#include <Eigen/Core>

#include "stitchsim/geom/surface.h"

namespace stitchsim::planner::detail {

/// A surface point found from a nearby parameter.
struct Foot {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  bool converged = false;
};

/// Closest surface point to `p` by Gauss-Newton from `uv`.
Foot ProjectNear(const geom::Surface& s, const Eigen::Vector3d& p, Eigen::Vector2d uv);

/// `w` without its component along the unit `n`, made unit.
Eigen::Vector3d Tangential(const Eigen::Vector3d& w, const Eigen::Vector3d& n);

}  // namespace stitchsim::planner::detail
