// Depth of a primitive into a part slab, measured on the analytic surface (slab_depth.h).
#include "detail/slab_depth.h"

#include <algorithm>
#include <cmath>

#include "stitchsim/common/units.h"

namespace stitchsim::sim::detail {
namespace {

constexpr int kMaxFaceIntervals = 4;
constexpr int kMaxIntervals = 24;
constexpr double kRefineM = 0.0002;      // face refinement stops at steps this small
constexpr double kRefineWithinMm = 2.0;  // faces refined: grid depth this close to the best

int Intervals(double length_m, double spacing_m, int max_intervals) {
  return std::clamp(static_cast<int>(std::ceil(length_m / spacing_m - 1e-9)), 1, max_intervals);
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
  const int along = Intervals(2 * hl, spacing_m, kMaxIntervals);
  for (int i = 0; i <= along; ++i) ring(r, -hl + 2 * hl * i / along);
  const int radial = Intervals(r, spacing_m, kMaxIntervals);
  for (double z : {-hl, hl}) {
    out.push_back({Eigen::Vector3d(0, 0, z), 0.0});
    for (int i = 1; i < radial; ++i) ring(r * i / radial, z);
  }
}

// One point's depth into the slab, with its deepest point (part frame, mm).
struct PointDepth {
  double depth_mm = -1.0;  // < 0: not over the domain
  Eigen::Vector3d deepest_mm = Eigen::Vector3d::Zero();
};

class SlabProbe {
 public:
  SlabProbe(const Eigen::Isometry3d& body_in_part, const Slab& slab)
      : body_in_part_(body_in_part), slab_(slab) {}
  PointDepth At(const Eigen::Vector3d& point_m, double radius_m) const {
    const Eigen::Vector3d p_mm = 1000.0 * (body_in_part_ * point_m);
    const geom::SurfaceProjection pr = slab_.surface->Project(p_mm);
    if (!pr.inside_domain) return {};
    const double radius_mm = 1000.0 * radius_m;
    // The deepest point of a sample's ball lies along -normal from its centre.
    return {std::clamp(slab_.top_mm - pr.signed_distance_mm + radius_mm, 0.0,
                       slab_.top_mm - slab_.bottom_mm),
            p_mm - radius_mm * pr.normal};
  }

