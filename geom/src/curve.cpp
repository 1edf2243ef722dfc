#include "stitchsim/geom/curve.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace stitchsim::geom {
namespace {

class LineSegment final : public CurveSegment {
 public:
  LineSegment(Eigen::Vector2d a, Eigen::Vector2d b) : a_(a), b_(b) {}
  Eigen::Vector2d At(double t) const override { return a_ + t * (b_ - a_); }
  Eigen::Vector2d Derivative(double) const override { return b_ - a_; }
  void Evaluate(double t, Eigen::Vector2d& point, Eigen::Vector2d& derivative) const override {
    point = a_ + t * (b_ - a_);
    derivative = b_ - a_;
  }

 private:
  Eigen::Vector2d a_, b_;
};

class EllipticArc final : public CurveSegment {
 public:
  EllipticArc(Eigen::Vector2d c, double a, double b, double rot, double th0, double th1)
      : c_(c), a_(a), b_(b), th0_(th0), th1_(th1) {
    r_ << std::cos(rot), -std::sin(rot), std::sin(rot), std::cos(rot);
  }
  Eigen::Vector2d At(double t) const override {
    const double th = th0_ + t * (th1_ - th0_);
    return c_ + r_ * Eigen::Vector2d(a_ * std::cos(th), b_ * std::sin(th));
  }
  Eigen::Vector2d Derivative(double t) const override {
    const double th = th0_ + t * (th1_ - th0_);
    return (th1_ - th0_) * (r_ * Eigen::Vector2d(-a_ * std::sin(th), b_ * std::cos(th)));
  }
  void Evaluate(double t, Eigen::Vector2d& point, Eigen::Vector2d& derivative) const override {
    // The same expressions as At and Derivative, one sin/cos pair for both.
    const double th = th0_ + t * (th1_ - th0_);
    const double c = std::cos(th);
    const double s = std::sin(th);
    point = c_ + r_ * Eigen::Vector2d(a_ * c, b_ * s);
    derivative = (th1_ - th0_) * (r_ * Eigen::Vector2d(-a_ * s, b_ * c));
  }

 private:
  Eigen::Vector2d c_;
  double a_, b_, th0_, th1_;
  Eigen::Matrix2d r_;
};

// 8-point Gauss-Legendre on [0, 1].
constexpr double kGaussX[8] = {0.019855071751231856, 0.10166676129318664, 0.2372337950418355,
                               0.4082826787521751,   0.5917173212478249,  0.7627662049581645,
                               0.8983332387068134,   0.9801449282487681};
constexpr double kGaussW[8] = {0.05061426814518813, 0.11119051722668724, 0.15685332293894363,
                               0.18134189168918100, 0.18134189168918100, 0.15685332293894363,
                               0.11119051722668724, 0.05061426814518813};

// |d/dt surface(curve(t))|: mm of lifted path per unit t.
double Speed(const Surface& surface, const CurveSegment& segment, double t) {
  Eigen::Vector2d uv, duv;
  segment.Evaluate(t, uv, duv);
  return (surface.Jacobian(uv) * duv).norm();
}

// Lifted length from t0 to t1 (negative when t1 < t0), 8-point Gauss-Legendre.
double GaussLength(const Surface& surface, const CurveSegment& segment, double t0, double t1) {
  double sum = 0.0;
  for (int k = 0; k < 8; ++k) {
    sum += kGaussW[k] * Speed(surface, segment, t0 + (t1 - t0) * kGaussX[k]);
  }
  return sum * (t1 - t0);
}

// Newton, safeguarded by bisection, for the t in [lo, hi] where the lifted length from t0
// equals `remaining_mm` (which may be negative); t0 is in [lo, hi]. Each step integrates only
// from the last iterate, so the cost does not grow with the distance from the knot.
double SolveForArcLength(const Surface& surface, const CurveSegment& segment, double t0,
                         double remaining_mm, double lo, double hi) {
  // Below this residual one more Newton step leaves an error of order
  // (speed' / speed^2) * f^2, far below 1e-12 mm for any curve a scene can describe, so the
  // step is taken without evaluating the integral again.
  constexpr double kFinishMm = 1e-7;
  double t = t0;
  double f = -remaining_mm;  // lifted length from t0 to t minus the target
  for (int iter = 0; iter < 60; ++iter) {
    if (std::abs(f) < 1e-13) break;
    if (f > 0) {
      hi = t;
    } else {
      lo = t;
    }
    const double speed = Speed(surface, segment, t);
    double next = speed > 0 ? t - f / speed : 0.5 * (lo + hi);
    // Inclusive: near the root a step may round onto the bracket end it just set.
    const bool newton = next >= lo && next <= hi;
    if (!newton) next = 0.5 * (lo + hi);
    if (newton && std::abs(f) < kFinishMm) return next;
    if (next == t) break;
    f += GaussLength(surface, segment, t, next);
    t = next;
  }
  return t;
}

}  // namespace

