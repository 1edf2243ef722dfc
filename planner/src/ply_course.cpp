// One course of a ply: poses along the centre curve, the tows there, and where each tow is
// cut and restarted at the ply boundary (bisection along the course).

#include "ply_course.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "detail/smooth_curve.h"
#include "stitchsim/geom/polygon2.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/geom/surface_walk.h"
#include "stitchsim/process/afp_steering.h"

namespace stitchsim::planner {
namespace {

/// The centre curve as a C2 function of its length (detail::SmoothCurve): poses along it
/// have no kinks, so the tows steer only where the curve does.
class CentreLine {
 public:
  CentreLine(const geom::Surface& s, const SurfaceCurve& c) : s_(s), curve_(s, c) {}
  double Length() const { return curve_.Length(); }

  /// The point at length s: uv and the tool frame (z normal, y along the course).
  PlyPoint At(double s) const {
    PlyPoint p;
    p.s_mm = std::clamp(s, 0.0, Length());
    p.uv = curve_.Uv(p.s_mm);
    const Eigen::Vector3d n = s_.Normal(p.uv).normalized();
    const Eigen::Vector3d t = s_.Jacobian(p.uv) * curve_.Slope(p.s_mm);
    p.tool.linear() = geom::FrameFromNormalAndDirection(n, geom::Tangential(t, n))
                          .value_or(Eigen::Matrix3d::Identity());
    p.tool.translation() = s_.Point(p.uv);
    return p;
  }

 private:
  const geom::Surface& s_;
  detail::SmoothCurve curve_;
};

/// Tow states at one point: bit t-1 set when the band's tow t lays material there.
struct Sample {
  PlyPoint point;
  std::uint64_t laid = 0;
  bool ok = false;
};

class CourseBuilder final : public TowRuler {
 public:
  CourseBuilder(const CourseContext& ctx, const SurfaceCurve& centre)
      : ctx_(ctx), line_(ctx.surface, centre) {}

  std::optional<Eigen::Vector3d> Centre(int tow, double s) const override {
    const Sample x = At(s);
    if (!x.ok) return std::nullopt;
    const auto i = static_cast<std::size_t>(tow);
    return ctx_.surface.Point(0.5 * (x.point.boundary_uv[i - 1] + x.point.boundary_uv[i]));
  }
  double End() const override { return line_.Length(); }
  double Step() const override { return 0.5 * ctx_.layout.width_mm; }

  Sample At(double s) const {
    Sample x;
    x.point = line_.At(s);
    const process::TowCross cross =
        process::TowsAt(ctx_.surface, x.point.tool, ctx_.layout, ctx_.band, &x.point.uv,
                        ctx_.options.max_substep_mm);
    if (!cross.ok) return x;
    x.ok = true;
    x.point.boundary = cross.boundary;
    x.point.boundary_uv = cross.boundary_uv;
    x.point.across = cross.across;
    const double p = ctx_.ply.coverage;
    for (int t = 1; t <= ctx_.band.count; ++t) {
      const double out = geom::FractionOutside(ctx_.ply.boundary_uv,
                                               cross.boundary_uv[static_cast<std::size_t>(t - 1)],
                                               cross.boundary_uv[static_cast<std::size_t>(t)]);
      const bool laid = p <= 0.0 ? out <= 1e-9 : (p >= 1.0 ? out < 1.0 - 1e-9 : out < p);
      if (laid) x.laid |= std::uint64_t{1} << (t - 1);
    }
    return x;
  }

  /// Where tow bit `bit` changes between a (state as at a) and b, to event_tol.
  double Bisect(double a, double b, std::uint64_t bit) const {
    const bool at_a = (At(a).laid & bit) != 0;
    while (b - a > ctx_.options.event_tol_mm) {
      const double m = 0.5 * (a + b);
      const Sample x = At(m);
      if (x.ok && ((x.laid & bit) != 0) == at_a) {
        a = m;
      } else {
        b = m;
      }
    }
    return 0.5 * (a + b);
  }

  const CentreLine& Line() const { return line_; }

