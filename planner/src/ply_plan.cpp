// PlanPly: reference course, offsets in both directions, tows and their cuts per course.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

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

constexpr double kExtensionStepMm = 5.0;
// A course-width offset walks the surface in this many substeps at least (exact on a circle;
// the 0.5 mm default step made a 7 m wing course cost seconds).
constexpr double kOffsetSubsteps = 20.0;

/// The geodesic through the origin's foot point along `d`, both ways until it leaves `region`
/// (steps of kExtensionStepMm, the walk of geom::WalkOnSurface).
ReferenceCurve GeodesicReference(const geom::Surface& surface, const geom::SurfaceProjection& foot,
                                 const Eigen::Vector3d& d, const geom::Domain2& region);

/// The fibre axis through the ply origin at the ply angle, as far both ways as it projects
/// onto the surface inside `region`.
ReferenceCurve ReferenceCourse(const geom::Surface& surface, const scene::PlySpec& ply,
                               double angle_rad, const geom::Domain2& region,
                               const PlyPlanOptions& options) {
  const geom::SurfaceProjection foot = surface.Project(ply.origin_mm);
  const Eigen::Vector3d n = foot.normal;
  const Eigen::Vector3d d = Eigen::AngleAxisd(angle_rad, n) * geom::Tangential(ply.direction, n);
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
  if (ply.reference_path == scene::ReferencePath::kGeodesic)
    return GeodesicReference(surface, foot, d, region);
  if (ply.reference_path == scene::ReferencePath::kConstantAngle)
    return ConstantAngleReference(surface, ply, angle_rad, region, options.point_spacing_mm);
  FiberAxis axis{ply.origin_mm + t_min * d, ply.origin_mm + t_max * d, ply.projection};
  return ProjectFiberAxis(surface, axis, options.chord_tol_mm);
}

