#pragma once
// Where a constraint (stringer, intercostal, spar cap) may not be stitched: one geometry for
// the raster planner, which keeps its rows off it, and the constraint.crossing rule, which
// judges a programme against it. A constraint's box (a mesh constraint: the part-axis-aligned
// bounding box of its vertices) is grown by a margin on every side; on a height-field surface
// its footprint is that box projected on the part's (x, y) plane (u = x, v = y). On any other
// surface its footprint lives in the surface's own (u, v): the box projected onto the surface
// (ConstraintFootprintOn).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {

/// A constraint's box grown by a margin, in 3D (part frame, mm).
struct GrownBox {
  std::string name;
  Eigen::Isometry3d to_local = Eigen::Isometry3d::Identity();  ///< part frame -> box frame
  Eigen::Vector3d half_mm = Eigen::Vector3d::Zero();           ///< half extents, margin included

  /// How far inside (>= 0) the box `p` is; negative outside.
  double Depth(const Eigen::Vector3d& p) const;
  /// The segment a-b meets the box (exact slab test): the depth of the middle of its part
  /// inside (>= 0); negative if it misses.
  double SegmentDepth(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
};

/// A constraint's box projected on the part's (x, y) plane as an oriented rectangle
/// (conservative for boxes tilted out of the plane), grown by a margin; or, on a surface that
/// is not a height field, an oriented rectangle in the surface's (u, v) (ConstraintFootprintOn).
struct Footprint {
  std::string name;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();   ///< part frame (x, y) or (u, v), mm
  Eigen::Vector2d axis_x = Eigen::Vector2d::UnitX();  ///< unit
  Eigen::Vector2d axis_y = Eigen::Vector2d::UnitY();  ///< unit, perpendicular to axis_x
  Eigen::Vector2d half_mm = Eigen::Vector2d::Zero();  ///< half extents, margin included

  bool Contains(const Eigen::Vector2d& p) const;
  /// How far inside (>= 0) the rectangle `p` is; negative outside.
  double Depth(const Eigen::Vector2d& p) const;
  /// True if the segment a-b meets the rectangle (exact slab test).
  bool Crosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  /// As Crosses: the depth of the middle of the part inside (>= 0); negative if it misses.
  double SegmentDepth(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  /// The x-range where the horizontal line y = `y` is inside; false if it misses.
  bool RowInterval(double y, double& x_min, double& x_max) const;
};

/// The constraint's box grown by `margin_mm`.
GrownBox ConstraintBox(const Constraint& constraint, double margin_mm);
/// The constraint's footprint on the part's (x, y) plane, grown by `margin_mm`.
Footprint ConstraintFootprint(const Constraint& constraint, double margin_mm);
/// ConstraintFootprint of every constraint of the scene, in scene order.
std::vector<Footprint> ConstraintFootprints(const Scene& scene, double margin_mm);

/// The constraint's footprint in the (u, v) of `surface`, grown by `margin_mm`. A height field:
/// ConstraintFootprint (u = x, v = y). Otherwise the box, grown by the margin along its two
/// axes most tangent to the surface, is projected onto the surface (closest points of its
/// corners and of points at most 10 mm apart along its edges) and bounded by an oriented
/// rectangle in (u, v) whose first axis is the box's x axis mapped into (u, v) at the foot
/// point of its centre. nullopt with `error` set when it does not project (the centre's foot
/// point lies outside the domain, or a projection is not finite).
std::optional<Footprint> ConstraintFootprintOn(const Constraint& constraint,
                                               const geom::Surface& surface, double margin_mm,
                                               std::string& error);

/// Where a part-frame point falls in the plane of footprints on `surface`: (x, y) on a height
/// field, the (u, v) of its closest point otherwise.
Eigen::Vector2d FootprintPlanePoint(const geom::Surface& surface, const Eigen::Vector3d& p);

}  // namespace stitchsim::scene
