#include "stitchsim/process/afp_tows.h"

#include <cmath>
#include <limits>

#include "stitchsim/geom/surface_walk.h"

namespace stitchsim::process {
namespace {

// Grid cells per direction searched for the near side when a projection landed on the far one.
constexpr int kNearSideGrid = 48;

// The foot of `p` on the side of the surface whose normal faces `z` (the head): Gauss-Newton
// from the nearest grid point that faces it. Rare (a far-side projection); about 2,400 surface
// evaluations.
geom::SurfaceFoot NearSideFoot(const geom::Surface& s, const Eigen::Vector3d& p,
                               const Eigen::Vector3d& z) {
  const geom::Domain2 d = s.Domain();
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best_uv = Eigen::Vector2d::Zero();
  for (int i = 0; i <= kNearSideGrid; ++i) {
    for (int k = 0; k <= kNearSideGrid; ++k) {
      const Eigen::Vector2d uv =
          d.min +
          (d.max - d.min).cwiseProduct(Eigen::Vector2d(i, k) / static_cast<double>(kNearSideGrid));
      const double dist = (s.Point(uv) - p).squaredNorm();
      if (dist < best && s.Normal(uv).dot(z) > 0.0) {
        best = dist;
        best_uv = uv;
      }
    }
  }
  if (!std::isfinite(best)) return {};
  return geom::ProjectNear(s, p, best_uv);
}

}  // namespace

TowLayout TowLayoutOf(const scene::HeadSpec& head) {
  return TowLayout{head.afp.tows, head.afp.tow_width_mm};
}

double TowCentreOffset(const TowLayout& layout, int tow) {
  return (tow - 0.5 * (layout.tows + 1)) * layout.width_mm;
}

std::uint64_t AllTows(const TowLayout& layout) {
  return layout.tows >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << layout.tows) - 1;
}

TowBand PlyTowBand(const TowLayout& head, int count) {
  return TowBand{(head.tows - count) / 2 + 1, count};
}

double BandCentreOffset(const TowLayout& head, const TowBand& band) {
  return 0.5 * (TowCentreOffset(head, band.first) + TowCentreOffset(head, band.Last()));
}

std::uint64_t BandTows(const TowBand& band) {
  const std::uint64_t ones =
      band.count >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << band.count) - 1;
  return ones << (band.first - 1);
}

TowCross TowsAt(const geom::Surface& surface, const Eigen::Isometry3d& tool_part,
                const TowLayout& layout, const Eigen::Vector2d* uv_hint, double max_substep_mm) {
  return TowsAt(surface, tool_part, layout, WholeHead(layout), uv_hint, max_substep_mm);
}

TowCross TowsAt(const geom::Surface& surface, const Eigen::Isometry3d& tool_part,
                const TowLayout& layout, const TowBand& band, const Eigen::Vector2d* uv_hint,
                double max_substep_mm) {
  TowCross out;
  if (!(max_substep_mm > 0)) max_substep_mm = 0.5 * layout.width_mm;
  const Eigen::Vector3d p = tool_part.translation();
  // The global closest point (the hint only speeds the search: a descent from a hint on the
  // other skin of a closed wing would stay there), refined by the same local step as before.
  const geom::SurfaceProjection proj =
      uv_hint != nullptr ? surface.ProjectFrom(p, *uv_hint) : surface.Project(p);
  if (!proj.inside_domain) return out;
  geom::SurfaceFoot foot = geom::ProjectNear(surface, p, proj.uv);
  // The roller presses on the side of the surface its head axis comes from. On a thin or
  // closed part (a wing's skin wraps round its section) the closest point can lie on the far
  // side; then start again from the nearest of a grid of points that face the head.
  const Eigen::Vector3d z = tool_part.linear().col(2);
  if (foot.converged && surface.Normal(foot.uv).dot(z) <= 0.0) foot = NearSideFoot(surface, p, z);
  if (!foot.converged) return out;
  if (!surface.Domain().Contains(foot.uv, 1e-6)) return out;
  out.centre_uv = foot.uv;
  out.centre = foot.point;
  const int k = layout.tows;
  // The head's boundaries lo .. hi are the band's 0 .. band.count.
  const int lo = band.first - 1, hi = band.Last();
  out.boundary_uv.resize(static_cast<std::size_t>(band.count) + 1);
  out.boundary.resize(static_cast<std::size_t>(band.count) + 1);
  out.across.resize(static_cast<std::size_t>(band.count) + 1);
  const Eigen::Vector3d x = tool_part.linear().col(0);
  // Walk right from the centre, then left, stopping at every head boundary on the way (the
  // same walk whichever band is asked for) until the band's last one.
  for (const double sign : {1.0, -1.0}) {
    geom::SurfaceFoot at = foot;
    double walked = 0.0;  // along the surface from the centre, signed
    Eigen::Vector3d dir = sign * x;
    for (int b = sign > 0 ? (k + 1) / 2 : k / 2; sign > 0 ? b <= hi : b >= lo;
         b += sign > 0 ? 1 : -1) {
      const double target = (b - 0.5 * k) * layout.width_mm;  // boundary b's offset
      const double step = std::abs(target - walked);
      const geom::SurfaceFoot next = geom::WalkOnSurface(surface, at.uv, dir, step, max_substep_mm);
      if (!next.converged || !surface.Domain().Contains(next.uv, 1e-6)) return out;
      // Keep walking outwards along the same geodesic.
      dir = next.tangent;
      at = next;
      walked = target;
      if (b < lo || b > hi) continue;
      out.boundary_uv[static_cast<std::size_t>(b - lo)] = at.uv;
      out.boundary[static_cast<std::size_t>(b - lo)] = at.point;
      out.across[static_cast<std::size_t>(b - lo)] = sign * at.tangent;
    }
  }
  out.ok = true;
  return out;
}

}  // namespace stitchsim::process
