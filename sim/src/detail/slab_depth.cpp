// Depth of a primitive into a part slab, measured on the analytic surface (slab_depth.h).
#include "detail/slab_depth.h"

#include <algorithm>
#include <cmath>

namespace stitchsim::sim::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxIntervals = 24;

int Intervals(double length_m, double spacing_m) {
  return std::clamp(static_cast<int>(std::ceil(length_m / spacing_m - 1e-9)), 1, kMaxIntervals);
}

// The six faces of a box of half extents `h`, each a grid.
void BoxSamples(const Eigen::Vector3d& h, double spacing_m, std::vector<DepthSample>& out) {
  for (int axis = 0; axis < 3; ++axis) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    const int nb = Intervals(2 * h[b], spacing_m), nc = Intervals(2 * h[c], spacing_m);
    for (double sign : {-1.0, 1.0}) {
      for (int i = 0; i <= nb; ++i) {
        for (int j = 0; j <= nc; ++j) {
          Eigen::Vector3d p;
          p[axis] = sign * h[axis];
          p[b] = -h[b] + 2 * h[b] * i / nb;
          p[c] = -h[c] + 2 * h[c] * j / nc;
          out.push_back({p, 0.0});
        }
      }
    }
  }
}

// Rings along the side and on both caps of a cylinder (radius r, half length hl, along z).
void CylinderSamples(double r, double hl, double spacing_m, std::vector<DepthSample>& out) {
  const int around = std::clamp(static_cast<int>(std::ceil(2 * kPi * r / spacing_m)), 8, 48);
  auto ring = [&](double radius, double z) {
    for (int k = 0; k < around; ++k) {
      const double a = 2 * kPi * k / around;
      out.push_back({Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), z), 0.0});
    }
  };
  const int along = Intervals(2 * hl, spacing_m);
  for (int i = 0; i <= along; ++i) ring(r, -hl + 2 * hl * i / along);
  const int radial = Intervals(r, spacing_m);
  for (double z : {-hl, hl}) {
    out.push_back({Eigen::Vector3d(0, 0, z), 0.0});
    for (int i = 1; i < radial; ++i) ring(r * i / radial, z);
  }
}

}  // namespace

std::vector<DepthSample> PrimitiveDepthSamples(MjcfShape shape, const Eigen::Vector3d& size_m,
                                               double spacing_m) {
  std::vector<DepthSample> out;
  switch (shape) {
    case MjcfShape::kBox:
      BoxSamples(size_m, spacing_m, out);
      break;
    case MjcfShape::kSphere:
      out.push_back({Eigen::Vector3d::Zero(), size_m.x()});
      break;
    case MjcfShape::kCapsule: {
      const int n = Intervals(2 * size_m.y(), spacing_m);
      for (int i = 0; i <= n; ++i) {
        out.push_back({Eigen::Vector3d(0, 0, -size_m.y() + 2 * size_m.y() * i / n), size_m.x()});
      }
      break;
    }
    case MjcfShape::kCylinder:
      CylinderSamples(size_m.x(), size_m.y(), spacing_m, out);
      break;
    case MjcfShape::kPlane:
      break;
  }
  return out;
}

std::optional<SlabDepth> DeepestInSlab(const std::vector<DepthSample>& samples,
                                       const Eigen::Isometry3d& body_world,
                                       const Eigen::Isometry3d& part_world, const Slab& slab) {
  const Eigen::Isometry3d body_in_part = part_world.inverse() * body_world;
  const double thickness_mm = slab.top_mm - slab.bottom_mm;
  std::optional<SlabDepth> best;
  for (const DepthSample& s : samples) {
    const Eigen::Vector3d p_mm = 1000.0 * (body_in_part * s.point_m);
    const geom::SurfaceProjection pr = slab.surface->Project(p_mm);
    if (!pr.inside_domain) continue;
    const double radius_mm = 1000.0 * s.radius_m;
    const double depth_mm =
        std::clamp(slab.top_mm - pr.signed_distance_mm + radius_mm, 0.0, thickness_mm);
    if (best && depth_mm <= best->depth_m * 1000.0) continue;
    // The deepest point of a sample's ball lies along -normal from its centre.
    const Eigen::Vector3d deepest_mm = p_mm - radius_mm * pr.normal;
    best = SlabDepth{depth_mm / 1000.0, part_world * (deepest_mm / 1000.0)};
  }
  return best;
}

bool InsideSlab(const Eigen::Vector3d& point_world_m, const Eigen::Isometry3d& part_world,
                const Slab& slab) {
  const geom::SurfaceProjection pr =
      slab.surface->Project(1000.0 * (part_world.inverse() * point_world_m));
  return pr.inside_domain && pr.signed_distance_mm >= slab.bottom_mm &&
         pr.signed_distance_mm <= slab.top_mm;
}

}  // namespace stitchsim::sim::detail
