// afp.coverage: how the laid tows cover each ply of the scene (M70 P<n> lays ply n of the
// scene's `plies:`, 1-based). A grid over the ply boundary's (u, v) box (cells <= w / 4, at
// most kMaxCells, each weighted by its area on the surface, |Ju x Jv|) is painted with every
// laid tow's quad between consecutive poses (a course paints a cell once per tow). When the
// ply ends: the area left bare and the area laid twice or more, as percent of the ply's area
// beyond a band of one tow width along its boundary (inside the band the coverage policy
// governs), and the area laid outside the boundary (in the finding's message).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "afp_laid.h"

namespace stitchsim::verify {
namespace {

constexpr double kMaxCells = 1.0e6;

double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

bool InsidePolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

double DistanceToPolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d ab = poly[i] - poly[j];
    const double t =
        std::clamp((p - poly[j]).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (poly[j] + t * ab - p).norm());
  }
  return best;
}

// True when `p` lies in the convex quad a b c d (either winding).
bool InsideQuad(const Eigen::Vector2d (&q)[4], const Eigen::Vector2d& p) {
  int pos = 0, neg = 0;
  for (int i = 0; i < 4; ++i) {
    const double c = Cross2(q[(i + 1) % 4] - q[i], p - q[i]);
    pos += c > 0;
    neg += c < 0;
  }
  return pos == 0 || neg == 0;
}

