// afp.compaction: how the compaction roller stands on the surface at every laying pose: the
// tool point on the laid surface (its distance along the normal from its foot, less the
// thickness the programme's earlier plies laid within a tow width of the foot
// (afp_thickness.h): above the thickest = lift, below the thinnest = press, either =
// standoff), the roller axis (tool x) in the tangent plane (roll) and the head axis leaning
// along the travel (tool y out of the tangent plane: seed 003's inclined pressure). Each of
// the five is a subject with its own limit (standoff's a fraction of the laying ply's
// thickness, at the programmed points: lift and press are the roller's compliance along the
// whole path, standoff says whether the path follows the plies below at all); the rule's figures
// are percent of the limit, the findings give the value itself. A pose whose tows leave the surface
// is an error.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "afp_thickness.h"
#include "afp_value_grid.h"
#include "detail/rule_registry.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

using scene::LimitKey;

struct Measure {
  const char* subject;
  const char* unit;
  const char* what;
  LimitKey key;
};

constexpr std::array<Measure, 5> kMeasures = {{
    {"lift", "mm", "tool point above the laid surface by", LimitKey::kAfpCompactionMaxLiftMm},
    {"press", "mm", "tool point below the laid surface by", LimitKey::kAfpCompactionMaxPressMm},
    {"roll", "deg", "roller axis out of the tangent plane by", LimitKey::kAfpCompactionMaxRollDeg},
    {"lean", "deg", "head axis leaning along the travel by", LimitKey::kAfpCompactionMaxLeanDeg},
    // Its limit is a fraction of the laying ply's thickness (applied as mm per line).
    {"standoff", "mm", "tool point off the laid surface by",
     LimitKey::kAfpCompactionMaxStandoffFraction},
}};
constexpr std::size_t kStandoff = 4;

// "1-16", "3", "1-4, 6-16": the set bits of `mask` as runs of 1-based tow numbers.
std::string TowSpan(std::uint64_t mask) {
  std::string out;
  for (int t = 1; t <= 64; ++t) {
    if (!detail::TowLaid(mask, t)) continue;
    int last = t;
    while (last < 64 && detail::TowLaid(mask, last + 1)) ++last;
    if (!out.empty()) out += ", ";
    out += std::to_string(t);
    if (last > t) out += "-" + std::to_string(last);
    t = last;
  }
  return out;
}

