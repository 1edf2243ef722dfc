#include "projection_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stitchsim::geom::detail {
namespace {

constexpr int kBlock = 8;  // cells per block side
// Every box is widened by at least this fraction of its cell's diagonal (a piece of surface
// with an inflection can bulge between samples while its midpoints lie on the chords).
constexpr double kMinPadOfDiagonal = 1e-3;

}  // namespace

double ProjectionIndex::Distance2(const Box& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = (b.lo - p).cwiseMax(p - b.hi).cwiseMax(0.0);
  return d.squaredNorm();
}

bool ProjectionIndex::Build(const Surface& s, const Eigen::Vector2i& cells) {
  const Domain2 dom = s.Domain();
  cells_ = cells.cwiseMax(1);
  origin_ = dom.min;
  cell_ = (dom.max - dom.min).cwiseQuotient(cells_.cast<double>());
  const int su = 2 * cells_.x() + 1, sv = 2 * cells_.y() + 1;
  std::vector<Eigen::Vector3d> sample(static_cast<std::size_t>(su) * static_cast<std::size_t>(sv));
  auto at = [&](int i, int k) -> Eigen::Vector3d& {
    return sample[static_cast<std::size_t>(k) * static_cast<std::size_t>(su) +
                  static_cast<std::size_t>(i)];
  };
  for (int k = 0; k < sv; ++k) {
    for (int i = 0; i < su; ++i) {
      at(i, k) = s.Point(origin_ + 0.5 * cell_.cwiseProduct(Eigen::Vector2d(i, k)));
      if (!at(i, k).allFinite()) return false;
    }
  }
  cell_boxes_.assign(static_cast<std::size_t>(cells_.prod()), Box{});
  centres_.assign(cell_boxes_.size(), Eigen::Vector3d::Zero());
  for (int iv = 0; iv < cells_.y(); ++iv) {
    for (int iu = 0; iu < cells_.x(); ++iu) {
      const int i = 2 * iu, k = 2 * iv;
      Box b{at(i, k), at(i, k)};
      for (int a = 0; a <= 2; ++a) {
        for (int c = 0; c <= 2; ++c) {
          b.lo = b.lo.cwiseMin(at(i + a, k + c));
          b.hi = b.hi.cwiseMax(at(i + a, k + c));
        }
      }
      // How far each midpoint bulges from the chord (or patch) through its neighbours.
      double bulge = 0.0;
      for (int c = 0; c <= 2; ++c) {
        bulge =
            std::max(bulge, (at(i + 1, k + c) - 0.5 * (at(i, k + c) + at(i + 2, k + c))).norm());
        bulge =
            std::max(bulge, (at(i + c, k + 1) - 0.5 * (at(i + c, k) + at(i + c, k + 2))).norm());
      }
      const Eigen::Vector3d corners =
          0.25 * (at(i, k) + at(i + 2, k) + at(i, k + 2) + at(i + 2, k + 2));
      bulge = std::max(bulge, (at(i + 1, k + 1) - corners).norm());
      const double pad =
          2.0 * bulge + kMinPadOfDiagonal * (at(i + 2, k + 2) - at(i, k)).norm() + 1e-9;
      b.lo.array() -= pad;
      b.hi.array() += pad;
      const auto index = static_cast<std::size_t>(iv) * static_cast<std::size_t>(cells_.x()) +
                         static_cast<std::size_t>(iu);
      cell_boxes_[index] = b;
      centres_[index] = at(i + 1, k + 1);
    }
  }
  blocks_ = (cells_.array() + kBlock - 1) / kBlock;
  block_boxes_.assign(static_cast<std::size_t>(blocks_.prod()), Box{});
  std::vector<bool> seen(block_boxes_.size(), false);
  for (int iv = 0; iv < cells_.y(); ++iv) {
    for (int iu = 0; iu < cells_.x(); ++iu) {
      const auto bi =
          static_cast<std::size_t>(iv / kBlock) * static_cast<std::size_t>(blocks_.x()) +
          static_cast<std::size_t>(iu / kBlock);
      const Box& c =
          cell_boxes_[static_cast<std::size_t>(iv) * static_cast<std::size_t>(cells_.x()) +
                      static_cast<std::size_t>(iu)];
      Box& b = block_boxes_[bi];
      if (!seen[bi]) {
        b = c;
        seen[bi] = true;
      }
      b.lo = b.lo.cwiseMin(c.lo);
      b.hi = b.hi.cwiseMax(c.hi);
    }
  }
  return true;
}

Eigen::Vector2d ProjectionIndex::NearestCentre(const Eigen::Vector3d& p) const {
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_i = 0;
  for (std::size_t i = 0; i < centres_.size(); ++i) {
    const double d = (centres_[i] - p).squaredNorm();
    if (d < best) {
      best = d;
      best_i = i;
    }
  }
  const auto nu = static_cast<std::size_t>(cells_.x());
  return CentreOf(Eigen::Vector2i(static_cast<int>(best_i % nu), static_cast<int>(best_i / nu)));
}

Eigen::Vector2i ProjectionIndex::CellOf(const Eigen::Vector2d& uv) const {
  const Eigen::Vector2d f = (uv - origin_).cwiseQuotient(cell_);
  return Eigen::Vector2i(std::clamp(static_cast<int>(std::floor(f.x())), 0, cells_.x() - 1),
                         std::clamp(static_cast<int>(std::floor(f.y())), 0, cells_.y() - 1));
}

Eigen::Vector2d ProjectionIndex::CentreOf(const Eigen::Vector2i& c) const {
  return origin_ + cell_.cwiseProduct(c.cast<double>() + Eigen::Vector2d::Constant(0.5));
}

void ProjectionIndex::CellsWithin(const Eigen::Vector3d& p, double radius,
                                  std::vector<Near>& out) const {
  out.clear();
  const double r2 = radius * radius;
  for (int bv = 0; bv < blocks_.y(); ++bv) {
    for (int bu = 0; bu < blocks_.x(); ++bu) {
      const auto bi = static_cast<std::size_t>(bv) * static_cast<std::size_t>(blocks_.x()) +
                      static_cast<std::size_t>(bu);
      if (!(Distance2(block_boxes_[bi], p) < r2)) continue;
      const int iv_end = std::min(cells_.y(), (bv + 1) * kBlock);
      const int iu_end = std::min(cells_.x(), (bu + 1) * kBlock);
      for (int iv = bv * kBlock; iv < iv_end; ++iv) {
        for (int iu = bu * kBlock; iu < iu_end; ++iu) {
          const double d2 = Distance2(
              cell_boxes_[static_cast<std::size_t>(iv) * static_cast<std::size_t>(cells_.x()) +
                          static_cast<std::size_t>(iu)],
              p);
          if (d2 < r2) out.push_back({Eigen::Vector2i(iu, iv), d2});
        }
      }
    }
  }
  std::sort(out.begin(), out.end(),
            [](const Near& a, const Near& b) { return a.box_d2 < b.box_d2; });
}

}  // namespace stitchsim::geom::detail
