#include "stitchsim/geom/surface_walk.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace stitchsim::geom {

SurfaceFoot ProjectNear(const Surface& s, const Eigen::Vector3d& p, Eigen::Vector2d uv) {
  SurfaceFoot out;
  for (int iter = 0; iter < 200; ++iter) {
    Eigen::Vector3d at;
    Eigen::Matrix<double, 3, 2> j;
    s.PointAndJacobian(uv, at, j);
    const Eigen::Vector2d step = (j.transpose() * j).ldlt().solve(j.transpose() * (p - at));
    if (!step.allFinite()) return out;
    uv += step;
    if (step.norm() < 1e-13 * (1.0 + uv.norm())) {
      out.converged = true;
      break;
    }
  }
  out.uv = uv;
  out.point = s.Point(uv);
  return out;
}

Eigen::Vector2d UvOfTangent(const Surface& s, const Eigen::Vector2d& uv, const Eigen::Vector3d& t) {
  const Eigen::Matrix<double, 3, 2> j = s.Jacobian(uv);
  return (j.transpose() * j).ldlt().solve(j.transpose() * t);
}

Eigen::Vector3d Tangential(const Eigen::Vector3d& w, const Eigen::Vector3d& n) {
  return (w - w.dot(n) * n).normalized();
}

namespace {

/// d n / ds at `uv` along the unit tangent `w` (central difference over `eps_mm` of arc).
Eigen::Vector3d NormalRate(const Surface& s, const Eigen::Vector2d& uv, const Eigen::Vector3d& w) {
  constexpr double kEpsMm = 1e-3;
  const Eigen::Vector2d uv_rate = UvOfTangent(s, uv, w);
  return (s.Normal(uv + kEpsMm * uv_rate) - s.Normal(uv - kEpsMm * uv_rate)) / (2.0 * kEpsMm);
}

// A walk's first chord is at most this long: its direction's error grows as its length^4
// (on a cylinder of R 75 at 60 deg, 1e-8 rad for 3.5 mm; half a tow width is 3.175 mm).
constexpr double kFirstChordMm = 3.5;

/// The chord of a circle of curvature `k` over the arc `h`.
double CircleChord(double k, double h) {
  const double bend = std::abs(k) * h;
  return bend > 1e-6 ? 2.0 * std::sin(0.5 * bend) / std::abs(k) : h * (1.0 - bend * bend / 24.0);
}

/// The geodesic's point at arc `h` from `x` (its unit tangent in x.tangent): its Taylor series
/// (x'' = k n with k = -t.n', x''' = k n' + k' n, x''''.n = k'' - k |n'|^2; the terms in k' and
/// k'', nil on a cylinder and a sphere, are left to the projection) for the chord's direction, the
/// chord of a circle of curvature k over the arc h for its length (exact on a circle; on a helix of
/// radius R at a to the axis, to h^5 sin^6 a cos^2 a / 720 R^4).
SurfaceFoot FirstChord(const Surface& s, const SurfaceFoot& x, double h, double& k) {
  const Eigen::Vector3d& w = x.tangent;
  const Eigen::Vector3d rate = NormalRate(s, x.uv, w);
  k = -w.dot(rate);
  const Eigen::Vector3d taylor =
      x.point + h * w +
      (0.5 * h * h * k - (h * h * h * h / 24.0) * k * rate.squaredNorm()) * s.Normal(x.uv) +
      (h * h * h / 6.0) * k * rate;
  const SurfaceFoot y = ProjectNear(s, taylor, x.uv);
  if (!y.converged) return y;
  return ProjectNear(s, x.point + CircleChord(k, h) * (y.point - x.point).normalized(), y.uv);
}

/// Arc over chord of a circle whose chords turn by `turn_rad` from one to the next.
double ArcPerChord(double turn_rad) {
  const double half = 0.5 * turn_rad;
  return half > 1e-6 ? half / std::sin(half) : 1.0 + half * half / 6.0;
}

}  // namespace

