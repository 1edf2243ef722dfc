#include "stitchsim/planner/offset_curves.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

#include "stitchsim/geom/surface_walk.h"

namespace stitchsim::planner {

namespace {

using Foot = geom::SurfaceFoot;
using geom::ProjectNear;
using geom::Tangential;

constexpr int kInitialAxisPieces = 16;
constexpr int kMaxRefineDepth = 24;

// Where the line p + t v meets the surface: Newton on S(uv) - p - t v = 0 from `uv`.
bool IntersectNear(const geom::Surface& s, const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                   Eigen::Vector2d& uv, double* t_out = nullptr) {
  double t = 0.0;
  for (int iter = 0; iter < 60; ++iter) {
    Eigen::Matrix3d j;
    j.leftCols<2>() = s.Jacobian(uv);
    j.col(2) = -v;
    const Eigen::Vector3d f = s.Point(uv) - p - t * v;
    const Eigen::Vector3d dx = j.fullPivLu().solve(-f);
    if (!dx.allFinite()) return false;
    uv += dx.head<2>();
    t += dx.z();
    if (dx.norm() < 1e-12 * (1.0 + uv.norm() + std::abs(t))) {
      if (t_out != nullptr) *t_out = t;
      return true;
    }
  }
  return false;
}

// The first crossing of p + t v (smallest t) from Newton started at the surface's own line
// intersection and at a grid over the domain: no single start suits every surface kind.
bool IntersectAnywhere(const geom::Surface& s, const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                       Eigen::Vector2d& uv) {
  const geom::Domain2 dom = s.Domain();
  std::vector<Eigen::Vector2d> starts;
  Eigen::Vector3d hit;
  if (s.IntersectLine(p, v, hit)) starts.push_back(s.Project(hit).uv);
  constexpr int kGrid = 6;
  for (int i = 0; i <= kGrid; ++i) {
    for (int k = 0; k <= kGrid; ++k) {
      starts.push_back(dom.min + (dom.max - dom.min).cwiseProduct(Eigen::Vector2d(i, k) / kGrid));
    }
  }
  bool found = false;
  double best_t = 0.0;
  for (Eigen::Vector2d start : starts) {
    double t = 0.0;
    if (!IntersectNear(s, p, v, start, &t) || !dom.Contains(start, 1e-6)) continue;
    if (!found || t < best_t) {
      found = true;
      best_t = t;
      uv = start;
    }
  }
  return found;
}

CurvePoint PointAt(const geom::Surface& s, const Eigen::Vector2d& uv) {
  CurvePoint p;
  p.uv = uv;
  p.position = s.Point(uv);
  p.normal = s.Normal(uv);
  return p;
}

// Unit tangents from the neighbours: the derivative of the quadratic through three points
// (chord-length parameter) inside, the mirror of the neighbour's tangent about the chord at
// the ends (exact on a circular arc).
void SetTangents(SurfaceCurve& c) {
  const std::size_t n = c.size();
  if (n < 2) return;
  for (std::size_t j = 1; j + 1 < n; ++j) {
    const Eigen::Vector3d a = c[j].position - c[j - 1].position;
    const Eigen::Vector3d b = c[j + 1].position - c[j].position;
    const double h1 = a.norm();
    const double h2 = b.norm();
    c[j].tangent = Tangential(h1 * h1 * b + h2 * h2 * a, c[j].normal);
  }
  if (n == 2) {
    const Eigen::Vector3d chord = (c[1].position - c[0].position).normalized();
    c[0].tangent = Tangential(chord, c[0].normal);
    c[1].tangent = Tangential(chord, c[1].normal);
    return;
  }
  const Eigen::Vector3d chord0 = (c[1].position - c[0].position).normalized();
  c[0].tangent = Tangential(2.0 * chord0.dot(c[1].tangent) * chord0 - c[1].tangent, c[0].normal);
  const Eigen::Vector3d chord1 = (c[n - 1].position - c[n - 2].position).normalized();
  c[n - 1].tangent =
      Tangential(2.0 * chord1.dot(c[n - 2].tangent) * chord1 - c[n - 2].tangent, c[n - 1].normal);
}

struct AxisSampler {
  const geom::Surface& surface;
  const FiberAxis& axis;
  double chord_tol_mm;

