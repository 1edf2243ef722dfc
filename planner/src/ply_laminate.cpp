// Laminate family plies (seed 002, second method): the course centre lines are laminate
// family curves at the ply angle across the offset curves of the 0 deg reference, spaced a
// course width apart across the fibres.

#include <algorithm>
#include <cmath>

#include "ply_course.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/surface_walk.h"
#include "stitchsim/planner/laminate_family.h"

namespace stitchsim::planner {
namespace {

/// `c` resampled every `step` mm of its chord length from its start (uv interpolated, lifted
/// onto the surface).
SurfaceCurve Resample(const geom::Surface& s, const SurfaceCurve& c, double step) {
  std::vector<double> len = {0.0};
  for (std::size_t i = 1; i < c.size(); ++i)
    len.push_back(len.back() + (c[i].position - c[i - 1].position).norm());
  const int n = static_cast<int>(std::floor(len.back() / step + 1e-9));
  SurfaceCurve out;
  std::size_t i = 0;
  for (int k = 0; k <= n; ++k) {
    const double at = std::min(step * k, len.back());
    while (i + 2 < c.size() && len[i + 1] < at) ++i;
    const double span = len[i + 1] - len[i];
    const double f = span > 0.0 ? std::clamp((at - len[i]) / span, 0.0, 1.0) : 0.0;
    CurvePoint p;
    p.uv = (1.0 - f) * c[i].uv + f * c[i + 1].uv;
    p.position = s.Point(p.uv);
    p.normal = s.Normal(p.uv).normalized();
    p.tangent = geom::Tangential((1.0 - f) * c[i].tangent + f * c[i + 1].tangent, p.normal);
    out.push_back(p);
  }
  return out;
}

/// A curve through laminate crossings: feet, normals and tangents from the neighbours.
SurfaceCurve FromCrossings(const geom::Surface& s, const std::vector<Eigen::Vector3d>& pts) {
  SurfaceCurve out;
  for (const Eigen::Vector3d& x : pts) {
    const geom::SurfaceProjection f = s.Project(x);
    CurvePoint p;
    p.uv = f.uv;
    p.position = f.point;
    p.normal = f.normal;
    out.push_back(p);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, out.size() - 1);
    out[i].tangent = geom::Tangential(out[b].position - out[a].position, out[i].normal);
  }
  return out;
}

}  // namespace

std::vector<SurfaceCurve> LaminateCourseLines(const LaminateInputs& in) {
  // The fibre line's angle to the 0 deg curves, in (0, pi): it heads to their left.
  double theta = std::fmod(in.angle_rad, kPi);
  if (theta <= 0.0) theta += kPi;
  // Start points a course width apart across the fibres: every `step` points of the
  // reference resampled at spacing / step (about 1 mm).
  const double spacing = in.course_width_mm / std::sin(theta);  // along the reference
  const int step = std::max(1, static_cast<int>(std::ceil(spacing)));
  const SurfaceCurve mid = Resample(in.surface, in.reference, spacing / step);
  // Offset curves of the reference by one tow width, both ways (each trimmed by `trim`).
  std::vector<SurfaceCurve> left = {mid}, right = {Reversed(mid)};
  for (int side : {1, -1}) {
    std::vector<SurfaceCurve>& out = side > 0 ? left : right;
    SurfaceCurve c = mid;
    for (int i = 0; i < 5000; ++i) {
      auto next = in.offset(c, side);
      if (!next || next->size() < 2) break;
      c = *next;
      out.push_back(side > 0 ? c : Reversed(c));
    }
  }
  LaminateOptions o;
  o.theta_rad = theta;
  std::vector<SurfaceCurve> lines;
  const std::size_t n = mid.size();
  const std::size_t first = (n - 1) % static_cast<std::size_t>(step) / 2;
  for (std::size_t j = first; j < n; j += static_cast<std::size_t>(step)) {
    const LaminateCurve l = LaminateFamilyCurve(in.surface, left, j, o);
    const LaminateCurve r = LaminateFamilyCurve(in.surface, right, n - 1 - j, o);
    std::vector<Eigen::Vector3d> pts;
    for (auto it = r.crossings.rbegin(); it != r.crossings.rend(); ++it)
      pts.push_back(it->position);
    if (!pts.empty()) pts.pop_back();  // the start point, again in `l`
    for (const auto& c : l.crossings) pts.push_back(c.position);
    if (pts.size() >= 2) lines.push_back(FromCrossings(in.surface, pts));
  }
  return lines;
}

}  // namespace stitchsim::planner