SurfaceFoot WalkOnSurface(const Surface& s, const Eigen::Vector2d& uv,
                          const Eigen::Vector3d& direction, double length_mm,
                          double max_substep_mm) {
  const Eigen::Vector3d n0 = s.Normal(uv);
  SurfaceFoot x{uv, s.Point(uv), true, Tangential(direction, n0)};
  if (!(length_mm > 0)) return x;
  const int pieces = std::max(1, static_cast<int>(std::ceil(length_mm / max_substep_mm)));
  const double h = length_mm / pieces;
  // The first chord fixes the walk's direction (its twist out of the plane of the tangent and
  // the normal is third order in its length, and an error there turns the whole walk): over
  // more than kFirstChordMm it is walked in short chords.
  const bool sub_walk = h > kFirstChordMm;
  double k0 = 0.0;  // the normal curvature along the first chord's start
  SurfaceFoot y =
      sub_walk ? WalkOnSurface(s, uv, x.tangent, h, kFirstChordMm) : FirstChord(s, x, h, k0);
  if (!y.converged) return y;
  // Then chords each the last one reflected in the tangent plane between them (the discrete
  // geodesic: a shortest polyline's chords meet every tangent plane at equal angles), as long
  // as the first one times the ratio of arc to chord there to here, judged by the turn between
  // chords. Points one arc apart on a helix of a cylinder or a great circle of a sphere are such
  // a polyline with equal chords, so the walk is exact there; elsewhere it is second order.
  Eigen::Vector3d chord = y.point - x.point;
  const double first_chord_mm = chord.norm();
  double first_gain = 1.0;
  for (int k = 1; k < pieces; ++k) {
    const Eigen::Vector3d n = s.Normal(y.uv);
    const Eigen::Vector3d c = chord / chord.norm();
    const double gain = ArcPerChord(2.0 * std::asin(std::min(1.0, std::abs(c.dot(n)))));
    if (k == 1) first_gain = gain;
    const Eigen::Vector3d next = c - 2.0 * c.dot(n) * n;
    SurfaceFoot z = ProjectNear(s, y.point + first_chord_mm * first_gain / gain * next, y.uv);
    if (!z.converged) return z;
    chord = z.point - y.point;
    y = z;
  }
  // The end tangent: the last chord's tangential part less its third-order twist.
  const Eigen::Vector3d n1 = s.Normal(y.uv);
  const Eigen::Vector3d t1 = Tangential(chord, n1);
  const Eigen::Vector3d rate1 = NormalRate(s, y.uv, t1);
  const double k1 = -t1.dot(rate1);
  y.tangent = Tangential(chord - (h * h * h / 6.0) * k1 * rate1, n1);
  if (pieces == 1 && !sub_walk && std::abs(k1) != std::abs(k0)) {
    // One chord: its length from the curvature at both ends (the start's alone is first order
    // where the curvature changes; equal on a cylinder and a sphere).
    const double k_mean = std::sqrt(0.5 * (k0 * k0 + k1 * k1));
    const Eigen::Vector3d tangent = y.tangent;
    y = ProjectNear(s, x.point + CircleChord(k_mean, h) * chord.normalized(), y.uv);
    y.tangent = tangent;
  }
  return y;
}

std::optional<double> DistanceAlongGeodesic(const Surface& s, const Eigen::Vector2d& uv,
                                            const Eigen::Vector3d& direction,
                                            const Eigen::Vector3d& to, double max_substep_mm) {
  const Eigen::Vector3d w = Tangential(direction, s.Normal(uv));
  double d = (to - s.Point(uv)).dot(w);
  // Each pass walks to the current estimate and adds what is left along the end tangent; the
  // remainder shrinks by about the turn of the tangent over it (to 1e-9 mm: a surface's points
  // are found to about 1e-13 of their parameter, 1e-10 mm at a metre).
  for (int iter = 0; iter < 10; ++iter) {
    const double sign = d < 0 ? -1.0 : 1.0;
    const SurfaceFoot f = WalkOnSurface(s, uv, sign * w, std::abs(d), max_substep_mm);
    if (!f.converged) return std::nullopt;
    const double rest = (to - f.point).dot(sign * f.tangent);
    d += rest;
    if (std::abs(rest) <= 1e-9) break;
  }
  return d;
}

}  // namespace stitchsim::geom
