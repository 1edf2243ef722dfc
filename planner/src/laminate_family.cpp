#include "stitchsim/planner/laminate_family.h"

#include <cmath>
#include <limits>
#include <optional>

#include "stitchsim/geom/surface_walk.h"

namespace stitchsim::planner {
namespace {

using geom::Tangential;

// A point on a polyline curve: segment j, fraction s, on the surface.
struct OnCurve {
  std::size_t j = 0;
  double s = 0.0;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();
};

// Angle from a to b about n (both in the tangent plane of n).
double SignedAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& n) {
  return std::atan2(n.dot(a.cross(b)), a.dot(b));
}

OnCurve Locate(const geom::Surface& surface, const SurfaceCurve& c, std::size_t j, double s) {
  const CurvePoint& a = c[j];
  const CurvePoint& b = c[std::min(j + 1, c.size() - 1)];
  const geom::SurfaceFoot f = geom::ProjectNear(surface, a.position + s * (b.position - a.position),
                                                a.uv + s * (b.uv - a.uv));
  OnCurve out;
  out.j = j;
  out.s = s;
  out.uv = f.uv;
  out.position = f.point;
  out.normal = surface.Normal(f.uv);
  out.tangent = Tangential(a.tangent + s * (b.tangent - a.tangent), out.normal);
  return out;
}

// Where the plane through p with normal m cuts curve c, on the side of `ahead`, nearest p.
std::optional<OnCurve> CutCurve(const geom::Surface& surface, const SurfaceCurve& c,
                                const Eigen::Vector3d& p, const Eigen::Vector3d& m,
                                const Eigen::Vector3d& ahead) {
  std::optional<OnCurve> best;
  double best_dist = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j + 1 < c.size(); ++j) {
    const double f0 = m.dot(c[j].position - p);
    const double f1 = m.dot(c[j + 1].position - p);
    if ((f0 > 0 && f1 > 0) || (f0 < 0 && f1 < 0) || f0 == f1) continue;
    const double s = f0 / (f0 - f1);
    const Eigen::Vector3d x = c[j].position + s * (c[j + 1].position - c[j].position);
    const double dist = (x - p).norm();
    if (ahead.dot(x - p) <= 0 || dist >= best_dist) continue;
    best_dist = dist;
    best = Locate(surface, c, j, s);
  }
  return best;
}

// Geodesic curvature of curve c at segment j, positive when it turns towards N x T.
double GeodesicCurvature(const SurfaceCurve& c, std::size_t j) {
  if (c.size() < 3) return 0.0;
  const std::size_t k = std::clamp<std::size_t>(j, 1, c.size() - 2);
  const Eigen::Vector3d& n = c[k].normal;
  const Eigen::Vector3d a = Tangential(c[k].position - c[k - 1].position, n);
  const Eigen::Vector3d b = Tangential(c[k + 1].position - c[k].position, n);
  const double len = 0.5 * ((c[k].position - c[k - 1].position).norm() +
                            (c[k + 1].position - c[k].position).norm());
  return SignedAngle(a, b, n) / len;
}

struct Segment {
  OnCurve to;
  double leave_rad = 0.0;
  double arrive_rad = 0.0;
};

std::optional<Segment> Launch(const geom::Surface& surface, const SurfaceCurve& next,
                              const OnCurve& from, double phi) {
  const Eigen::Vector3d side = from.normal.cross(from.tangent);
  const Eigen::Vector3d o = std::cos(phi) * from.tangent + std::sin(phi) * side;
  const std::optional<OnCurve> to =
      CutCurve(surface, next, from.position, o.cross(from.normal).normalized(), o);
  if (!to) return std::nullopt;
  const Eigen::Vector3d d = to->position - from.position;
  Segment seg{*to, SignedAngle(from.tangent, Tangential(d, from.normal), from.normal),
              SignedAngle(to->tangent, Tangential(d, to->normal), to->normal)};
  return seg;
}

// Eq. 4 with the curve at `from` as a circle: its radius from the geodesic curvature, d from
// the circle's centre to the crossing reached (negative when the next curve lies inside).
double Eq4Error(const SurfaceCurve& c, const OnCurve& from, const OnCurve& to, double theta) {
  const double k = GeodesicCurvature(c, from.j);
  if (std::abs(k) < 1e-12) return 0.0;
  const Eigen::Vector3d centre = from.position + from.normal.cross(from.tangent) / k;
  return LaminateAngleError(1.0 / std::abs(k), (to.position - centre).norm() - 1.0 / std::abs(k),
                            theta);
}

// The laminate curve's angle at each crossing: inside, the mean of the arriving and leaving
// segments' angles (the tangent of a smooth curve through the crossings); at the ends, the
// segment's angle mirrored about the neighbour's turn, as offset curves' end tangents are.
void SetCrossingAngles(std::vector<LaminateCrossing>& x) {
  const std::size_t n = x.size();
  for (std::size_t i = 1; i + 1 < n; ++i)
    x[i].crossing_rad = 0.5 * (x[i].arrive_rad + x[i].leave_rad);
  if (n < 2) return;
  x[0].crossing_rad = x[0].leave_rad;
  x[n - 1].crossing_rad = x[n - 1].arrive_rad;
  if (n < 3) return;
  x[0].crossing_rad -= 0.5 * (x[1].leave_rad - x[1].arrive_rad);
  x[n - 1].crossing_rad += 0.5 * (x[n - 2].leave_rad - x[n - 2].arrive_rad);
}

}  // namespace

LaminateCurve LaminateFamilyCurve(const geom::Surface& surface,
                                  const std::vector<SurfaceCurve>& curves, std::size_t start_index,
                                  const LaminateOptions& options) {
  LaminateCurve out;
  if (curves.empty() || curves[0].size() < 2 || start_index >= curves[0].size()) {
    out.message = "laminate family: needs a start point on a first curve of two points or more";
    return out;
  }
  const double theta = options.theta_rad;
  const std::size_t j0 = std::min(start_index, curves[0].size() - 2);
  OnCurve at = Locate(surface, curves[0], j0, start_index == j0 ? 0.0 : 1.0);
  out.crossings.push_back({0, at.position, 0.0, 0.0, 0.0, 0.0});
  for (std::size_t i = 0; i + 1 < curves.size(); ++i) {
    double phi = theta;
    std::optional<Segment> seg = Launch(surface, curves[i + 1], at, phi);
    for (int iter = 0; options.corrected && seg && iter < 30; ++iter) {
      // The segment is the chord of a curve meeting both offset curves at theta.
      const double g = 0.5 * (seg->leave_rad + seg->arrive_rad) - theta;
      if (std::abs(g) < options.tolerance_rad) break;
      phi -= g;
      seg = Launch(surface, curves[i + 1], at, phi);
    }
    if (!seg) {
      out.message = "laminate family: the plane misses curve " + std::to_string(i + 1);
      SetCrossingAngles(out.crossings);
      return out;
    }
    out.crossings.back().leave_rad = seg->leave_rad;
    LaminateCrossing next{
        i + 1,           seg->to.position, 0.0,
        seg->arrive_rad, seg->arrive_rad,  Eq4Error(curves[i], at, seg->to, theta)};
    out.crossings.push_back(next);
    at = seg->to;
  }
  SetCrossingAngles(out.crossings);
  out.ok = true;
  return out;
}

}  // namespace stitchsim::planner
