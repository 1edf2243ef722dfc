#pragma once
// Where a constraint (stringer, intercostal, spar cap) may not be stitched: one geometry for
// the raster planner, which keeps its rows off it, and the constraint.crossing rule, which
// judges a programme against it. A constraint's box (a mesh constraint: the part-axis-aligned
// bounding box of its vertices) is grown by a margin on every side; on a height-field surface
// its footprint is that box projected on the part's (x, y) plane, otherwise the box itself.

#include <Eigen/Geometry>
#include <string>
#include <vector>

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
/// (conservative for boxes tilted out of the plane), grown by a margin.
struct Footprint {
  std::string name;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();   ///< part frame, mm
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

}  // namespace stitchsim::scene
