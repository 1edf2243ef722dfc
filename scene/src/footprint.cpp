#include "stitchsim/scene/footprint.h"

#include <algorithm>
#include <cmath>

namespace stitchsim::scene {
namespace {

// Slab test of the segment la + t d, t in [0, 1], against |x_k| <= half_k for k < dims (local
// coordinates): the parameter range inside, false if the segment misses.
template <typename Vec>
bool ClipToSlabs(const Vec& la, const Vec& d, const Vec& half, int dims, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  for (int k = 0; k < dims; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(la[k]) > half[k]) return false;
      continue;
    }
    double ta = (-half[k] - la[k]) / d[k];
    double tb = (half[k] - la[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

// The box of a constraint before any margin: pose and half extents (a mesh: the axis-aligned
// bounding box of its vertices).
struct RawBox {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half_mm = Eigen::Vector3d::Zero();
  bool from_mesh = false;
  Eigen::Vector3d mesh_centre = Eigen::Vector3d::Zero();
};

RawBox RawBoxOf(const Constraint& c) {
  RawBox b;
  b.half_mm = 0.5 * c.size_mm;
  b.rotation = c.pose_mm.linear();
  if (c.shape == Constraint::Shape::kMesh && !c.mesh.vertices.empty()) {
    Eigen::AlignedBox3d box;
    for (const auto& v : c.mesh.vertices) box.extend(v);
    b.from_mesh = true;
    b.mesh_centre = box.center();
    b.half_mm = 0.5 * box.sizes();
    b.rotation.setIdentity();
  }
  return b;
}

// Closest points of the box's corners and of points at most 10 mm apart along its 12 edges
// (the box: centre, rotation, half extents), as (u, v) on `s`; false if one is not finite.
bool ProjectBoxOutline(const geom::Surface& s, const Eigen::Vector3d& centre,
                       const Eigen::Matrix3d& rotation, const Eigen::Vector3d& half,
                       std::vector<Eigen::Vector2d>& uvs) {
  constexpr double kStepMm = 10.0;
  constexpr int kMaxSteps = 4000;
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const int steps =
        std::clamp(static_cast<int>(std::ceil(2.0 * half[axis] / kStepMm)), 1, kMaxSteps);
    for (int corner = 0; corner < 4; ++corner) {
      Eigen::Vector3d local = Eigen::Vector3d::Zero();
      local[a] = (corner & 1) ? half[a] : -half[a];
      local[b] = (corner & 2) ? half[b] : -half[b];
      for (int k = 0; k <= steps; ++k) {
        local[axis] = half[axis] * (2.0 * k / steps - 1.0);
        const Eigen::Vector2d uv = s.Project(centre + rotation * local).uv;
        if (!uv.allFinite()) return false;
        uvs.push_back(uv);
      }
    }
  }
  return true;
}

}  // namespace

double GrownBox::Depth(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d q = to_local * p;
  double depth = 1e300;
  for (int k = 0; k < 3; ++k) depth = std::min(depth, half_mm[k] - std::abs(q[k]));
  return depth;
}

double GrownBox::SegmentDepth(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  const Eigen::Vector3d la = to_local * a;
  const Eigen::Vector3d d = to_local * b - la;
  double t0 = 0.0, t1 = 1.0;
  if (!ClipToSlabs(la, d, half_mm, 3, t0, t1)) return -1.0;
  return std::max(0.0, Depth(a + (b - a) * (0.5 * (t0 + t1))));
}

bool Footprint::Contains(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d d = p - centre;
  return std::abs(d.dot(axis_x)) <= half_mm.x() && std::abs(d.dot(axis_y)) <= half_mm.y();
}

double Footprint::Depth(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d d = p - centre;
  return std::min(half_mm.x() - std::abs(d.dot(axis_x)), half_mm.y() - std::abs(d.dot(axis_y)));
}

bool Footprint::Crosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const Eigen::Vector2d la((a - centre).dot(axis_x), (a - centre).dot(axis_y));
  const Eigen::Vector2d lb((b - centre).dot(axis_x), (b - centre).dot(axis_y));
  double t0 = 0.0, t1 = 1.0;
  return ClipToSlabs(la, Eigen::Vector2d(lb - la), half_mm, 2, t0, t1);
}

double Footprint::SegmentDepth(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const Eigen::Vector2d la((a - centre).dot(axis_x), (a - centre).dot(axis_y));
  const Eigen::Vector2d lb((b - centre).dot(axis_x), (b - centre).dot(axis_y));
  double t0 = 0.0, t1 = 1.0;
  if (!ClipToSlabs(la, Eigen::Vector2d(lb - la), half_mm, 2, t0, t1)) return -1.0;
  return std::max(0.0, Depth(a + (b - a) * (0.5 * (t0 + t1))));
}

bool Footprint::RowInterval(double y, double& x_min, double& x_max) const {
  // The line (t, y): solve |(p - c).ax| <= hx and |(p - c).ay| <= hy for t.
  double lo = -1e300, hi = 1e300;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d& ax = k == 0 ? axis_x : axis_y;
    const double base = (y - centre.y()) * ax.y() - centre.x() * ax.x();
    if (std::abs(ax.x()) < 1e-12) {
      if (std::abs(base) > half_mm[k]) return false;
      continue;
    }
    double a = (-half_mm[k] - base) / ax.x();
    double b = (half_mm[k] - base) / ax.x();
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
  if (lo > hi) return false;
  x_min = lo;
  x_max = hi;
  return true;
}

GrownBox ConstraintBox(const Constraint& c, double margin_mm) {
  const RawBox raw = RawBoxOf(c);
  GrownBox b;
  b.name = c.name;
  b.to_local = raw.from_mesh ? Eigen::Isometry3d(Eigen::Translation3d(-raw.mesh_centre))
                             : c.pose_mm.inverse();
  b.half_mm = raw.half_mm;
  b.half_mm.array() += margin_mm;
  return b;
}

Footprint ConstraintFootprint(const Constraint& c, double margin_mm) {
  const RawBox raw = RawBoxOf(c);
  Footprint f;
  f.name = c.name;
  f.centre = raw.from_mesh ? Eigen::Vector2d(raw.mesh_centre.head<2>())
                           : Eigen::Vector2d(c.pose_mm.translation().head<2>());
  Eigen::Vector2d ax = raw.rotation.col(0).head<2>();
  if (ax.norm() < 1e-9) ax = Eigen::Vector2d::UnitX();
  f.axis_x = ax.normalized();
  f.axis_y = Eigen::Vector2d(-f.axis_x.y(), f.axis_x.x());
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d& a = k == 0 ? f.axis_x : f.axis_y;
    double h = 0.0;
    for (int i = 0; i < 3; ++i) {
      h += std::abs(Eigen::Vector2d(raw.rotation.col(i).head<2>()).dot(a)) * raw.half_mm[i];
    }
    f.half_mm[k] = h + margin_mm;
  }
  return f;
}