  Eigen::Vector3d At(double t) const { return axis.start_mm + t * (axis.end_mm - axis.start_mm); }

  bool Sample(double t, Eigen::Vector2d& uv) const {
    return IntersectNear(surface, At(t), axis.projection, uv) &&
           surface.Domain().Contains(uv, 1e-6);
  }

  // Appends the points of (t0, t1] to `out`, halving where a chord strays beyond tolerance.
  bool Refine(double t0, const CurvePoint& p0, double t1, const CurvePoint& p1, int depth,
              SurfaceCurve& out) const {
    const double tm = 0.5 * (t0 + t1);
    Eigen::Vector2d uv = 0.5 * (p0.uv + p1.uv);
    if (!Sample(tm, uv)) return false;
    const CurvePoint pm = PointAt(surface, uv);
    const Eigen::Vector3d chord = p1.position - p0.position;
    const Eigen::Vector3d off = pm.position - p0.position;
    const double dev = chord.norm() > 0 ? chord.normalized().cross(off).norm() : off.norm();
    if (dev <= chord_tol_mm || depth >= kMaxRefineDepth) {
      out.push_back(p1);
      return true;
    }
    return Refine(t0, p0, tm, pm, depth + 1, out) && Refine(tm, pm, t1, p1, depth + 1, out);
  }
};

// Tangent of the projected axis: the (du, dv) that the axis direction induces along V.
Eigen::Vector3d ProjectedAxisTangent(const geom::Surface& s, const FiberAxis& axis,
                                     const CurvePoint& p) {
  Eigen::Matrix3d j;
  j.leftCols<2>() = s.Jacobian(p.uv);
  j.col(2) = -axis.projection;
  const Eigen::Vector3d x = j.fullPivLu().solve(axis.end_mm - axis.start_mm);
  return Tangential(j.leftCols<2>() * x.head<2>(), p.normal);
}

// Seed 002's offset of one point: P + d (N x T), projected to the closest surface point.
Foot PaperOffset(const geom::Surface& s, const CurvePoint& p, double d) {
  const Eigen::Vector3d o = p.normal.cross(p.tangent).normalized();
  return ProjectNear(s, p.position + d * o, p.uv);
}

// The corrected offset: walks the surface from P along N x T in substeps, each projected back
// and its arc length taken from the chord and the turn of the tangent (exact on a circle), the
// direction carried as the chord laid into the next tangent plane, until the arc walked is d.
Foot CorrectedOffset(const geom::Surface& s, const CurvePoint& p, double d, double max_substep) {
  return geom::WalkOnSurface(s, p.uv, p.normal.cross(p.tangent), d, max_substep);
}

constexpr std::array<double, 5> kGaussX = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                           0.5384693101056831, 0.9061798459386640};
constexpr std::array<double, 5> kGaussW = {0.2369268850561891, 0.4786286704993665,
                                           0.5688888888888889, 0.4786286704993665,
                                           0.2369268850561891};

double GaussLength(const geom::Surface& s, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                   int panels) {
  const Eigen::Vector2d dir = b - a;
  double sum = 0.0;
  for (int i = 0; i < panels; ++i) {
    for (std::size_t k = 0; k < kGaussX.size(); ++k) {
      const double t = (i + 0.5 * (1.0 + kGaussX[k])) / panels;
      sum += kGaussW[k] * (s.Jacobian(a + t * dir) * dir).norm();
    }
  }
  return 0.5 * sum / panels;
}

}  // namespace

