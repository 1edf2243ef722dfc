#pragma once
// Local moves on a surface: the closest point near a known parameter (Gauss-Newton, no global
// search) and a walk along the surface from a point in a tangent direction for a given arc
// length (the direction carried from step to step as the chord laid into the next tangent
// plane). Used by the offset-curve constructions and by everything that places AFP tows
// beside a course centre line (planner and verifier alike). Part frame, mm.

#include <Eigen/Core>

#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {

/// A surface point found from a nearby parameter.
struct SurfaceFoot {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  bool converged = false;
};

/// Closest surface point to `p` by Gauss-Newton from `uv`. Not converged: no point near.
SurfaceFoot ProjectNear(const Surface& s, const Eigen::Vector3d& p, Eigen::Vector2d uv);

/// `w` without its component along the unit `n`, made unit.
Eigen::Vector3d Tangential(const Eigen::Vector3d& w, const Eigen::Vector3d& n);

/// Walks the surface from the point at `uv` along the tangent direction `direction` (laid into
/// the tangent plane there) for the arc length `length_mm` (>= 0), in substeps of at most
/// `max_substep_mm`, each projected back and its arc taken from the chord and the turn of the
/// tangent (exact on a circle). On a plane or along a cylinder's circumference the end point
/// is exact. Not converged if a substep leaves the surface.
SurfaceFoot WalkOnSurface(const Surface& s, const Eigen::Vector2d& uv,
                          const Eigen::Vector3d& direction, double length_mm,
                          double max_substep_mm = 0.5);

}  // namespace stitchsim::geom
