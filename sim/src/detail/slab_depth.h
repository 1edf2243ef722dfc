#pragma once
// Penetration depth of a primitive into a part slab (the solid between two offsets of the
// scene surface: the mold -depth..0, the preform 0..thickness), measured on the analytic
// surface instead of FCL's mesh-mesh contact depth (which is not a penetration depth).
// docs/collision.md, "Depth".

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "detail/collision_mjcf.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::sim::detail {

/// A point of a primitive's surface with a radius (sphere / capsule: the centre and the
/// radius; cylinder: radius 0). Geometry frame, metres.
struct DepthSample {
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  double radius_m = 0.0;
};

/// A box face: origin + s u + t v for s, t in [0, 1], searched on an nu x nv grid and then
/// refined around its deepest grid point. Geometry frame, metres.
struct DepthFace {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d u = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  int nu = 1, nv = 1;
};

/// Where the depth of a primitive is looked for.
struct DepthGeometry {
  std::vector<DepthSample> samples;
  std::vector<DepthFace> faces;
};

/// The depth points of an MJCF primitive (half sizes `size_m`, FCL's frame: capsule and
/// cylinder along z): box faces as grids at most `spacing_m` apart (at most 4 intervals along
/// an edge; corners included), refined to 0.2 mm where a grid comes within 2 mm of the
/// deepest; cylinder rings and caps and capsule axis points at most `spacing_m / 6` apart (at
/// most 24 intervals); a sphere's centre.
DepthGeometry PrimitiveDepthGeometry(MjcfShape shape, const Eigen::Vector3d& size_m,
                                     double spacing_m = 0.06);

/// One slab of the part: offsets along the surface normal, mm (bottom < top; `top` is the
/// face towards the head).
struct Slab {
  const geom::Surface* surface = nullptr;
  double bottom_mm = 0.0;
  double top_mm = 0.0;
};

/// The deepest reach of a body into a slab.
struct SlabDepth {
  double depth_m = 0.0;  ///< how far below the slab's top face the body reaches, 0..thickness
  Eigen::Vector3d point_world_m = Eigen::Vector3d::Zero();  ///< that deepest point
};

/// Depth of the body (carried by `body_world`) into `slab` (part frame at `part_world`): over
/// the body's points whose foot point lies inside the surface's domain, the largest
/// (top - signed distance + radius), clipped to 0..thickness (a point beyond the bottom face
/// has gone through). nullopt when no point lies over the domain.
std::optional<SlabDepth> DeepestInSlab(const DepthGeometry& body,
                                       const Eigen::Isometry3d& body_world,
                                       const Eigen::Isometry3d& part_world, const Slab& slab);

/// True when the world point lies inside the closed slab (over the domain, between the faces).
bool InsideSlab(const Eigen::Vector3d& point_world_m, const Eigen::Isometry3d& part_world,
                const Slab& slab);

}  // namespace stitchsim::sim::detail