class CompactionRule final : public Rule {
 public:
  CompactionRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.compaction",
             "compaction roller on the surface while laying: tool point lift and press along "
             "the normal, roller axis roll, head lean along the travel, tool point standoff from "
             "the laid surface (percent of each limit)",
             "%"),
        laid_(std::move(laid)),
        below_(laid_->Surface(), ctx.scene->plies, laid_->Layout()) {
    summary_.error_limit = 100.0;
    mergeable_ = false;  // judged over whole plies (Rule::Mergeable)
    for (std::size_t i = 0; i < kMeasures.size(); ++i) {
      limits_[i] = ctx.scene->limits.Value(kMeasures[i].key);
      AddSubject(kMeasures[i].subject, 100.0, std::nullopt);
    }
  }

  void OnLine(const trace::LineRecord& record) override {
    const detail::LaidLine* line = laid_->Sample(record);
    if (line == nullptr) return;
    below_.Lay(*line);  // commits the plies before this line's: Around() reads what lies below
    bool off_reported = false;
    for (const detail::LaidPose& pose : line->poses) {
      if (!pose.cross.ok) {
        if (!off_reported) {
          Record(FindingSeverity::kError, 0.0, 0.0, line->source_line, 0, "surface",
                 "the roller's tows leave the surface (or its domain) on this line", nullptr);
        }
        off_reported = true;
        continue;
      }
      laid_points_.Add(pose.cross.centre);
      laid_points_.Add(pose.cross.boundary.front());
      laid_points_.Add(pose.cross.boundary.back());
      const Eigen::Vector3d n = laid_->Surface().Normal(pose.cross.centre_uv);
      // The laid surface: the tool surface raised along the normal by the thickness below,
      // read within one tow width of the foot (a roller bridges a step narrower than a tow:
      // lift over the thickest, press under the thinnest, standoff outside both).
      const double d = (pose.tool.translation() - pose.cross.centre).dot(n);
      const detail::StackRange h = below_.Around(pose.cross.centre_uv, laid_->Layout().width_mm);
      const std::array<double, kMeasures.size()> values = {
          std::max(0.0, d - h.max_mm), std::max(0.0, h.min_mm - d),
          std::asin(std::min(1.0, std::abs(pose.tool.linear().col(0).dot(n)))) * kRadToDeg,
          std::asin(std::min(1.0, std::abs(pose.tool.linear().col(1).dot(n)))) * kRadToDeg,
          std::max({0.0, d - h.max_mm, h.min_mm - d})};
      const double ply_mm = below_.PlyThickness(line->ply);
      const bool programmed = pose.fraction <= 0.0 || pose.fraction >= 1.0;
      for (std::size_t i = 0; i < kMeasures.size(); ++i) {
        const double limit = i == kStandoff ? limits_[i] * ply_mm : limits_[i];
        // Standoff at the programmed points only (the line's ends): between them the chord's
        // dip on a curved surface is the roller's compliance (press), not the path's standoff.
        // A ply of no thickness has none.
        if (i == kStandoff && (ply_mm <= 0.0 || !programmed)) continue;
        const double pct = limit > 0 ? values[i] / limit * 100.0 : (values[i] > 0) * 1e9;
        ObserveSubject(i, pct, line->source_line, 0);
        if (pct > 100.0 && pct > worst_pct_) KeepRoller(pose, pct, d, h.max_mm);
        CheckUpper(
            pct, line->source_line, 0, kMeasures[i].subject,
            [&] {
              char limit_text[96];
              if (i == kStandoff) {
                std::snprintf(limit_text, sizeof(limit_text), "%.4g mm: %.3g of the ply's %.4g mm",
                              limit, limits_[i], ply_mm);
              } else {
                std::snprintf(limit_text, sizeof(limit_text), "%.4g %s", limit, kMeasures[i].unit);
              }
              char buf[320];
              std::snprintf(buf, sizeof(buf),
                            "ply %d course %d (tows %s) %s %.4g %s (limit %s; %.4g to %.4g mm laid "
                            "below within a tow width):",
                            line->ply, line->course, TowSpan(line->tows).c_str(), kMeasures[i].what,
                            values[i], kMeasures[i].unit, limit_text, h.min_mm, h.max_mm);
              return std::string(buf);
            },
            nullptr, &pose.cross.centre);
      }
    }
  }

  void Finish(const RuleContext&) override { below_.Finish(); }

  void AddLaydownFigures(std::vector<LaydownFigures>& figures) const override {
    for (LaydownFigures& f : figures) {
      std::optional<detail::StackRange> range;
      if (f.ply == 0) {
        range = below_.Whole();
      } else if (const auto it = below_.PlyStacks().find(f.ply); it != below_.PlyStacks().end()) {
        range = it->second;
      }
      if (!range) continue;
      f.thickness_min_mm = range->min_mm;
      f.thickness_max_mm = range->max_mm;
    }
  }

  const detail::ThicknessBelow& Below() const { return below_; }

  // The laid courses' centre and outer edges (the compaction rule visits every laying pose);
  // the worst pose over a limit: its roller over the k + 1 tow boundaries, then its foot on
  // the laid surface under them, for its close-up.
  std::vector<DrawnPoints> Drawings() const override {
    std::vector<DrawnPoints> out = {laid_points_.Drawn("afp_laid")};
    if (!roller_.empty()) out.push_back({"close_up:afp_roller", roller_});
    return out;
  }

 private:
  // The roller at `pose` as the rule measures it: across the tows, over each tow boundary on
  // the tool surface by the tool point's height `d_mm` plus the roll's rise at that boundary;
  // its foot: the boundaries on the laid surface (raised by `laid_mm`, the thickest below).
  void KeepRoller(const detail::LaidPose& pose, double pct, double d_mm, double laid_mm) {
    worst_pct_ = pct;
    const int k = laid_->Layout().tows;
    const Eigen::Vector3d n0 = laid_->Surface().Normal(pose.cross.centre_uv);
    const double rise = pose.tool.linear().col(0).dot(n0);  // sine of the signed roll
    const double slope = rise / std::sqrt(std::max(1e-12, 1.0 - rise * rise));
    roller_.resize(2 * static_cast<std::size_t>(k + 1));
    for (int j = 0; j <= k; ++j) {
      const std::size_t i = static_cast<std::size_t>(j);
      const Eigen::Vector3d n = laid_->Surface().Normal(pose.cross.boundary_uv[i]);
      const double across = (j - 0.5 * k) * laid_->Layout().width_mm;
      roller_[i] = pose.cross.boundary[i] + (d_mm + across * slope) * n;
      roller_[i + static_cast<std::size_t>(k + 1)] = pose.cross.boundary[i] + laid_mm * n;
    }
  }

  std::shared_ptr<detail::LaidTows> laid_;
  detail::ThinnedPoints laid_points_;
  std::array<double, kMeasures.size()> limits_{};
  detail::ThicknessBelow below_;
  double worst_pct_ = 0.0;               ///< the worst percent over a limit so far
  std::vector<Eigen::Vector3d> roller_;  ///< its roller, then its foot, 2 (k + 1), part mm
};

}  // namespace

const detail::ThicknessBelow* detail::ThicknessOf(const Rule& rule) {
  const auto* c = dynamic_cast<const CompactionRule*>(&rule);
  return c != nullptr ? &c->Below() : nullptr;
}

RuleEntry AfpCompactionRuleEntry() {
  return {"afp.compaction", CloseUpFamily::kAfp, detail::RunsWhenLaying,
          [](const RuleContext& ctx, detail::RuleMaking& making) -> std::unique_ptr<Rule> {
            return std::make_unique<CompactionRule>(ctx, making.Laid(ctx));
          }};
}

}  // namespace stitchsim::verify
