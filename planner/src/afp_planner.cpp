#include "stitchsim/planner/afp_planner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "detail/program_text.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/process/afp_tows.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::planner {
namespace {

// |q_x| below this counts as zero: the head axis lies in the y-z plane (seed eq. 12).
constexpr double kZeroQx = 1e-12;

std::string Fixed(double v, int decimals = 6) {
  // Values that print as zero print as "0.000000", never "-0.000000".
  const double scale = std::pow(10.0, decimals);
  if (std::abs(v) * scale < 0.5) v = 0.0;
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

std::string DegText(double rad) { return Fixed(rad * kRadToDeg, 3); }

void CheckTravel(AfpPlan& plan) {
  struct Axis {
    const char* code;
    const char* letter;
    double AfpHeadAxes::*field;
    double min_rad;
    double max_rad;
  };
  const Axis axes[] = {
      {"afp-b-over-travel", "B", &AfpHeadAxes::b_rad, plan.limits.b_min_rad, plan.limits.b_max_rad},
      {"afp-c-over-travel", "C", &AfpHeadAxes::c_rad, plan.limits.c_min_rad, plan.limits.c_max_rad},
  };
  for (const Axis& a : axes) {
    AfpOverTravel f;
    f.code = a.code;
    double worst_excess = 0.0;
    for (const AfpPoint& p : plan.points) {
      const double v = p.axes.*a.field;
      const double excess = std::max(a.min_rad - v, v - a.max_rad);
      if (excess <= 0.0) continue;
      if (f.points == 0) f.first_index = p.index;
      ++f.points;
      if (excess > worst_excess) {
        worst_excess = excess;
        f.worst_rad = v;
        f.limit_rad = v > a.max_rad ? a.max_rad : a.min_rad;
      }
    }
    if (f.points == 0) continue;
    f.message = std::string(a.letter) + " reaches " + DegText(f.worst_rad) + " deg, past its " +
                (f.limit_rad == a.max_rad ? "maximum " : "minimum ") + DegText(f.limit_rad) +
                " deg, at " + std::to_string(f.points) + " of " +
                std::to_string(plan.points.size()) + " points (first: point " +
                std::to_string(f.first_index) + ", s " +
                Fixed(plan.points[static_cast<std::size_t>(f.first_index)].s_mm, 3) + " mm)";
    plan.over_travel.push_back(std::move(f));
  }
}

}  // namespace

AfpHeadAxes AfpHeadAxesFromDirection(const Eigen::Vector3d& q_in) {
  const Eigen::Vector3d q = q_in.normalized();
  AfpHeadAxes out;
  const double b = std::acos(std::clamp(q.z(), -1.0, 1.0));
  if (std::abs(q.x()) < kZeroQx) {
    out.c_rad = q.y() >= 0.0 ? kPi / 2 : -kPi / 2;
    out.b_rad = b;
  } else {
    out.c_rad = std::atan(q.y() / q.x());
    out.b_rad = q.x() < 0.0 ? -b : b;
  }
  return out;
}

std::optional<Eigen::Vector3d> InclinationVector(const Eigen::Vector3d& normal,
                                                 const Eigen::Vector3d& course_direction,
                                                 double incline_rad) {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d along = course_direction - course_direction.dot(n) * n;
  if (!(along.norm() > 1e-12 * std::max(1.0, course_direction.norm()))) return std::nullopt;
  const Eigen::Vector3d t = along.normalized();
  return (std::sin(incline_rad) * t + std::cos(incline_rad) * n).normalized();
}

SeedCylinderPose SeedConcaveCylinderPose(double alpha, double beta, double theta) {
  SeedCylinderPose p;
  p.normal = Eigen::Vector3d(0.0, std::cos(alpha), std::sin(alpha));
  p.tangent = Eigen::Vector3d(std::tan(beta), std::cos(alpha - kPi / 2), std::sin(alpha - kPi / 2));
  const double r = p.tangent.norm();
  p.inclination = std::sin(theta) * p.tangent / r + std::cos(theta) * p.normal;
  const Eigen::Vector3d& q = p.inclination;
  // Eq. (7) C = atan(q_y / q_x); eq. (11) B = acos(q_z); eq. (12) for q_x = 0.
  p.axes.b_rad = std::acos(std::clamp(q.z(), -1.0, 1.0));
  if (std::abs(q.x()) < kZeroQx) {
    p.axes.c_rad = std::cos(alpha) >= 0.0 ? kPi / 2 : -kPi / 2;
  } else {
    p.axes.c_rad = std::atan(q.y() / q.x());
    if (q.x() < 0.0) p.axes.b_rad = -p.axes.b_rad;
  }
  return p;
}

AfpAxisLimits AfpAxisLimitsFrom(const scene::RuleLimits& limits) {
  using scene::LimitKey;
  AfpAxisLimits out;
  out.b_min_rad = limits.Value(LimitKey::kAfpBMinDeg) / kRadToDeg;
  out.b_max_rad = limits.Value(LimitKey::kAfpBMaxDeg) / kRadToDeg;
  out.c_min_rad = limits.Value(LimitKey::kAfpCMinDeg) / kRadToDeg;
  out.c_max_rad = limits.Value(LimitKey::kAfpCMaxDeg) / kRadToDeg;
  return out;
}

std::unique_ptr<geom::Curve2> MakeLayAngleCourse(const geom::Domain2& domain,
                                                 double lay_angle_rad) {
  const Eigen::Vector2d centre = 0.5 * (domain.min + domain.max);
  const Eigen::Vector2d dir(std::cos(lay_angle_rad), std::sin(lay_angle_rad));
  // Slab clip of centre + t * dir to the domain rectangle.
  double t_lo = -1e300;
  double t_hi = 1e300;
  for (int k = 0; k < 2; ++k) {
    if (std::abs(dir[k]) < 1e-15) continue;
    const double a = (domain.min[k] - centre[k]) / dir[k];
    const double b = (domain.max[k] - centre[k]) / dir[k];
    t_lo = std::max(t_lo, std::min(a, b));
    t_hi = std::min(t_hi, std::max(a, b));
  }
  auto curve = std::make_unique<geom::Curve2>();
  curve->Add(geom::MakeLineSegment(centre + t_lo * dir, centre + t_hi * dir), "course");
  return curve;
}

namespace {

// The B and C ranges over the course and the largest C step between points.
void AxisRanges(AfpPlan& plan) {
  plan.b_min_rad = plan.b_max_rad = plan.points.front().axes.b_rad;
  plan.c_min_rad = plan.c_max_rad = plan.points.front().axes.c_rad;
  for (std::size_t i = 0; i < plan.points.size(); ++i) {
    const AfpHeadAxes& a = plan.points[i].axes;
    plan.b_min_rad = std::min(plan.b_min_rad, a.b_rad);
    plan.b_max_rad = std::max(plan.b_max_rad, a.b_rad);
    plan.c_min_rad = std::min(plan.c_min_rad, a.c_rad);
    plan.c_max_rad = std::max(plan.c_max_rad, a.c_rad);
    if (i > 0) {
      plan.c_max_step_rad =
          std::max(plan.c_max_step_rad, std::abs(a.c_rad - plan.points[i - 1].axes.c_rad));
    }
  }
}

}  // namespace

namespace {

// The pose at a point of the course: head axis q (normal or inclined), tool y along the course.
struct CourseFrames {
  const scene::Scene& scene;
  const geom::Curve2& curve;
  const geom::SurfacePath& lifted;
  double incline_rad;

