#pragma once
// Local moves on a surface: the closest point near a known parameter (Gauss-Newton, no global
// search) and a walk along the surface geodesic from a point in a tangent direction for a
// given arc length. Used by the offset-curve constructions and by everything that places AFP tows
// beside a course centre line (planner and verifier alike). Part frame, mm.

#include <Eigen/Core>
#include <optional>

#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {

/// A surface point found from a nearby parameter.
struct SurfaceFoot {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  bool converged = false;
  /// WalkOnSurface only: the walk's unit tangent where it ends (its start direction carried
  /// along the geodesic); zero from ProjectNear.
  Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
};

/// Closest surface point to `p` by Gauss-Newton from `uv`. Not converged: no point near.
SurfaceFoot ProjectNear(const Surface& s, const Eigen::Vector3d& p, Eigen::Vector2d uv);

/// The (u, v) step whose image J d(u, v) is closest to the tangent vector `t` at `uv` (least
/// squares through the Jacobian; exact for a vector in the tangent plane).
Eigen::Vector2d UvOfTangent(const Surface& s, const Eigen::Vector2d& uv, const Eigen::Vector3d& t);

/// `w` without its component along the unit `n`, made unit.
Eigen::Vector3d Tangential(const Eigen::Vector3d& w, const Eigen::Vector3d& n);

/// Walks the surface geodesic from the point at `uv` along the tangent direction `direction`
/// (laid into the tangent plane there) for the arc length `length_mm` (>= 0), in chords of
/// at most `max_substep_mm`: the first from the geodesic's Taylor series (walked in shorter
/// chords over 3.5 mm), each next one the last reflected in the tangent plane between them (a
/// discrete geodesic) and sized by the turn between chords, each end projected back. Exact on a
/// plane, on a cylinder (helices) and on a sphere (great circles); second order in the substep
/// elsewhere. The result's `tangent` is the geodesic's direction at the end. Not converged if a
/// substep leaves the surface.
SurfaceFoot WalkOnSurface(const Surface& s, const Eigen::Vector2d& uv,
                          const Eigen::Vector3d& direction, double length_mm,
                          double max_substep_mm = 0.5);

/// Signed distance along the surface geodesic from the point at `uv` in the tangent direction
/// `direction` to where `to` lies across it (its offset to the side and off the surface set
/// aside): the geodesic walked until `to` is abeam, negative behind. Nullopt if the walk
/// leaves the surface. For the gap between two courses' facing edges (planner and afp rules).
std::optional<double> DistanceAlongGeodesic(const Surface& s, const Eigen::Vector2d& uv,
                                            const Eigen::Vector3d& direction,
                                            const Eigen::Vector3d& to, double max_substep_mm = 0.5);

}  // namespace stitchsim::geom
