// The laminate planner's thickness field: what the plies below actually lay, in (u, v).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "stitchsim/planner/laminate_planner.h"

namespace stitchsim::planner {
namespace {

/// How far outside a tow's quad a cell centre still counts as covered, mm: abutting courses
/// leave seams of up to 1e-4 mm (the walk's rounding; the wing's plies), and a cell centre in
/// such a seam would read as a trench of one ply through the field.
constexpr double kQuadTolMm = 0.01;

/// True when `x` lies inside the quad a0 a1 b1 b0 (either winding) or within kQuadTolMm of
/// it, so cells on the line two abutting tows share are covered by both.
bool InsideTowQuad(const Eigen::Vector2d (&q)[4], const Eigen::Vector2d& x) {
  int positive = 0, negative = 0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d e = q[(k + 1) % 4] - q[k];
    const Eigen::Vector2d r = x - q[k];
    const double len = e.norm();
    if (len <= 0.0) continue;
    const double side = (e.x() * r.y() - e.y() * r.x()) / len;  // signed distance, mm
    if (side > kQuadTolMm) ++positive;
    if (side < -kQuadTolMm) ++negative;
  }
  return positive == 0 || negative == 0;
}

}  // namespace

ThicknessField::ThicknessField(const geom::Domain2& domain, double cell_mm) {
  cell_ = std::min(cell_mm > 0.0 ? cell_mm : 2.0, 2.0);
  // One cell of zeros around the domain, so the lookup ramps to zero at its edge.
  origin_ = domain.min - Eigen::Vector2d::Constant(cell_);
  const Eigen::Vector2d size = domain.max - domain.min;
  nu_ = static_cast<long>(std::ceil(size.x() / cell_)) + 2;
  nv_ = static_cast<long>(std::ceil(size.y() / cell_)) + 2;
  mm_.assign(static_cast<std::size_t>(nu_ * nv_), 0.0);
}

double ThicknessField::Sample(long i, long j) const {
  if (i < 0 || j < 0 || i >= nu_ || j >= nv_) return 0.0;
  return mm_[static_cast<std::size_t>(i + nu_ * j)];
}

double ThicknessField::At(const Eigen::Vector2d& uv) const {
  // Sample (i, j) sits at the centre of its cell.
  const double fu = (uv.x() - origin_.x()) / cell_ - 0.5;
  const double fv = (uv.y() - origin_.y()) / cell_ - 0.5;
  const double i0 = std::floor(fu), j0 = std::floor(fv);
  const double a = fu - i0, b = fv - j0;
  const long i = static_cast<long>(i0), j = static_cast<long>(j0);
  return (1 - a) * (1 - b) * Sample(i, j) + a * (1 - b) * Sample(i + 1, j) +
         (1 - a) * b * Sample(i, j + 1) + a * b * Sample(i + 1, j + 1);
}

double ThicknessField::MaxMm() const {
  return mm_.empty() ? 0.0 : *std::max_element(mm_.begin(), mm_.end());
}

std::pair<double, double> ThicknessField::AddPly(const PlyPlan& plan, double thickness_mm) {
  std::vector<std::uint8_t> laid(mm_.size(), 0);
  auto mark = [&](const Eigen::Vector2d(&q)[4]) {
    Eigen::Vector2d lo = q[0], hi = q[0];
    for (const auto& p : q) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const long i0 = std::max(0L, static_cast<long>(std::floor((lo.x() - origin_.x()) / cell_)));
    const long j0 = std::max(0L, static_cast<long>(std::floor((lo.y() - origin_.y()) / cell_)));
    const long i1 =
        std::min(nu_ - 1, static_cast<long>(std::floor((hi.x() - origin_.x()) / cell_)));
    const long j1 =
        std::min(nv_ - 1, static_cast<long>(std::floor((hi.y() - origin_.y()) / cell_)));
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) {
        const Eigen::Vector2d centre = origin_ + cell_ * Eigen::Vector2d(i + 0.5, j + 0.5);
        if (InsideTowQuad(q, centre)) laid[static_cast<std::size_t>(i + nu_ * j)] = 1;
      }
  };
  for (const PlyCourse& c : plan.courses) {
    for (const PlyTow& t : c.tows) {
      const std::size_t k = static_cast<std::size_t>(t.tow - plan.band.first);  // left edge
      for (const TowSegment& g : t.laid) {
        for (std::size_t p = 1; p < c.points.size(); ++p) {
          const PlyPoint& a = c.points[p - 1];
          const PlyPoint& b = c.points[p];
          // The part of the step between the two poses that the piece lays: a piece that
          // starts or ends between poses (its add or cut) lays that fraction of the step.
          const double s0 = std::max(a.s_mm, g.start_mm), s1 = std::min(b.s_mm, g.end_mm);
          if (s1 <= s0 || b.s_mm <= a.s_mm) continue;
          auto at = [&](double s, std::size_t edge) -> Eigen::Vector2d {
            const double f = (s - a.s_mm) / (b.s_mm - a.s_mm);
            return (1 - f) * a.boundary_uv[edge] + f * b.boundary_uv[edge];
          };
          const Eigen::Vector2d q[4] = {at(s0, k), at(s0, k + 1), at(s1, k + 1), at(s1, k)};
          mark(q);
        }
      }
    }
  }
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < mm_.size(); ++i) {
    if (laid[i] == 0) continue;
    lo = std::min(lo, mm_[i]);
    hi = std::max(hi, mm_[i]);
    mm_[i] += thickness_mm;
  }
  if (lo > hi) return {0.0, 0.0};
  return {lo, hi};
}

}  // namespace stitchsim::planner