class CoverageRule final : public Rule {
 public:
  CoverageRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.coverage",
             "ply area left bare (rule figures) and laid twice or more, beyond a band of one "
             "tow width along the ply boundary, percent of that area",
             "%"),
        scene_(ctx.scene),
        laid_(std::move(laid)) {
    summary_.error_limit = ctx.scene->limits.Get(scene::LimitKey::kAfpCoverageMaxBarePct);
    doubled_limit_ = ctx.scene->limits.Value(scene::LimitKey::kAfpCoverageMaxDoubledPct);
    AddSubject("bare", summary_.error_limit, std::nullopt);
    AddSubject("doubled", doubled_limit_, std::nullopt);
  }

  void OnLine(const trace::LineRecord& record) override {
    if (record.ply != ply_) EndPly(record.ply);
    if (record.course != course_) ++pass_, course_ = record.course;
    const detail::LaidLine* line = laid_->Sample(record);
    if (line == nullptr || spec_ == nullptr) return;
    last_line_ = line->source_line;
    for (std::size_t i = 1; i < line->poses.size(); ++i) {
      const process::TowCross &a = line->poses[i - 1].cross, &b = line->poses[i].cross;
      if (!a.ok || !b.ok) continue;
      for (int t = 1; t <= laid_->Layout().tows; ++t) {
        if (!detail::TowLaid(line->tows, t)) continue;
        const auto l = static_cast<std::size_t>(t) - 1, r = static_cast<std::size_t>(t);
        const Eigen::Vector2d quad[4] = {a.boundary_uv[l], a.boundary_uv[r], b.boundary_uv[r],
                                         b.boundary_uv[l]};
        Paint(quad, static_cast<std::uint32_t>(pass_ * 64 + t));
      }
    }
  }

  void Finish(const RuleContext&) override { EndPly(0); }

 private:
  void Paint(const Eigen::Vector2d (&quad)[4], std::uint32_t stamp) {
    Eigen::Vector2d lo = quad[0], hi = quad[0];
    for (const auto& q : quad) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - min_.x()) / cell_ - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - min_.y()) / cell_ - 0.5)));
    const int i1 = std::min(nu_ - 1, static_cast<int>(std::ceil((hi.x() - min_.x()) / cell_)));
    const int j1 = std::min(nv_ - 1, static_cast<int>(std::ceil((hi.y() - min_.y()) / cell_)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * nu_ + i;
        if (stamp_[k] == stamp || !InsideQuad(quad, Centre(i, j))) continue;
        stamp_[k] = stamp;
        if (count_[k] < 255) ++count_[k];
      }
    }
  }

  Eigen::Vector2d Centre(int i, int j) const {
    return min_ + cell_ * Eigen::Vector2d(i + 0.5, j + 0.5);
  }

  void StartPly(const scene::PlySpec& ply) {
    spec_ = &ply;
    min_ = max_ = ply.boundary_uv.front();
    for (const auto& p : ply.boundary_uv) min_ = min_.cwiseMin(p), max_ = max_.cwiseMax(p);
    const Eigen::Vector2d size = max_ - min_;
    cell_ = std::max(0.25 * laid_->Layout().width_mm, std::sqrt(size.prod() / kMaxCells));
    nu_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_)));
    nv_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_)));
    count_.assign(static_cast<std::size_t>(nu_) * nv_, 0);
    stamp_.assign(count_.size(), 0);
  }

  void EndPly(int next_ply) {
    if (spec_ != nullptr && last_line_ > 0) Judge();
    spec_ = nullptr;
    last_line_ = 0;
    ply_ = next_ply;
    const auto& plies = scene_->plies;
    if (next_ply >= 1 && static_cast<std::size_t>(next_ply) <= plies.size() &&
        plies[static_cast<std::size_t>(next_ply) - 1].boundary_uv.size() >= 3) {
      StartPly(plies[static_cast<std::size_t>(next_ply) - 1]);
    }
  }

  void Judge() {
    const double band = laid_->Layout().width_mm;
    double interior = 0, bare = 0, doubled = 0, outside = 0;
    for (int j = 0; j < nv_; ++j) {
      for (int i = 0; i < nu_; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * nu_ + i;
        const Eigen::Vector2d c = Centre(i, j);
        const bool in = InsidePolygon(spec_->boundary_uv, c);
        if (!in && count_[k] == 0) continue;
        const Eigen::Matrix<double, 3, 2> jac = laid_->Surface().Jacobian(c);
        const double area = jac.col(0).cross(jac.col(1)).norm() * cell_ * cell_;
        if (!in) {
          outside += area;
        } else if (DistanceToPolygon(spec_->boundary_uv, c) > band) {
          interior += area;
          bare += count_[k] == 0 ? area : 0.0;
          doubled += count_[k] >= 2 ? area : 0.0;
        }
      }
    }
    if (interior <= 0) return;
    const double bare_pct = bare / interior * 100, doubled_pct = doubled / interior * 100;
    ObserveSubject(0, bare_pct, last_line_, 0);
    ObserveSubject(1, doubled_pct, last_line_, 0);
    char buf[240];
    std::snprintf(buf, sizeof(buf),
                  "ply %s: %.4g %% bare, %.4g %% doubled beyond the boundary band; %.4g mm^2 laid "
                  "outside its boundary; bare",
                  spec_->name.c_str(), bare_pct, doubled_pct, outside);
    CheckUpper(
        bare_pct, last_line_, 0, "bare", [&] { return std::string(buf); }, nullptr);
    if (doubled_pct > doubled_limit_) {
      std::string message = buf;
      message.replace(message.rfind("bare"), 4, "");
      Record(FindingSeverity::kError, doubled_pct, doubled_limit_, last_line_, 0, "doubled",
             message + "doubled area exceeds its limit", nullptr);
    }
  }

  const scene::Scene* scene_;
  std::shared_ptr<detail::LaidTows> laid_;
  double doubled_limit_ = 0.0;
  int ply_ = 0, course_ = 0, pass_ = 0, last_line_ = 0;
  const scene::PlySpec* spec_ = nullptr;  ///< the ply being laid, if the scene has it
  Eigen::Vector2d min_ = Eigen::Vector2d::Zero(), max_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  int nu_ = 0, nv_ = 0;
  std::vector<std::uint8_t> count_;   ///< per cell: passes that painted it (saturating)
  std::vector<std::uint32_t> stamp_;  ///< per cell: the last pass (course, tow) that painted it
};

}  // namespace

std::unique_ptr<Rule> MakeAfpCoverageRule(const RuleContext& ctx,
                                          std::shared_ptr<detail::LaidTows> laid) {
  return std::make_unique<CoverageRule>(ctx, std::move(laid));
}

}  // namespace stitchsim::verify
