// PlanPly: reference course, offsets in both directions, tows and their cuts per course.

#include <algorithm>
#include <cmath>

#include "ply_course.h"
#include "stitchsim/geom/polygon2.h"
#include "stitchsim/geom/surface_walk.h"
#include "stitchsim/planner/offset_curves.h"
#include "stitchsim/planner/ply_planner.h"

namespace stitchsim::planner {
namespace {

/// The ply's (u, v) bounding box grown by `margin`.
geom::Domain2 Region(const std::vector<Eigen::Vector2d>& boundary, double margin) {
  geom::Domain2 r{boundary.front(), boundary.front()};
  for (const auto& p : boundary) {
    r.min = r.min.cwiseMin(p);
    r.max = r.max.cwiseMax(p);
  }
  r.min.array() -= margin;
  r.max.array() += margin;
  return r;
}

/// The fibre axis through the ply origin at the ply angle, as far both ways as it projects
/// onto the surface inside `region`.
ReferenceCurve ReferenceCourse(const geom::Surface& surface, const scene::PlySpec& ply,
                               const geom::Domain2& region, const PlyPlanOptions& options) {
  const geom::SurfaceProjection foot = surface.Project(ply.origin_mm);
  const Eigen::Vector3d n = foot.normal;
  const Eigen::Vector3d d =
      Eigen::AngleAxisd(ply.angle_rad, n) * geom::Tangential(ply.direction, n);
  const geom::Domain2 domain = surface.Domain();
  auto projects = [&](double t) {
    Eigen::Vector3d hit;
    if (!surface.IntersectLine(ply.origin_mm + t * d, ply.projection, hit)) return false;
    const geom::SurfaceProjection f = surface.Project(hit);
    return f.inside_domain && domain.Contains(f.uv, -1e-6) && region.Contains(f.uv);
  };
  const double step = 2.0;
  const int max_steps = 200000;
  double t_max = 0.0, t_min = 0.0;
  for (int i = 0; i < max_steps && projects(t_max + step); ++i) t_max += step;
  for (int i = 0; i < max_steps && projects(t_min - step); ++i) t_min -= step;
  if (t_max - t_min < step) {
    ReferenceCurve r;
    r.message = "the fibre axis of ply '" + ply.name + "' does not cross the ply on the surface";
    return r;
  }
  FiberAxis axis{ply.origin_mm + t_min * d, ply.origin_mm + t_max * d, ply.projection};
  return ProjectFiberAxis(surface, axis, options.chord_tol_mm);
}

SurfaceCurve Reversed(SurfaceCurve c) {
  std::reverse(c.begin(), c.end());
  for (auto& p : c) p.tangent = -p.tangent;
  return c;
}

/// One offset of `curve` by `distance` to its left (side > 0: N x T) or right.
std::optional<SurfaceCurve> OffsetOnce(const geom::Surface& surface, const SurfaceCurve& curve,
                                       double distance, int side, scene::PlyOffsetMethod method) {
  OffsetOptions o;
  o.distance_mm = distance;
  o.count = 1;
  o.method =
      method == scene::PlyOffsetMethod::kPaper ? OffsetMethod::kPaper : OffsetMethod::kCorrected;
  const SurfaceCurve base = side > 0 ? curve : Reversed(curve);
  OffsetFamily f = OffsetCurves(surface, base, o);
  if (!f.ok || f.curves.size() < 2) return std::nullopt;
  return side > 0 ? f.curves[1] : Reversed(f.curves[1]);
}

/// The run of points inside `region` (the longest contiguous one).
SurfaceCurve Trim(const SurfaceCurve& c, const geom::Domain2& region) {
  std::size_t best_a = 0, best_n = 0;
  for (std::size_t i = 0; i < c.size();) {
    if (!region.Contains(c[i].uv)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < c.size() && region.Contains(c[j].uv)) ++j;
    if (j - i > best_n) best_a = i, best_n = j - i;
    i = j;
  }
  return SurfaceCurve(c.begin() + static_cast<long>(best_a),
                      c.begin() + static_cast<long>(best_a + best_n));
}

/// The longest run of points of `c` whose offset by `distance` to `side`, predicted from the
/// surface's Jacobian, stays `margin` inside the domain.
SurfaceCurve KeepOffsetOnSurface(const geom::Surface& surface, const SurfaceCurve& c,
                                 double distance, int side, double margin) {
  geom::Domain2 inner = surface.Domain();
  inner.min.array() += margin;
  inner.max.array() -= margin;
  std::size_t best_a = 0, best_n = 0, run_a = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const CurvePoint& p = c[i];
    const Eigen::Matrix<double, 3, 2> j = surface.Jacobian(p.uv);
    const Eigen::Vector3d d = side * distance * p.normal.cross(p.tangent);
    const Eigen::Vector2d duv = (j.transpose() * j).ldlt().solve(j.transpose() * d);
    if (!inner.Contains(p.uv + duv)) {
      run_a = i + 1;
    } else if (i + 1 - run_a > best_n) {
      best_a = run_a;
      best_n = i + 1 - run_a;
    }
  }
  return SurfaceCurve(c.begin() + static_cast<long>(best_a),
                      c.begin() + static_cast<long>(best_a + best_n));
}

void Summarise(PlyPlan& plan, const scene::Scene& scene) {
  std::sort(plan.courses.begin(), plan.courses.end(),
            [](const PlyCourse& a, const PlyCourse& b) { return a.offset_index < b.offset_index; });
  for (std::size_t i = 0; i < plan.courses.size(); ++i) {
    PlyCourse& c = plan.courses[i];
    c.number = static_cast<int>(i) + 1;
    plan.laid_length_mm += c.End() - c.Start();
    for (const PlyTow& t : c.tows) {
      plan.tow_segments += static_cast<int>(t.laid.size());
      plan.events += 2 * static_cast<int>(t.laid.size());
      plan.min_radius_mm = std::min(plan.min_radius_mm, t.min_radius_mm);
    }
  }
  for (std::size_t i = 0; i + 1 < plan.courses.size(); ++i) {
    CourseSeam seam = MeasureSeam(plan.courses[i], plan.courses[i + 1]);
    plan.max_gap_mm = std::max(plan.max_gap_mm, seam.max_gap_mm);
    plan.max_overlap_mm = std::max(plan.max_overlap_mm, seam.max_overlap_mm);
    plan.seams.push_back(seam);
  }
  const double limit = scene.head.afp.min_steering_radius_mm;
  if (plan.min_radius_mm < limit) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "a tow of ply '%s' is steered to a radius of %.1f mm, below the head's "
                  "minimum steering radius %.1f mm (it would wrinkle)",
                  plan.ply_name.c_str(), plan.min_radius_mm, limit);
    plan.findings.push_back({"ply-steering-radius", text});
  }
}

}  // namespace