std::vector<Footprint> ConstraintFootprints(const Scene& scene, double margin_mm) {
  std::vector<Footprint> out;
  out.reserve(scene.constraints.size());
  for (const Constraint& c : scene.constraints) out.push_back(ConstraintFootprint(c, margin_mm));
  return out;
}

std::optional<Footprint> ConstraintFootprintOn(const Constraint& c, const geom::Surface& s,
                                               double margin_mm, std::string& error) {
  if (s.IsHeightField()) return ConstraintFootprint(c, margin_mm);
  const RawBox raw = RawBoxOf(c);
  const Eigen::Vector3d centre = raw.from_mesh ? raw.mesh_centre : c.pose_mm.translation();
  const geom::SurfaceProjection foot = s.Project(centre);
  if (!foot.inside_domain || !foot.uv.allFinite()) {
    error = "its centre's closest point on the surface lies outside the surface's domain";
    return std::nullopt;
  }
  // Grown along the two box axes most tangent to the surface, not along its height.
  int height_axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(raw.rotation.col(k).dot(foot.normal)) >
        std::abs(raw.rotation.col(height_axis).dot(foot.normal)))
      height_axis = k;
  }
  Eigen::Vector3d half = raw.half_mm;
  for (int k = 0; k < 3; ++k) {
    if (k != height_axis) half[k] += margin_mm;
  }
  std::vector<Eigen::Vector2d> uvs;
  if (!ProjectBoxOutline(s, centre, raw.rotation, half, uvs)) {
    error = "a point of its box has no closest point on the surface";
    return std::nullopt;
  }
  // The first box axis across the height, mapped into (u, v) by the Jacobian's pseudo-inverse.
  const Eigen::Matrix<double, 3, 2> j = s.Jacobian(foot.uv);
  const Eigen::Matrix2d jtj = j.transpose() * j;
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();
  for (int k = 0; k < 3; ++k) {
    if (k == height_axis) continue;
    const Eigen::Vector2d d = jtj.ldlt().solve(j.transpose() * raw.rotation.col(k));
    if (d.allFinite() && d.norm() > 1e-9) axis = d.normalized();
    break;
  }
  Footprint f;
  f.name = c.name;
  f.axis_x = axis;
  f.axis_y = Eigen::Vector2d(-axis.y(), axis.x());
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = Eigen::Vector2d::Constant(-1e300);
  for (const Eigen::Vector2d& uv : uvs) {
    const Eigen::Vector2d q((uv - foot.uv).dot(f.axis_x), (uv - foot.uv).dot(f.axis_y));
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const Eigen::Vector2d mid = 0.5 * (lo + hi);
  f.centre = foot.uv + mid.x() * f.axis_x + mid.y() * f.axis_y;
  f.half_mm = 0.5 * (hi - lo);
  return f;
}

Eigen::Vector2d FootprintPlanePoint(const geom::Surface& s, const Eigen::Vector3d& p) {
  if (s.IsHeightField()) return p.head<2>();
  return s.Project(p).uv;
}

}  // namespace stitchsim::scene