  std::optional<AfpPoint> PointAt(const geom::PathPoint& at) const {
    AfpPoint p;
    p.uv = at.uv;
    p.position = at.position;
    p.normal = at.normal.normalized();
    const Eigen::Vector2d duv = curve.Segment(at.segment).Derivative(at.t);
    const Eigen::Vector3d dir = scene.surface->Jacobian(at.uv) * duv;
    const auto q = InclinationVector(p.normal, dir, incline_rad);
    if (!q) return std::nullopt;
    p.tangent = (dir - dir.dot(p.normal) * p.normal).normalized();
    p.inclination = *q;
    p.alpha_rad = std::atan2(p.normal.z(), p.normal.y());
    p.axes = AfpHeadAxesFromDirection(p.inclination);
    // q leans at most < 90 deg from n towards t, so t is never along q.
    p.tool.linear() = *geom::FrameFromNormalAndDirection(p.inclination, p.tangent);
    p.tool.translation() = p.position;
    return p;
  }

  // True when every tow of the head lies on the surface at arc length s (process::TowsAt, the
  // model the afp.* rules judge the programme with).
  bool BandFits(double s_mm) const {
    const std::optional<AfpPoint> p = PointAt(lifted.AtArcLength(s_mm));
    return p &&
           process::TowsAt(*scene.surface, p->tool, process::TowLayoutOf(scene.head), nullptr).ok;
  }
};

// The stretch of the path [begin, end] (arc length, mm) over which the head's whole band of tows
// lies on the surface: a course clipped to the domain by its centre line hangs half its band
// off the surface at its ends, which the afp.* rules report. Ends found to kBandEndToleranceMm.
struct BandRange {
  double begin_mm = 0.0;
  double end_mm = 0.0;
};
constexpr double kBandEndToleranceMm = 0.01;

std::optional<BandRange> BandOnSurface(const CourseFrames& f, double spacing_mm,
                                       const std::string& name, const SourceLocation& where,
                                       DiagnosticSink& sink) {
  const double length = f.lifted.Length();
  const int n = std::max(1, static_cast<int>(std::ceil(length / spacing_mm - 1e-9)));
  std::vector<bool> fits(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) fits[static_cast<std::size_t>(i)] = f.BandFits(length * i / n);
  const auto first = std::find(fits.begin(), fits.end(), true);
  if (first == fits.end()) {
    sink.Error(
        "plan-afp-band-off-surface", where,
        "AFP course '" + name + "': the head's band of tows leaves the surface all along it");
    return std::nullopt;
  }
  const int lo = static_cast<int>(first - fits.begin());
  const int hi = n - static_cast<int>(std::find(fits.rbegin(), fits.rend(), true) - fits.rbegin());
  for (int i = lo; i <= hi; ++i) {
    if (fits[static_cast<std::size_t>(i)]) continue;
    sink.Error("plan-afp-band-off-surface", where,
               "AFP course '" + name + "': the head's band of tows leaves the surface at s " +
                   Fixed(length * i / n, 3) + " mm, between stretches where it fits");
    return std::nullopt;
  }
  // Bisect each trimmed end between a point off and a point on.
  auto edge = [&](double off, double on) {
    while (std::abs(on - off) > kBandEndToleranceMm) {
      const double mid = 0.5 * (off + on);
      (f.BandFits(mid) ? on : off) = mid;
    }
    return on;
  };
  BandRange r;
  r.begin_mm = lo == 0 ? 0.0 : edge(length * (lo - 1) / n, length * lo / n);
  r.end_mm = hi == n ? length : edge(length * (hi + 1) / n, length * hi / n);
  return r;
}

}  // namespace

std::optional<AfpPlan> PlanAfpCourse(const scene::Scene& scene, const scene::PathSpec* path,
                                     const AfpPlanOptions& options, DiagnosticSink& sink) {
  const SourceLocation where = path != nullptr ? path->where : SourceLocation{scene.file.string()};
  if (scene.head.kind != scene::HeadKind::kAfp) {
    sink.Error("plan-not-afp-head", SourceLocation{scene.file.string()},
               "scene '" + scene.name + "' mounts head '" + scene.head.name + "', not an AFP head");
    return std::nullopt;
  }
  if (!(options.point_spacing_mm > 0.0) || !std::isfinite(options.point_spacing_mm)) {
    sink.Error("plan-bad-point-spacing", where, "AFP point spacing must be positive and finite");
    return std::nullopt;
  }
  if (!std::isfinite(options.incline_rad) || std::abs(options.incline_rad) >= kPi / 2) {
    sink.Error("plan-bad-incline", where, "inclination must be within (-90, 90) deg");
    return std::nullopt;
  }
  AfpPlan plan;
  plan.incline_rad = options.incline_rad;
  plan.limits = AfpAxisLimitsFrom(scene.limits);
  std::unique_ptr<geom::Curve2> own_curve;
  const geom::Curve2* curve = nullptr;
  if (options.lay_angle_rad) {
    if (!std::isfinite(*options.lay_angle_rad)) {
      sink.Error("plan-bad-lay-angle", where, "lay angle must be finite");
      return std::nullopt;
    }
    own_curve = MakeLayAngleCourse(scene.surface->Domain(), *options.lay_angle_rad);
    curve = own_curve.get();
    plan.lay_angle_rad = *options.lay_angle_rad;
    char name[48];
    std::snprintf(name, sizeof(name), "lay%g", *options.lay_angle_rad * kRadToDeg);
    plan.course_name = name;
  } else if (path != nullptr) {
    curve = path->curve.get();
    plan.course_name = path->name;
  } else {
    sink.Error("plan-no-course", where, "an AFP course needs a lay angle or a scene path");
    return std::nullopt;
  }
  const geom::SurfacePath lifted(*scene.surface, *curve);
  const double path_length = lifted.Length();
  if (!(path_length > options.point_spacing_mm * 1e-6)) {
    sink.Error("plan-path-too-short", where, "AFP course '" + plan.course_name + "' is empty");
    return std::nullopt;
  }
  if (path_length / options.point_spacing_mm >
      static_cast<double>(limits::kMaxAfpPointsPerCourse)) {
    sink.Error("plan-too-many-points", where,
               "AFP course '" + plan.course_name + "' (" + std::to_string(path_length) +
                   " mm) at " + std::to_string(options.point_spacing_mm) +
                   " mm spacing would take more than " +
                   std::to_string(limits::kMaxAfpPointsPerCourse) +
                   " points, the limit for one course (docs/limits.md)");
    return std::nullopt;
  }
  const CourseFrames frames{scene, *curve, lifted, options.incline_rad};
  const std::optional<BandRange> band =
      BandOnSurface(frames, options.point_spacing_mm, plan.course_name, where, sink);
  if (!band) return std::nullopt;
  plan.length_mm = band->end_mm - band->begin_mm;
  plan.trimmed_start_mm = band->begin_mm;
  plan.trimmed_end_mm = path_length - band->end_mm;
  const int segments =
      std::max(1, static_cast<int>(std::ceil(plan.length_mm / options.point_spacing_mm - 1e-9)));
  plan.points.reserve(static_cast<std::size_t>(segments) + 1);
  geom::PathPoint at = lifted.AtArcLength(band->begin_mm);
  for (int i = 0; i <= segments; ++i) {
    const double s = plan.length_mm * i / segments;
    if (i > 0) at = lifted.AtArcLengthFrom(at, band->begin_mm + s);
    std::optional<AfpPoint> p = frames.PointAt(at);
    if (!p) {
      sink.Error("plan-degenerate-frame", where,
                 "AFP course '" + plan.course_name + "' runs along the surface normal at s " +
                     Fixed(band->begin_mm + s, 3) + " mm");
      return std::nullopt;
    }
    p->index = i;
    p->s_mm = s;
    plan.points.push_back(*p);
  }
  AxisRanges(plan);
  CheckTravel(plan);
  return plan;
}

int AfpCoursePly(const scene::Scene& scene) { return static_cast<int>(scene.plies.size()) + 1; }

void WriteAfpProgram(const AfpPlan& plan, const scene::Scene& scene,
                     const program::Dialect& dialect, std::ostream& out) {
  using program::Axis;
  program::ProgramWriter w(out, dialect);
  program::ProgramIdentity id;
  id.scene = scene.name;
  id.head = scene.head.name;
  id.course = plan.course_name;
  if (std::isfinite(plan.lay_angle_rad)) id.lay_angle_deg = plan.lay_angle_rad * kRadToDeg;
  id.incline_deg = plan.incline_rad * kRadToDeg;
  id.points = static_cast<long>(plan.points.size());
  id.course_length_mm = plan.length_mm;
  const program::ProgramHeader header = program::WriteIdentity(id);

  program::Block b;
  detail::WriteOpening(w, b, dialect, header, scene.head.tool_number);
  // The course is a ply of its own, numbered after the scene's plies (docs/program-format.md,
  // "AFP programmes"): one course, every tow of the head added at the start, cut at the end.
  const auto code = [&](int m, std::optional<int> param, std::string comment) {
    detail::WriteCode(w, b, m, param, std::move(comment));
  };
  code(dialect.m.ply_start, AfpCoursePly(scene),
       "PLY name=" + plan.course_name + ", a course of plan afp, not a scene ply");
  code(dialect.m.course_start, 1, "COURSE 1 of 1");
  detail::PoseWords pose_words(dialect);
  double modal_feed = 0.0;  // mm/min; none written yet
  for (const AfpPoint& p : plan.points) {
    b.Clear();
    b.motion = p.index == 0 ? program::Motion::kRapid : program::Motion::kFeed;
    pose_words.Set(b, p.position, p.tool.linear());
    b[Axis::kPathLength] = p.s_mm;
    if (p.index == 0) b.comment = "start";
    const double feed = scene.head.afp.layup_speed_mm_s * 60.0 * p.feed_fraction;
    if (p.index >= 1 && feed != modal_feed) {
      b.feed = feed;
      modal_feed = feed;
    }
    w.Write(b);
    if (p.index == 0) code(dialect.m.tow_add, 0, "every tow of the head");
  }
  code(dialect.m.tow_cut, 0, {});
  code(dialect.m.course_end, std::nullopt, {});
  detail::WriteEnding(w, b, dialect);
}

void WriteAfpCsv(const AfpPlan& plan, std::ostream& out) {
  std::string text =
      "index,s_mm,alpha_deg,tangent_x,tangent_y,tangent_z,inclination_x,inclination_y,"
      "inclination_z,B_deg,C_deg\n";
  for (const AfpPoint& p : plan.points) {
    text += std::to_string(p.index);
    const double values[] = {p.s_mm,
                             p.alpha_rad * kRadToDeg,
                             p.tangent.x(),
                             p.tangent.y(),
                             p.tangent.z(),
                             p.inclination.x(),
                             p.inclination.y(),
                             p.inclination.z(),
                             p.axes.b_rad * kRadToDeg,
                             p.axes.c_rad * kRadToDeg};
    for (double v : values) {
      text += ',';
      text += Fixed(v);
    }
    text += '\n';
  }
  out << text;
}

}  // namespace stitchsim::planner
