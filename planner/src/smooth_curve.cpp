#include "detail/smooth_curve.h"

#include <algorithm>

#include "stitchsim/geom/surface_walk.h"

namespace stitchsim::planner::detail {

SmoothCurve::SmoothCurve(const geom::Surface& surface, const SurfaceCurve& c) {
  std::vector<const CurvePoint*> kept;
  for (const CurvePoint& p : c) {
    if (!kept.empty() && (p.position - kept.back()->position).norm() < 1e-6) continue;
    s_.push_back(kept.empty() ? 0.0 : s_.back() + (p.position - kept.back()->position).norm());
    uv_.push_back(p.uv);
    kept.push_back(&p);
  }
  const std::size_t n = uv_.size();
  m_.assign(n, Eigen::Vector2d::Zero());
  if (n < 2) return;
  // Clamped spline: tridiagonal system for the second derivatives (Thomas algorithm).
  std::vector<double> lower(n, 0.0), diag(n, 0.0), upper(n, 0.0);
  std::vector<Eigen::Vector2d> rhs(n, Eigen::Vector2d::Zero());
  auto h = [&](std::size_t i) { return s_[i + 1] - s_[i]; };
  auto secant = [&](std::size_t i) { return Eigen::Vector2d((uv_[i + 1] - uv_[i]) / h(i)); };
  const Eigen::Vector2d slope0 = geom::UvOfTangent(surface, uv_.front(), kept.front()->tangent);
  const Eigen::Vector2d slope1 = geom::UvOfTangent(surface, uv_.back(), kept.back()->tangent);
  diag[0] = 2.0 * h(0);
  upper[0] = h(0);
  rhs[0] = 6.0 * (secant(0) - slope0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    lower[i] = h(i - 1);
    diag[i] = 2.0 * (h(i - 1) + h(i));
    upper[i] = h(i);
    rhs[i] = 6.0 * (secant(i) - secant(i - 1));
  }
  lower[n - 1] = h(n - 2);
  diag[n - 1] = 2.0 * h(n - 2);
  rhs[n - 1] = 6.0 * (slope1 - secant(n - 2));
  for (std::size_t i = 1; i < n; ++i) {
    const double f = lower[i] / diag[i - 1];
    diag[i] -= f * upper[i - 1];
    rhs[i] -= f * rhs[i - 1];
  }
  m_[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) m_[i] = (rhs[i] - upper[i] * m_[i + 1]) / diag[i];
}

std::size_t SmoothCurve::Piece(double s) const {
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const long i = static_cast<long>(it - s_.begin()) - 1;
  return static_cast<std::size_t>(std::clamp<long>(i, 0, static_cast<long>(s_.size()) - 2));
}

Eigen::Vector2d SmoothCurve::Uv(double s) const {
  if (s_.size() < 2) return uv_.empty() ? Eigen::Vector2d::Zero() : uv_.front();
  s = std::clamp(s, 0.0, Length());
  const std::size_t i = Piece(s);
  const double h = s_[i + 1] - s_[i], a = s_[i + 1] - s, b = s - s_[i];
  return m_[i] * (a * a * a / (6.0 * h)) + m_[i + 1] * (b * b * b / (6.0 * h)) +
         (uv_[i] / h - m_[i] * h / 6.0) * a + (uv_[i + 1] / h - m_[i + 1] * h / 6.0) * b;
}

Eigen::Vector2d SmoothCurve::Slope(double s) const {
  if (s_.size() < 2) return Eigen::Vector2d::Zero();
  s = std::clamp(s, 0.0, Length());
  const std::size_t i = Piece(s);
  const double h = s_[i + 1] - s_[i], a = s_[i + 1] - s, b = s - s_[i];
  return -m_[i] * (a * a / (2.0 * h)) + m_[i + 1] * (b * b / (2.0 * h)) -
         (uv_[i] / h - m_[i] * h / 6.0) + (uv_[i + 1] / h - m_[i + 1] * h / 6.0);
}

}  // namespace stitchsim::planner::detail