 private:
  Eigen::Isometry3d body_in_part_;
  const Slab& slab_;
};

// The deepest grid point of a face, with its (s, t).
struct FaceBest {
  PointDepth d;
  double s = 0.0, t = 0.0;
};

PointDepth OnFace(const DepthFace& f, const SlabProbe& probe, double s, double t) {
  return probe.At(f.origin + s * f.u + t * f.v, 0.0);
}

FaceBest DeepestOnGrid(const DepthFace& f, const SlabProbe& probe) {
  FaceBest best;
  for (int i = 0; i <= f.nu; ++i) {
    for (int j = 0; j <= f.nv; ++j) {
      const double s = static_cast<double>(i) / f.nu, t = static_cast<double>(j) / f.nv;
      const PointDepth d = OnFace(f, probe, s, t);
      if (d.depth_mm > best.d.depth_mm) best = {d, s, t};
    }
  }
  return best;
}

// A compass search on the face from its deepest grid point, the steps halved to kRefineM.
PointDepth Refine(const DepthFace& f, const SlabProbe& probe, FaceBest best) {
  double ds = 0.5 / f.nu, dt = 0.5 / f.nv;
  const double lu = f.u.norm(), lv = f.v.norm();
  for (int iter = 0; iter < 64 && (ds * lu > kRefineM || dt * lv > kRefineM); ++iter) {
    const double cand[4][2] = {
        {best.s + ds, best.t}, {best.s - ds, best.t}, {best.s, best.t + dt}, {best.s, best.t - dt}};
    bool moved = false;
    for (const auto& c : cand) {
      const double s = std::clamp(c[0], 0.0, 1.0), t = std::clamp(c[1], 0.0, 1.0);
      if (s == best.s && t == best.t) continue;  // clamped onto the current point
      const PointDepth d = OnFace(f, probe, s, t);
      if (d.depth_mm > best.d.depth_mm + 1e-9) {
        best = {d, s, t};
        moved = true;
      }
    }
    if (!moved) {
      ds *= 0.5;
      dt *= 0.5;
    }
  }
  return best.d;
}

}  // namespace

DepthGeometry PrimitiveDepthGeometry(MjcfShape shape, const Eigen::Vector3d& size_m,
                                     double spacing_m) {
  DepthGeometry out;
  switch (shape) {
    case MjcfShape::kBox:
      for (int axis = 0; axis < 3; ++axis) {
        const int b = (axis + 1) % 3, c = (axis + 2) % 3;
        for (double sign : {-1.0, 1.0}) {
          DepthFace f;
          f.origin[axis] = sign * size_m[axis];
          f.origin[b] = -size_m[b];
          f.origin[c] = -size_m[c];
          f.u[b] = 2 * size_m[b];
          f.v[c] = 2 * size_m[c];
          f.nu = Intervals(2 * size_m[b], spacing_m, kMaxFaceIntervals);
          f.nv = Intervals(2 * size_m[c], spacing_m, kMaxFaceIntervals);
          out.faces.push_back(f);
        }
      }
      break;
    case MjcfShape::kSphere:
      out.samples.push_back({Eigen::Vector3d::Zero(), size_m.x()});
      break;
    case MjcfShape::kCapsule: {
      const int n = Intervals(2 * size_m.y(), spacing_m / 6, kMaxIntervals);
      for (int i = 0; i <= n; ++i) {
        out.samples.push_back(
            {Eigen::Vector3d(0, 0, -size_m.y() + 2 * size_m.y() * i / n), size_m.x()});
      }
      break;
    }
    case MjcfShape::kCylinder:
      CylinderSamples(size_m.x(), size_m.y(), spacing_m / 6, out.samples);
      break;
    case MjcfShape::kPlane:
      break;
  }
  return out;
}

std::optional<SlabDepth> DeepestInSlab(const DepthGeometry& body,
                                       const Eigen::Isometry3d& body_world,
                                       const Eigen::Isometry3d& part_world, const Slab& slab) {
  const SlabProbe probe(part_world.inverse() * body_world, slab);
  PointDepth best;
  for (const DepthSample& s : body.samples) {
    const PointDepth d = probe.At(s.point_m, s.radius_m);
    if (d.depth_mm > best.depth_mm) best = d;
  }
  // Faces: every grid, then refined only where a grid came within kRefineWithinMm of the
  // deepest point found (a grid misses at most the sag of the surface over one cell).
  std::vector<FaceBest> grids;
  grids.reserve(body.faces.size());
  for (const DepthFace& f : body.faces) {
    grids.push_back(DeepestOnGrid(f, probe));
    if (grids.back().d.depth_mm > best.depth_mm) best = grids.back().d;
  }
  const double grid_best_mm = best.depth_mm;
  for (std::size_t k = 0; k < grids.size(); ++k) {
    if (grids[k].d.depth_mm < 0.0 || grids[k].d.depth_mm < grid_best_mm - kRefineWithinMm) {
      continue;
    }
    const PointDepth d = Refine(body.faces[k], probe, grids[k]);
    if (d.depth_mm > best.depth_mm) best = d;
  }
  if (best.depth_mm < 0.0) return std::nullopt;
  return SlabDepth{best.depth_mm / 1000.0, part_world * (best.deepest_mm / 1000.0)};
}

bool InsideSlab(const Eigen::Vector3d& point_world_m, const Eigen::Isometry3d& part_world,
                const Slab& slab) {
  const geom::SurfaceProjection pr =
      slab.surface->Project(1000.0 * (part_world.inverse() * point_world_m));
  return pr.inside_domain && pr.signed_distance_mm >= slab.bottom_mm &&
         pr.signed_distance_mm <= slab.top_mm;
}

}  // namespace stitchsim::sim::detail