std::unique_ptr<CurveSegment> MakeLineSegment(Eigen::Vector2d from, Eigen::Vector2d to) {
  return std::make_unique<LineSegment>(from, to);
}

std::unique_ptr<CurveSegment> MakeEllipticArc(Eigen::Vector2d centre, double a, double b,
                                              double rotation_rad, double start_rad,
                                              double end_rad) {
  return std::make_unique<EllipticArc>(centre, a, b, rotation_rad, start_rad, end_rad);
}

void Curve2::Add(std::unique_ptr<CurveSegment> segment, std::string label) {
  segments_.push_back(std::move(segment));
  labels_.push_back(std::move(label));
}

bool Curve2::Closed(double tol_mm) const {
  return !segments_.empty() && (Start() - End()).norm() <= tol_mm;
}

Eigen::Vector2d Curve2::Start() const { return segments_.front()->At(0.0); }
Eigen::Vector2d Curve2::End() const { return segments_.back()->At(1.0); }

SurfacePath::SurfacePath(const Surface& surface, const Curve2& curve, double tolerance_mm)
    : surface_(&surface), curve_(&curve) {
  assert(curve.SegmentCount() > 0);
  closed_ = curve.Closed(1e-9);
  const std::size_t n = curve.SegmentCount();
  knot_t_.resize(n);
  knot_s_.resize(n);
  segment_start_s_.resize(n);
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    segment_start_s_[i] = s;
    // Refine a uniform knot grid until doubling it changes the length below tolerance.
    int pieces = 16;
    double previous = -1.0;
    for (int round = 0; round < 12; ++round) {
      double total = 0.0;
      for (int k = 0; k < pieces; ++k) {
        total +=
            SegmentLength(i, static_cast<double>(k) / pieces, static_cast<double>(k + 1) / pieces);
      }
      if (previous >= 0.0 && std::abs(total - previous) <= tolerance_mm) break;
      previous = total;
      pieces *= 2;
    }
    auto& kt = knot_t_[i];
    auto& ks = knot_s_[i];
    kt.resize(static_cast<std::size_t>(pieces) + 1);
    ks.resize(static_cast<std::size_t>(pieces) + 1);
    kt[0] = 0.0;
    ks[0] = 0.0;
    for (int k = 1; k <= pieces; ++k) {
      kt[static_cast<std::size_t>(k)] = static_cast<double>(k) / pieces;
      ks[static_cast<std::size_t>(k)] =
          ks[static_cast<std::size_t>(k - 1)] +
          SegmentLength(i, static_cast<double>(k - 1) / pieces, static_cast<double>(k) / pieces);
    }
    s += ks.back();
  }
  total_length_mm_ = s;
}

double SurfacePath::SegmentLength(std::size_t segment, double t0, double t1) const {
  return GaussLength(*surface_, curve_->Segment(segment), t0, t1);
}

double SurfacePath::ArcLengthAt(std::size_t segment, double t) const {
  const auto& kt = knot_t_[segment];
  const auto& ks = knot_s_[segment];
  t = std::clamp(t, 0.0, 1.0);
  const auto it = std::upper_bound(kt.begin(), kt.end(), t);
  const std::size_t k = std::min<std::size_t>(
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - kt.begin() - 1, 0)), kt.size() - 2);
  return segment_start_s_[segment] + ks[k] + SegmentLength(segment, kt[k], t);
}

PathPoint SurfacePath::At(std::size_t segment, double t) const {
  PathPoint p;
  p.segment = segment;
  p.t = t;
  p.uv = curve_->Segment(segment).At(t);
  p.position = surface_->Point(p.uv);
  p.normal = surface_->Normal(p.uv);
  p.arc_length_mm = ArcLengthAt(segment, t);
  return p;
}