std::optional<PlyPlan> PlanPly(const scene::Scene& scene, const scene::PlySpec& ply,
                               const PlyPlanOptions& options, DiagnosticSink& sink) {
  if (scene.head.kind != scene::HeadKind::kAfp || scene.surface == nullptr) {
    sink.Error("plan-not-afp-head", ply.where,
               "scene '" + scene.name + "' mounts head '" + scene.head.name + "', not an AFP head");
    return std::nullopt;
  }
  if (ply.rule == scene::PlyRule::kLaminateFamily) {
    sink.Error("plan-ply-rule-not-implemented", ply.where,
               "ply '" + ply.name +
                   "': rule laminate_family is not implemented yet by `plan ply` (use rule: "
                   "offset)");
    return std::nullopt;
  }
  PlyPlan plan;
  plan.ply_name = ply.name;
  plan.angle_rad = ply.angle_rad;
  plan.coverage = ply.coverage;
  plan.layout = {ply.tows, scene.head.afp.tow_width_mm};
  for (std::size_t i = 0; i < scene.plies.size(); ++i)
    if (scene.plies[i].name == ply.name) plan.ply_index = static_cast<int>(i) + 1;
  const geom::Surface& surface = *scene.surface;
  const double width = plan.layout.tows * plan.layout.width_mm;
  geom::Domain2 region = Region(ply.boundary_uv, 0.5 * width + 10.0);
  region.min = region.min.cwiseMax(surface.Domain().min);
  region.max = region.max.cwiseMin(surface.Domain().max);
  const ReferenceCurve ref = ReferenceCourse(surface, ply, region, options);
  if (!ref.ok || ref.points.size() < 2) {
    sink.Error("plan-ply-no-reference", ply.where,
               "ply '" + ply.name +
                   "': " + (ref.message.empty() ? "the fibre axis does not project" : ref.message));
    return std::nullopt;
  }
  const CourseContext ctx{surface, ply, plan.layout, options};
  for (int side : {0, 1, -1}) {
    SurfaceCurve curve = Trim(ref.points, region);
    for (int index = 0;; ++index) {
      if (index > 0 || side == 0) {
        const int offset_index = side == 0 ? 0 : side * index;
        double off_surface_s = -1.0;
        std::optional<PlyCourse> course = PlanCourse(ctx, curve, offset_index, &off_surface_s);
        if (off_surface_s >= 0.0) {
          sink.Error("plan-ply-off-surface", ply.where,
                     "ply '" + ply.name + "': the tows of the course " +
                         std::to_string(offset_index) +
                         " course widths from the reference leave the surface " +
                         std::to_string(off_surface_s) +
                         " mm along it; keep the ply a course width inside the surface");
          return std::nullopt;
        }
        if (!course) break;  // lays nothing: the ply is behind
        plan.courses.push_back(std::move(*course));
        if (static_cast<int>(plan.courses.size()) > options.max_courses) {
          sink.Error("plan-ply-too-many-courses", ply.where,
                     "ply '" + ply.name + "' needs more than " +
                         std::to_string(options.max_courses) + " courses");
          return std::nullopt;
        }
        if (side == 0) break;
      }
      auto next = OffsetOnce(surface, curve, width, side, ply.method);
      // An offset point left the surface: offset only the points whose offset (predicted
      // to first order) stays on it, with a growing margin.
      for (int attempt = 1; !next && attempt <= 4; ++attempt) {
        const SurfaceCurve kept = KeepOffsetOnSurface(surface, curve, width, side, 5.0 * attempt);
        if (kept.size() < 2) break;
        next = OffsetOnce(surface, kept, width, side, ply.method);
      }
      if (!next) break;
      curve = Trim(*next, region);
      if (curve.size() < 2) break;
    }
  }
  if (plan.courses.empty()) {
    sink.Error("plan-ply-empty", ply.where, "ply '" + ply.name + "': no course lays a tow");
    return std::nullopt;
  }
  Summarise(plan, scene);
  return plan;
}

}  // namespace stitchsim::planner