 private:
  const CourseContext& ctx_;
  CentreLine line_;
};

struct Event {
  double s = 0.0;
  int tow = 1;
  bool add = true;
};

/// Each tow's smallest steering radius where laid (process::SteeringWindow over the tow
/// centres at the course's points from its add to its cut, as afp.steering_radius reads them
/// at the programme's poses) and its shortest piece (chords between those centres).
void TowFigures(const geom::Surface& surface, PlyCourse& course, const process::TowBand& band) {
  process::SteeringWindow window;
  std::vector<process::SteeringWindow::Radius> radii;
  for (PlyTow& tow : course.tows) {
    const std::size_t i = static_cast<std::size_t>(tow.tow - band.first + 1);
    for (const TowSegment& seg : tow.laid) {
      window.Reset();
      radii.clear();
      double length = 0.0;
      std::optional<Eigen::Vector3d> last;
      for (const PlyPoint& p : course.points) {
        if (p.s_mm < seg.start_mm || p.s_mm > seg.end_mm) continue;
        const Eigen::Vector2d uv = 0.5 * (p.boundary_uv[i - 1] + p.boundary_uv[i]);
        const Eigen::Vector3d centre = surface.Point(uv);
        if (last) length += (centre - *last).norm();
        last = centre;
        window.Add(centre, surface.Normal(uv), 0, radii);
      }
      for (const auto& r : radii) tow.min_radius_mm = std::min(tow.min_radius_mm, r.radius_mm);
      tow.shortest_piece_mm = std::min(tow.shortest_piece_mm, length);
    }
  }
}

}  // namespace

namespace {

/// The samples along the course and, per tow (index tow - 1), where the ply's boundary has it
/// laid (state changes between samples, found by bisection; a failed sample lays nothing).
std::vector<std::vector<TowSegment>> BoundarySegments(const CourseContext& ctx,
                                                      const CourseBuilder& b,
                                                      const std::vector<Sample>& samples) {
  std::vector<std::vector<TowSegment>> laid(static_cast<std::size_t>(ctx.band.count));
  const double length = b.Line().Length();
  for (int t = 1; t <= ctx.band.count; ++t) {
    const std::uint64_t bit = std::uint64_t{1} << (t - 1);
    auto& tow = laid[static_cast<std::size_t>(t - 1)];
    bool on = false;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const bool now = samples[i].ok && (samples[i].laid & bit) != 0;
      if (now == on) continue;
      const double s =
          i == 0 ? 0.0 : b.Bisect(samples[i - 1].point.s_mm, samples[i].point.s_mm, bit);
      if (now) {
        tow.push_back({s, s});
      } else {
        tow.back().end_mm = s;
      }
      on = now;
    }
    if (on) tow.back().end_mm = length;
  }
  return laid;
}

/// Every tow's adds and cuts, in order along the course. Positions closer than merge_tol to
/// the one before share its position (in `laid` too); pieces left empty go, pieces meeting join.
std::vector<Event> EventsOf(const CourseContext& ctx, std::vector<std::vector<TowSegment>>& laid) {
  std::vector<double> at;
  for (const auto& tow : laid) {
    for (const TowSegment& g : tow) at.insert(at.end(), {g.start_mm, g.end_mm});
  }
  std::sort(at.begin(), at.end());
  std::map<double, double> merged;
  double previous = -INFINITY;
  for (double s : at) {
    if (s - previous >= ctx.options.merge_tol_mm) previous = s;
    merged[s] = previous;
  }
  std::vector<Event> events;
  for (std::size_t t = 0; t < laid.size(); ++t) {
    std::vector<TowSegment> kept;
    for (TowSegment g : laid[t]) {
      g = {merged[g.start_mm], merged[g.end_mm]};
      if (g.end_mm <= g.start_mm) continue;
      if (!kept.empty() && g.start_mm <= kept.back().end_mm) {
        kept.back().end_mm = std::max(kept.back().end_mm, g.end_mm);
      } else {
        kept.push_back(g);
      }
    }
    for (const TowSegment& g : kept) {
      events.push_back({g.start_mm, static_cast<int>(t) + 1, true});
      events.push_back({g.end_mm, static_cast<int>(t) + 1, false});
    }
    laid[t] = std::move(kept);
  }
  std::sort(events.begin(), events.end(), [](const Event& x, const Event& y) {
    return x.s < y.s || (x.s == y.s && x.tow < y.tow);
  });
  return events;
}

/// The course's point positions: its events, the slow zones' edges (+-slow_zone_mm around
/// each, inside the course) and the samples between the first and the last event.
std::vector<double> PointPositions(const CourseContext& ctx, const std::vector<Event>& events,
                                   const std::vector<Sample>& samples) {
  const double first = events.front().s, last = events.back().s;
  std::vector<double> at;
  for (const Event& e : events)
    if (at.empty() || e.s != at.back()) at.push_back(e.s);
  const std::size_t event_points = at.size();
  auto add = [&](double s) {
    if (s <= first || s >= last) return;
    const bool near = std::any_of(
        at.begin(), at.end(), [&](double e) { return std::abs(e - s) < ctx.options.merge_tol_mm; });
    if (!near) at.push_back(s);
  };
  if (ctx.slow_zone_mm > 0.0) {
    for (std::size_t i = 0; i < event_points; ++i) {
      add(at[i] - ctx.slow_zone_mm);
      add(at[i] + ctx.slow_zone_mm);
    }
  }
  for (const Sample& x : samples) add(x.point.s_mm);
  std::sort(at.begin(), at.end());
  return at;
}

std::optional<PlyCourse> PlanCourseOn(const CourseContext& ctx, const SurfaceCurve& centre,
                                      int offset_index, bool curve_can_grow,
                                      CourseOffSurface& off_surface) {
  if (centre.size() < 2) return std::nullopt;
  const CourseBuilder b(ctx, centre);
  const double length = b.Line().Length();
  // Poses at most a steering half window apart: afp.steering_radius measures at the poses.
  const double spacing = std::min(ctx.options.point_spacing_mm, process::kSteeringHalfWindowMm);
  const int segments = std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)));
  std::vector<Sample> samples;
  samples.reserve(static_cast<std::size_t>(segments) + 1);
  for (int i = 0; i <= segments; ++i) {
    samples.push_back(b.At(length * i / segments));
    off_surface.anywhere = off_surface.anywhere || !samples.back().ok;
  }
  std::vector<std::vector<TowSegment>> laid = BoundarySegments(ctx, b, samples);
  const bool any = std::any_of(laid.begin(), laid.end(), [](const auto& t) { return !t.empty(); });
  if (!any) return std::nullopt;
  PlyCourse course;
  course.offset_index = offset_index;
  std::vector<double> boundary_ends;
  for (const auto& tow : laid)
    for (const TowSegment& g : tow)
      boundary_ends.insert(boundary_ends.end(), {g.start_mm, g.end_mm});
  std::sort(boundary_ends.begin(), boundary_ends.end());
  double need_mm = 0.0;
  for (int t = 1; t <= ctx.band.count; ++t) {
    MendTowPieces(ctx, b, t, laid[static_cast<std::size_t>(t - 1)], curve_can_grow, course.fixes,
                  need_mm);
  }
  if (need_mm > 0.0) {  // a piece runs past the curve's end: the course on a longer curve
    const SurfaceCurve longer = Extended(ctx.surface, centre, need_mm + b.Step(), b.Step());
    CourseOffSurface off;
    std::optional<PlyCourse> again = PlanCourseOn(ctx, longer, offset_index, false, off);
    off_surface.laying_s = off.laying_s;
    return again;
  }
  AlignExtendedEnds(ctx, b, boundary_ends, laid);
  const std::vector<Event> events = EventsOf(ctx, laid);
  if (events.empty()) return std::nullopt;  // every piece dropped
  for (double s : PointPositions(ctx, events, samples)) {
    Sample x = b.At(s);
    x.point.event = std::binary_search(events.begin(), events.end(), Event{s, 0, true},
                                       [](const Event& p, const Event& q) { return p.s < q.s; });
    if (!x.ok) {  // a tow boundary leaves the surface while the course lays
      off_surface.laying_s = s;
      return std::nullopt;
    }
    course.points.push_back(std::move(x.point));
  }
  for (int t = 1; t <= ctx.band.count; ++t) {
    PlyTow tow;
    tow.tow = ctx.band.first + t - 1;  // as the head numbers it
    tow.laid = std::move(laid[static_cast<std::size_t>(t - 1)]);
    course.tows.push_back(std::move(tow));
  }
  TowFigures(ctx.surface, course, ctx.band);
  return course;
}

}  // namespace