/// One offset of `curve` by `distance` to its left (side > 0: N x T) or right.
std::optional<SurfaceCurve> OffsetOnce(const geom::Surface& surface, const SurfaceCurve& curve,
                                       double distance, int side, scene::PlyOffsetMethod method) {
  OffsetOptions o;
  o.distance_mm = distance;
  o.count = 1;
  o.measure = false;
  o.max_substep_mm = std::max(o.max_substep_mm, distance / kOffsetSubsteps);
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

ReferenceCurve GeodesicReference(const geom::Surface& surface, const geom::SurfaceProjection& foot,
                                 const Eigen::Vector3d& d, const geom::Domain2& region) {
  ReferenceCurve out;
  CurvePoint start;
  start.uv = foot.uv;
  start.position = surface.Point(foot.uv);
  start.normal = surface.Normal(foot.uv);
  start.tangent = geom::Tangential(d, start.normal);
  CurvePoint behind = start;  // a point just behind, so that Extended walks along d
  behind.position = start.position - 1e-3 * start.tangent;
  const double reach = (region.max - region.min).norm();
  SurfaceCurve both = Extended(surface, {behind, start}, reach, kExtensionStepMm);
  // Extended walked forward from `start` and back from `behind`: drop `behind`.
  SurfaceCurve line;
  for (const CurvePoint& p : both) {
    if ((p.position - behind.position).norm() > 0) line.push_back(p);
  }
  out.points = Trim(line, region);
  out.ok = out.points.size() >= 2;
  if (!out.ok) out.message = "the geodesic from the ply origin does not cross the ply";
  return out;
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
    const Eigen::Vector2d duv =
        geom::UvOfTangent(surface, p.uv, side * distance * p.normal.cross(p.tangent));
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

/// The head's slow zone either side of each cut and add, mm (0: the head slows nowhere).
double SlowZoneMm(const scene::Scene& scene) {
  const scene::AfpSpec& afp = scene.head.afp;
  return afp.cut_add_feed_mm_s > 0.0 ? afp.cut_add_zone_mm : 0.0;
}

/// The tow piece limits the rules judge with: afp.min_tow_length's (verify/src/
/// afp_min_tow_length.cpp: the scene limit, else the head's cutter-to-roller distance) and
/// afp.restart_distance's (the scene limit, else the head's minimum restart distance).
void TowPieceLimits(const scene::Scene& scene, PlyPlan& plan) {
  plan.min_tow_length_mm = scene::MinTowLengthMm(scene).value_or(0.0);
  plan.min_restart_mm = scene::MinRestartMm(scene).value_or(0.0);
}

void Summarise(PlyPlan& plan, const scene::Scene& scene) {
  const geom::Surface& surface = *scene.surface;
  std::sort(plan.courses.begin(), plan.courses.end(),
            [](const PlyCourse& a, const PlyCourse& b) { return a.offset_index < b.offset_index; });
  for (std::size_t i = 0; i < plan.courses.size(); ++i) {
    PlyCourse& c = plan.courses[i];
    c.number = static_cast<int>(i) + 1;
    plan.laid_length_mm += c.End() - c.Start();
    plan.fixes += c.fixes;
    for (const PlyTow& t : c.tows) {
      plan.tow_segments += static_cast<int>(t.laid.size());
      plan.events += 2 * static_cast<int>(t.laid.size());
      plan.min_radius_mm = std::min(plan.min_radius_mm, t.min_radius_mm);
      plan.shortest_piece_mm = std::min(plan.shortest_piece_mm, t.shortest_piece_mm);
    }
  }
  for (std::size_t i = 0; i + 1 < plan.courses.size(); ++i) {
    CourseSeam seam = MeasureSeam(surface, plan.courses[i], plan.courses[i + 1]);
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

/// What a ply is planned with, and where its courses go.
class PlyBuilder {
 public:
  PlyBuilder(const scene::Scene& scene, const scene::PlySpec& ply, const PlyPlanOptions& options,
             DiagnosticSink& sink, PlyPlan& plan)
      : surface_(*scene.surface),
        ply_(ply),
        options_(options),
        sink_(sink),
        plan_(plan),
        width_(plan.band.count * plan.layout.width_mm),
        ctx_{surface_,
             ply,
             plan.layout,
             plan.band,
             options,
             plan.min_tow_length_mm,
             plan.min_restart_mm,
             SlowZoneMm(scene)} {}

  /// The ply's region in (u, v), grown by `margin`, inside the domain.
  geom::Domain2 Within(double margin) const {
    geom::Domain2 r = Region(ply_.boundary_uv, margin);
    r.min = r.min.cwiseMax(surface_.Domain().min);
    r.max = r.max.cwiseMin(surface_.Domain().max);
    return r;
  }

  std::optional<SurfaceCurve> Reference(double angle_rad, const geom::Domain2& region) {
    const ReferenceCurve ref = ReferenceCourse(surface_, ply_, angle_rad, region, options_);
    if (!ref.ok || ref.points.size() < 2) {
      sink_.Error("plan-ply-no-reference", ply_.where,
                  "ply '" + ply_.name + "': " +
                      (ref.message.empty() ? "the fibre axis does not project" : ref.message));
      return std::nullopt;
    }
    return Trim(ref.points, region);
  }

  /// `curve` offset by `distance` to `side`, trimmed to `region`; where an offset point would
  /// leave the surface, only the points whose offset (predicted to first order) stays on it
  /// are offset, with a growing margin. nullopt: nothing left.
  std::optional<SurfaceCurve> Offset(const SurfaceCurve& curve, double distance, int side,
                                     const geom::Domain2& region,
                                     bool* left_surface = nullptr) const {
    // Extended by two course widths, or less where the extension's offset would leave the
    // surface (near a sharp trailing edge the walk can lose the skin it is on).
    std::optional<SurfaceCurve> next;
    for (const double extension : {2.0, 1.0, 0.5, 0.0}) {
      const SurfaceCurve base = Extended(surface_, curve, extension * distance, kExtensionStepMm);
      next = OffsetOnce(surface_, base, distance, side, ply_.method);
      for (int attempt = 1; !next && attempt <= 4; ++attempt) {
        const SurfaceCurve kept =
            KeepOffsetOnSurface(surface_, base, distance, side, 5.0 * attempt);
        if (kept.size() < 2) break;
        next = OffsetOnce(surface_, kept, distance, side, ply_.method);
      }
      if (next) break;
    }
    if (!next) {
      if (left_surface != nullptr) *left_surface = true;
      return std::nullopt;
    }
    SurfaceCurve trimmed = Trim(*next, region);
    if (trimmed.size() < 2) return std::nullopt;
    return trimmed;
  }

  enum class Added { kYes, kNothing, kError };
  Added Course(const SurfaceCurve& curve, int offset_index) {
    CourseOffSurface off;
    std::optional<PlyCourse> course = PlanCourse(ctx_, curve, offset_index, off);
    if (off.laying_s >= 0.0) {
      sink_.Error("plan-ply-off-surface", ply_.where,
                  "ply '" + ply_.name + "': the tows of course " + std::to_string(offset_index) +
                      " (from the reference) leave the surface " + std::to_string(off.laying_s) +
                      " mm along it; keep the ply a course width inside the surface");
      return Added::kError;
    }
    if (!course) {
      // Nothing laid where the tows are off the surface: the ply may still need this course.
      if (off.anywhere) off_surface_.push_back(offset_index);
      return Added::kNothing;
    }
    plan_.courses.push_back(std::move(*course));
    if (static_cast<int>(plan_.courses.size()) > options_.max_courses) {
      sink_.Error("plan-ply-too-many-courses", ply_.where,
                  "ply '" + ply_.name + "' needs more than " +
                      std::to_string(options_.max_courses) + " courses");
      return Added::kError;
    }
    return Added::kYes;
  }

  /// Band offset ply: the reference at the ply angle, then offsets by the course width both
  /// ways until a course lays nothing.
  bool Offsets() {
    const geom::Domain2 region = Within(0.5 * width_ + 10.0);
    const auto ref = Reference(ply_.angle_rad, region);
    if (!ref) return false;
    if (Course(*ref, 0) == Added::kError) return false;
    Report(static_cast<double>(plan_.courses.size()), 0.0);
    for (int side : {1, -1}) {
      SurfaceCurve curve = *ref;
      for (int index = 1;; ++index) {
        bool left_surface = false;
        auto next = Offset(curve, width_, side, region, &left_surface);
        if (!next) {
          if (left_surface) off_surface_.push_back(side * index);
          break;
        }
        curve = std::move(*next);
        const Added a = Course(curve, side * index);
        if (a == Added::kError) return false;
        if (a == Added::kNothing) break;  // the ply is behind, or the surface ends
        Report(static_cast<double>(plan_.courses.size()), 0.0);
      }
    }
    return true;
  }

  /// Laminate family ply: laminate curves at the ply angle across the tow-width offsets of
  /// the 0 deg reference, a course width apart across the fibres.
  bool Laminate() {
    const double sin_theta = std::abs(std::sin(ply_.angle_rad));
    if (sin_theta < 1e-6) return Offsets();  // along the 0 deg curves: the band offset ply
    const Eigen::Vector2d size =
        Region(ply_.boundary_uv, 0.0).max - Region(ply_.boundary_uv, 0.0).min;
    const double reach = size.norm() * std::abs(std::cos(ply_.angle_rad)) / sin_theta;
    const geom::Domain2 region = Within(0.5 * width_ + 10.0 + reach);
    const auto ref = Reference(0.0, region);
    if (!ref) return false;
    const double tow = plan_.layout.width_mm;
    LaminateInputs in{surface_, *ref, ply_.angle_rad, width_, [&](const SurfaceCurve& c, int side) {
                        return Offset(c, tow, side, region);
                      }};
    const std::vector<SurfaceCurve> lines = LaminateCourseLines(in);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (Course(lines[i], -static_cast<int>(i)) == Added::kError) return false;
      Report(static_cast<double>(i + 1), static_cast<double>(lines.size()));
    }
    return true;
  }

  /// Offsets from the reference (> 0 to its left) of the courses not laid because their tows
  /// or their centre curve would leave the surface.
  const std::vector<int>& OffSurface() const { return off_surface_; }

 private:
  void Report(double done, double total) const {
    if (options_.progress) options_.progress(done, total);
  }

  const geom::Surface& surface_;
  const scene::PlySpec& ply_;
  const PlyPlanOptions& options_;
  DiagnosticSink& sink_;
  PlyPlan& plan_;
  double width_;
  CourseContext ctx_;
  std::vector<int> off_surface_;
};

/// The plan against its own coverage rule (PlanCoverage): false (plan-ply-off-surface) when
/// courses the surface has no room for leave the ply bare beyond the limit; a "ply-coverage"
/// finding when it falls short for another reason.
bool JudgeCoverage(PlyPlan& plan, const scene::Scene& scene, const scene::PlySpec& ply,
                   const std::vector<int>& off_surface, DiagnosticSink& sink) {
  const process::PlyCoveragePct pct = PlanCoverage(plan, *scene.surface, ply);
  plan.bare_pct = pct.bare;
  plan.doubled_pct = pct.doubled;
  plan.laid_outside_pct = pct.laid_outside;
  const double max_bare = scene.limits.Value(scene::LimitKey::kAfpCoverageMaxBarePct);
  const double max_doubled = scene.limits.Value(scene::LimitKey::kAfpCoverageMaxDoubledPct);
  char text[400];
  if (pct.bare > max_bare && !off_surface.empty()) {
    std::string courses;
    for (int i : off_surface)
      courses += (courses.empty() ? "" : " and ") + std::to_string(std::abs(i)) +
                 (i > 0 ? " to the left" : " to the right");
    std::snprintf(text, sizeof(text),
                  "ply '%s': the courses from %s of the reference outwards would lay their "
                  "tows off the surface and are not laid; without them %.3g %% of the ply is "
                  "bare (afp.coverage allows %.3g %%); keep the ply a course width (%.1f mm) "
                  "inside the surface",
                  ply.name.c_str(), courses.c_str(), pct.bare, max_bare,
                  plan.band.count * plan.layout.width_mm);
    sink.Error("plan-ply-off-surface", ply.where, text);
    return false;
  }
  for (const auto& [what, value, limit] :
       {std::tuple{"bare", pct.bare, max_bare}, std::tuple{"doubled", pct.doubled, max_doubled}}) {
    if (value <= limit) continue;
    std::snprintf(text, sizeof(text),
                  "the courses planned leave %.3g %% of ply '%s' %s beyond the band of one tow "
                  "along its boundary (afp.coverage allows %.3g %%)",
                  value, ply.name.c_str(), what, limit);
    plan.findings.push_back({"ply-coverage", text});
  }
  return true;
}

}  // namespace

std::optional<PlyPlan> PlanPly(const scene::Scene& scene, const scene::PlySpec& ply,
                               const PlyPlanOptions& options, DiagnosticSink& sink) {
  if (scene.head.kind != scene::HeadKind::kAfp || scene.surface == nullptr) {
    sink.Error("plan-not-afp-head", ply.where,
               "scene '" + scene.name + "' mounts head '" + scene.head.name + "', not an AFP head");
    return std::nullopt;
  }
  PlyPlan plan;
  plan.ply_name = ply.name;
  plan.angle_rad = ply.angle_rad;
  plan.coverage = ply.coverage;
  plan.layout = process::TowLayoutOf(scene.head);
  plan.band = process::PlyTowBand(plan.layout, ply.tows);
  TowPieceLimits(scene, plan);
  for (std::size_t i = 0; i < scene.plies.size(); ++i)
    if (scene.plies[i].name == ply.name) plan.ply_index = static_cast<int>(i) + 1;
  PlyBuilder builder(scene, ply, options, sink, plan);
  const bool ok =
      ply.rule == scene::PlyRule::kLaminateFamily ? builder.Laminate() : builder.Offsets();
  if (!ok) return std::nullopt;
  if (plan.courses.empty()) {
    sink.Error("plan-ply-empty", ply.where, "ply '" + ply.name + "': no course lays a tow");
    return std::nullopt;
  }
  Summarise(plan, scene);
  if (!JudgeCoverage(plan, scene, ply, builder.OffSurface(), sink)) return std::nullopt;
  return plan;
}

}  // namespace stitchsim::planner