std::size_t SurfacePath::SegmentAtArcLength(double s) const {
  s = std::clamp(s, 0.0, total_length_mm_);
  // Last segment whose start <= s.
  const auto seg = static_cast<std::size_t>(
      std::upper_bound(segment_start_s_.begin(), segment_start_s_.end(), s) -
      segment_start_s_.begin());
  return seg == 0 ? 0 : seg - 1;
}

std::size_t SurfacePath::KnotIntervalAt(std::size_t segment, double local_s) const {
  const auto& ks = knot_s_[segment];
  const auto k = std::upper_bound(ks.begin(), ks.end(), local_s) - ks.begin() - 1;
  return std::min<std::size_t>(static_cast<std::size_t>(std::max<std::ptrdiff_t>(k, 0)),
                               ks.size() - 2);
}

PathPoint SurfacePath::PointAt(std::size_t segment, double t, double s) const {
  PathPoint p;
  p.segment = segment;
  p.t = t;
  p.uv = curve_->Segment(segment).At(t);
  p.position = surface_->Point(p.uv);
  p.normal = surface_->Normal(p.uv);
  p.arc_length_mm = s;
  return p;
}

PathPoint SurfacePath::AtArcLength(double s) const {
  s = std::clamp(s, 0.0, total_length_mm_);
  const std::size_t seg = SegmentAtArcLength(s);
  return SolveInKnotInterval(seg, KnotIntervalAt(seg, s - segment_start_s_[seg]), s, nullptr);
}

PathPoint SurfacePath::AtArcLengthFrom(const PathPoint& near, double s) const {
  s = std::clamp(s, 0.0, total_length_mm_);
  const std::size_t seg = SegmentAtArcLength(s);
  const std::size_t k = KnotIntervalAt(seg, s - segment_start_s_[seg]);
  const auto& kt = knot_t_[seg];
  const bool same_interval = near.segment == seg && near.t >= kt[k] && near.t <= kt[k + 1];
  return SolveInKnotInterval(seg, k, s, same_interval ? &near : nullptr);
}

PathPoint SurfacePath::SolveInKnotInterval(std::size_t seg, std::size_t k, double s,
                                           const PathPoint* near) const {
  const auto& kt = knot_t_[seg];
  const auto& ks = knot_s_[seg];
  const double lo = kt[k];
  const double hi = kt[k + 1];
  const double target = s - segment_start_s_[seg] - ks[k];  // arc length from the knot
  const double span = ks[k + 1] - ks[k];
  // First guess: the interval's mean dt/ds, from the knot or from a nearby point (exact at
  // constant speed). The arc length is always measured from the knot, as the table is: a
  // chain of nearby points would add up each solution's rounding along a long path.
  double t0 = lo;
  if (span > 0) {
    t0 = near != nullptr ? near->t + (hi - lo) * (s - near->arc_length_mm) / span
                         : lo + (hi - lo) * target / span;
    t0 = std::clamp(t0, lo, hi);
  }
  const CurveSegment& cs = curve_->Segment(seg);
  const double remaining = target - GaussLength(*surface_, cs, lo, t0);
  return PointAt(seg, SolveForArcLength(*surface_, cs, t0, remaining, lo, hi), s);
}

std::optional<int> StitchCount(double path_length_mm, double nominal_mm) {
  if (!std::isfinite(path_length_mm) || !std::isfinite(nominal_mm) || nominal_mm <= 0.0 ||
      path_length_mm <= 0.0) {
    return std::nullopt;
  }
  if (path_length_mm < nominal_mm) return std::nullopt;  // shorter than one stitch
  const double ratio = path_length_mm / nominal_mm;
  if (ratio > 1e9) return std::nullopt;
  const int lo = std::max(1, static_cast<int>(std::floor(ratio)));
  const int hi = lo + 1;
  const double err_lo = std::abs(path_length_mm / lo - nominal_mm);
  const double err_hi = std::abs(path_length_mm / hi - nominal_mm);
  // Ties (within rounding) go to the larger count: shorter stitches are the safe side.
  const double tie_tol = 1e-12 * nominal_mm;
  return err_hi <= err_lo + tie_tol ? hi : lo;
}

}  // namespace stitchsim::geom
