#pragma once
// Small closed polygons in the plane (a ply boundary in a surface's (u, v)): signed area,
// point inside, self-crossing, and how much of a segment lies outside. Header only.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace stitchsim::geom {

using Polygon2 = std::vector<Eigen::Vector2d>;  ///< closed: the last point joins the first

/// Signed area (> 0 counter-clockwise).
inline double SignedArea(const Polygon2& p) {
  double a = 0.0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Eigen::Vector2d& q = p[i];
    const Eigen::Vector2d& r = p[(i + 1) % n];
    a += q.x() * r.y() - r.x() * q.y();
  }
  return 0.5 * a;
}

/// Even-odd rule; points on an edge count as either.
inline bool InsidePolygon(const Polygon2& p, const Eigen::Vector2d& x) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y() > x.y()) != (p[j].y() > x.y()) &&
        x.x() < (p[j].x() - p[i].x()) * (x.y() - p[i].y()) / (p[j].y() - p[i].y()) + p[i].x()) {
      in = !in;
    }
  }
  return in;
}

inline double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Parameter t in [0, 1] along a->b where it crosses c->d (proper or touching), if it does.
inline bool SegmentCrossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                            const Eigen::Vector2d& c, const Eigen::Vector2d& d, double& t) {
  const Eigen::Vector2d r = b - a, s = d - c;
  const double den = Cross2(r, s);
  if (std::abs(den) < 1e-300) return false;  // parallel: no single crossing
  t = Cross2(c - a, s) / den;
  const double w = Cross2(c - a, r) / den;
  return t >= 0.0 && t <= 1.0 && w >= 0.0 && w <= 1.0;
}

/// True if two edges that are not neighbours touch or cross (or neighbours fold back).
inline bool SelfCrossing(const Polygon2& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
      if (neighbours) continue;
      double t = 0.0;
      if (SegmentCrossing(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n], t)) return true;
    }
  }
  return false;
}

/// Fraction (0..1) of the segment a->b that lies outside the polygon.
inline double FractionOutside(const Polygon2& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b) {
  std::vector<double> ts = {0.0, 1.0};
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    double t = 0.0;
    if (SegmentCrossing(a, b, p[i], p[(i + 1) % n], t)) ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  double outside = 0.0;
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    const double len = ts[i + 1] - ts[i];
    if (len <= 0.0) continue;
    if (!InsidePolygon(p, a + 0.5 * (ts[i] + ts[i + 1]) * (b - a))) outside += len;
  }
  return std::clamp(outside, 0.0, 1.0);
}

/// Distance from x to the segment a-b.
inline double DistanceToSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                const Eigen::Vector2d& x) {
  const Eigen::Vector2d d = b - a;
  const double t = std::clamp((x - a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * d - x).norm();
}

/// Distance from x to the polygon's edges.
inline double DistanceToPolygon(const Polygon2& p, const Eigen::Vector2d& x) {
  double best = INFINITY;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    best = std::min(best, DistanceToSegment(p[i], p[(i + 1) % n], x));
  }
  return best;
}

}  // namespace stitchsim::geom