std::optional<PlyCourse> PlanCourse(const CourseContext& ctx, const SurfaceCurve& centre,
                                    int offset_index, CourseOffSurface& off_surface) {
  return PlanCourseOn(ctx, centre, offset_index, true, off_surface);
}

// A course is offset from its neighbour so extended and then trimmed again: an offset's ends
// (one-sided tangents, and at a fibre angle, the shift of the whole curve along itself) fall
// outside the ply, and every course reaches across the ply however many offsets lie between
// it and the reference.
SurfaceCurve Extended(const geom::Surface& surface, const SurfaceCurve& c, double length,
                      double step) {
  if (c.size() < 2) return c;
  auto grow = [&](const CurvePoint& end, const CurvePoint& inner, std::vector<CurvePoint>& out) {
    CurvePoint at = end;
    const Eigen::Vector3d chord = end.position - inner.position;
    if (chord.norm() <= 0) return;
    // The curve's own direction at its end (outwards); its last chord lags half a sample's turn.
    Eigen::Vector3d dir = end.tangent.dot(chord) >= 0 ? end.tangent : -end.tangent;
    for (double done = 0; done < length - 1e-9;) {
      const double h = std::min(step, length - done);
      const geom::SurfaceFoot f = geom::WalkOnSurface(surface, at.uv, dir, h);
      if (!f.converged || !surface.Domain().Contains(f.uv)) return;
      CurvePoint p;
      p.uv = f.uv;
      p.position = f.point;
      p.normal = surface.Normal(f.uv);
      p.tangent = geom::Tangential(f.tangent, p.normal);
      dir = f.tangent;  // the geodesic's own direction (a chord would turn it every step)
      out.push_back(p);
      at = p;
      done += h;
    }
  };
  std::vector<CurvePoint> head, tail;
  grow(c.front(), c[1], head);
  grow(c.back(), c[c.size() - 2], tail);
  for (CurvePoint& p : head) p.tangent = -p.tangent;  // the curve runs the other way
  SurfaceCurve out(head.rbegin(), head.rend());
  out.insert(out.end(), c.begin(), c.end());
  out.insert(out.end(), tail.begin(), tail.end());
  return out;
}