ReferenceCurve ProjectFiberAxis(const geom::Surface& surface, const FiberAxis& axis,
                                double chord_tol_mm) {
  ReferenceCurve out;
  const Eigen::Vector3d dir = axis.end_mm - axis.start_mm;
  if (!(chord_tol_mm > 0) || dir.norm() <= 0 || axis.projection.norm() <= 0 ||
      dir.normalized().cross(axis.projection.normalized()).norm() < 1e-9) {
    out.message =
        "fiber axis: needs a length, a projection vector not along it and a tolerance > 0";
    return out;
  }
  const AxisSampler sampler{surface, axis, chord_tol_mm};
  Eigen::Vector2d uv;
  if (!IntersectAnywhere(surface, axis.start_mm, axis.projection, uv)) {
    out.message = "fiber axis: its start does not project onto the surface";
    return out;
  }
  out.points.push_back(PointAt(surface, uv));
  for (int i = 1; i <= kInitialAxisPieces; ++i) {
    const double t0 = static_cast<double>(i - 1) / kInitialAxisPieces;
    const double t1 = static_cast<double>(i) / kInitialAxisPieces;
    const CurvePoint p0 = out.points.back();
    if (!sampler.Sample(t1, uv) ||
        !sampler.Refine(t0, p0, t1, PointAt(surface, uv), 0, out.points)) {
      out.message = "fiber axis: part of it does not project onto the surface";
      return out;
    }
  }
  for (CurvePoint& p : out.points) p.tangent = ProjectedAxisTangent(surface, axis, p);
  out.ok = true;
  return out;
}

OffsetFamily OffsetCurves(const geom::Surface& surface, const SurfaceCurve& reference,
                          const OffsetOptions& options) {
  OffsetFamily out;
  out.curves.push_back(reference);
  const double d = options.distance_mm;
  const geom::Domain2 domain = surface.Domain();
  for (int i = 0; i < options.count; ++i) {
    const SurfaceCurve& from = out.curves.back();
    SurfaceCurve next;
    next.reserve(from.size());
    for (const CurvePoint& p : from) {
      const Foot f = options.method == OffsetMethod::kPaper
                         ? PaperOffset(surface, p, d)
                         : CorrectedOffset(surface, p, d, options.max_substep_mm);
      if (!f.converged || !domain.Contains(f.uv, 1e-6)) {
        out.message = "offset " + std::to_string(i + 1) + " leaves the surface";
        return out;
      }
      next.push_back(PointAt(surface, f.uv));
    }
    SetTangents(next);
    OffsetStepReport step;
    for (std::size_t j = 0; j < next.size(); ++j) {
      step.eq2_error_mm.push_back(CircularOffsetError(d, from[j].normal, next[j].normal));
      if (options.measure) {
        step.surface_distance_mm.push_back(SurfaceLength(surface, from[j].uv, next[j].uv));
      }
    }
    out.curves.push_back(std::move(next));
    out.steps.push_back(std::move(step));
  }
  out.ok = true;
  return out;
}

OffsetDrift MeasureDrift(const geom::Surface& surface, const OffsetFamily& family,
                         double distance_mm, std::size_t point_index) {
  OffsetDrift out;
  for (std::size_t i = 0; i + 1 < family.curves.size(); ++i) {
    out.surface_length_mm += SurfaceLength(surface, family.curves[i].at(point_index).uv,
                                           family.curves[i + 1].at(point_index).uv);
    out.eq2_total_mm += family.steps.at(i).eq2_error_mm.at(point_index);
    out.nominal_mm += distance_mm;
  }
  out.drift_mm = out.nominal_mm - out.surface_length_mm;
  return out;
}

double SurfaceLength(const geom::Surface& surface, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& b, double rel_tol) {
  double prev = GaussLength(surface, a, b, 1);
  for (int panels = 2; panels <= 1024; panels *= 2) {
    const double cur = GaussLength(surface, a, b, panels);
    if (std::abs(cur - prev) <= rel_tol * std::max(cur, 1e-300)) return cur;
    prev = cur;
  }
  return prev;
}

double CircularOffsetError(double distance_mm, const Eigen::Vector3d& n0,
                           const Eigen::Vector3d& n1) {
  const double psi = std::atan2(n0.cross(n1).norm(), n0.dot(n1));
  if (psi < 1e-8) return distance_mm * psi * psi / 3.0;  // 1 - psi / tan psi ~ psi^2 / 3
  return distance_mm * (1.0 - psi / std::tan(psi));
}

double LaminateAngleError(double radius_mm, double distance_mm, double theta_rad) {
  return theta_rad - std::acos(std::clamp(
                         radius_mm * std::cos(theta_rad) / (radius_mm + distance_mm), -1.0, 1.0));
}

}  // namespace stitchsim::planner
