// The constant-angle reference course of a ply (`reference: path: constant_angle`): the
// streamline of the ply's design fibre direction field through the origin's foot point.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "ply_course.h"
#include "stitchsim/geom/surface_walk.h"
#include "stitchsim/planner/ply_planner.h"

namespace stitchsim::planner {
namespace {

/// Below this |projection . normal| (unit vectors) the reference does not project onto the
/// tangent plane (the projection runs within it).
constexpr double kMinProjectionAlong = 1e-6;

/// The unit design direction at `uv`, oriented along `previous` (a fibre direction is a line,
/// its sign is the walk's); nullopt where the reference does not project.
std::optional<Eigen::Vector3d> FieldAlong(const geom::Surface& surface, const scene::PlySpec& ply,
                                          double angle_rad, const Eigen::Vector2d& uv,
                                          const Eigen::Vector3d& previous) {
  std::optional<Eigen::Vector3d> d = DesignFiberDirection(ply, angle_rad, surface.Normal(uv));
  if (!d) return std::nullopt;
  return d->dot(previous) < 0.0 ? Eigen::Vector3d(-*d) : *d;
}

/// The streamline from the foot point `start` along `heading`, RK4 in (u, v) in arc-length
/// steps of `step_mm`, `start` first, until it leaves `region` after having been inside it,
/// leaves the domain, the field stops projecting, or it has run the region's diagonal plus
/// the start's distance from the region twice over (a closed streamline).
SurfaceCurve Streamline(const geom::Surface& surface, const scene::PlySpec& ply, double angle_rad,
                        const Eigen::Vector2d& start, const Eigen::Vector3d& heading,
                        const geom::Domain2& region, double step_mm) {
  SurfaceCurve out;
  Eigen::Vector2d uv = start;
  Eigen::Vector3d along = heading;
  const geom::Domain2 domain = surface.Domain();
  // d(u, v)/ds at `at`, or nullopt off the domain or where the field does not project.
  auto rate = [&](const Eigen::Vector2d& at) -> std::optional<Eigen::Vector2d> {
    if (!domain.Contains(at)) return std::nullopt;
    const auto d = FieldAlong(surface, ply, angle_rad, at, along);
    if (!d) return std::nullopt;
    return geom::UvOfTangent(surface, at, *d);
  };
  const Eigen::Vector2d centre = 0.5 * (region.min + region.max);
  const double reach = (region.max - region.min).norm() + (start - centre).norm();
  const int max_steps = static_cast<int>(std::ceil(2.0 * reach / step_mm)) + 16;
  bool entered = false;
  for (int i = 0; i <= max_steps && domain.Contains(uv); ++i) {
    const bool inside = region.Contains(uv);
    if (entered && !inside) break;
    entered = entered || inside;
    CurvePoint p;
    p.uv = uv;
    p.position = surface.Point(uv);
    p.normal = surface.Normal(uv);
    const auto d = FieldAlong(surface, ply, angle_rad, uv, along);
    if (!d) break;
    p.tangent = *d;
    along = *d;
    out.push_back(p);
    const auto k1 = rate(uv);
    const auto k2 = k1 ? rate(uv + 0.5 * step_mm * *k1) : std::nullopt;
    const auto k3 = k2 ? rate(uv + 0.5 * step_mm * *k2) : std::nullopt;
    const auto k4 = k3 ? rate(uv + step_mm * *k3) : std::nullopt;
    if (!k4) break;
    uv += step_mm / 6.0 * (*k1 + 2.0 * *k2 + 2.0 * *k3 + *k4);
  }
  return out;
}

}  // namespace

std::optional<Eigen::Vector3d> DesignFiberDirection(const scene::PlySpec& ply, double angle_rad,
                                                    const Eigen::Vector3d& normal) {
  const double along = ply.projection.normalized().dot(normal);
  if (std::abs(along) < kMinProjectionAlong) return std::nullopt;
  const Eigen::Vector3d d0 =
      ply.direction - (ply.direction.dot(normal) / ply.projection.dot(normal)) * ply.projection;
  if (d0.norm() < kMinProjectionAlong * ply.direction.norm()) return std::nullopt;
  return Eigen::AngleAxisd(angle_rad, normal) * d0.normalized();
}

ReferenceCurve ConstantAngleReference(const geom::Surface& surface, const scene::PlySpec& ply,
                                      double angle_rad, const geom::Domain2& region,
                                      double step_mm) {
  ReferenceCurve out;
  const Eigen::Vector2d foot = surface.Project(ply.origin_mm).uv;
  const auto d = DesignFiberDirection(ply, angle_rad, surface.Normal(foot));
  if (!d || !(step_mm > 0.0)) {
    out.message = "the reference direction of ply '" + ply.name +
                  "' does not project onto the surface at its origin";
    return out;
  }
  const SurfaceCurve ahead = Streamline(surface, ply, angle_rad, foot, *d, region, step_mm);
  const SurfaceCurve behind = Streamline(surface, ply, angle_rad, foot, -*d, region, step_mm);
  if (!behind.empty()) out.points = Reversed(SurfaceCurve(behind.begin() + 1, behind.end()));
  out.points.insert(out.points.end(), ahead.begin(), ahead.end());
  out.ok = out.points.size() >= 2;
  if (!out.ok)
    out.message = "the constant-angle reference of ply '" + ply.name + "' does not cross the ply";
  return out;
}

}  // namespace stitchsim::planner