SurfaceCurve Reversed(SurfaceCurve c) {
  std::reverse(c.begin(), c.end());
  for (auto& p : c) p.tangent = -p.tangent;
  return c;
}

CourseSeam MeasureSeam(const geom::Surface& surface, const PlyCourse& right,
                       const PlyCourse& left) {
  CourseSeam seam;
  seam.right = right.number;
  seam.left = left.number;
  if (left.points.size() < 2) return seam;
  const std::size_t k = right.points.front().boundary.size() - 1;
  for (const PlyPoint& p : right.points) {
    const Eigen::Vector3d e = -p.across.front();  // towards the left course
    const Eigen::Vector3d a = p.boundary.front();
    double best = INFINITY;
    Eigen::Vector3d q_best = a;
    for (std::size_t j = 1; j < left.points.size(); ++j) {
      const Eigen::Vector3d q0 = left.points[j - 1].boundary[k],
                            d = left.points[j].boundary[k] - q0;
      const double f = std::clamp((a - q0).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
      const Eigen::Vector3d q = q0 + f * d;
      if ((q - a).norm() < best) best = (q - a).norm(), q_best = q;
    }
    // Not beside this point: more than 1 mm along the edge (an overlap on a tight radius sinks
    // the facing edge below the tangent plane, which is no reason to skip it).
    const Eigen::Vector3d along = surface.Normal(p.boundary_uv.front()).cross(e);
    if (std::abs((q_best - a).dot(along)) > 1.0) continue;
    // Along the surface: the chord reads 2 R sin(g / 2R) for a gap g across a curvature 1 / R.
    const std::optional<double> walked =
        geom::DistanceAlongGeodesic(surface, p.boundary_uv.front(), e, q_best);
    const double across = walked.value_or((q_best - a).dot(e));
    if (across > 0) seam.max_gap_mm = std::max(seam.max_gap_mm, across);
    if (across < 0) seam.max_overlap_mm = std::max(seam.max_overlap_mm, -across);
  }
  return seam;
}

}  // namespace stitchsim::planner
