// afp.coverage: how much of each ply the programme covers (process::CoverageMap). A line's
// laid tows are painted as quads between its consecutive sampled poses into the course being
// laid; the course is counted when the line's ply or course changes. Each ply the programme
// lays (M70 P<n> = the n-th ply of the scene) is measured at the end against its boundary:
// bare and doubled area beyond the band of one tow width along the boundary (where the ply's
// coverage policy governs), as percent of the ply's area beyond that band; material laid
// outside is reported as a figure. A finding names the line that laid the course nearest the
// worst bare (doubled) patch. A ply the scene does not define (M70 P<n> past the scene's plies:
// `plan afp` lays its course as one) has no boundary: its laid area is a figure and what it
// lays twice is judged.
#include <algorithm>
#include <bit>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "detail/rule_registry.h"
#include "stitchsim/process/afp_coverage.h"
#include "stitchsim/verify/afp_coverage_image.h"

namespace stitchsim::verify {
namespace {

using detail::LaidLine;

// The map over the whole surface, for a ply the scene does not define (no boundary box).
std::unique_ptr<process::CoverageMap> MapOverDomain(const geom::Surface& surface,
                                                    const process::TowLayout& layout) {
  const geom::Domain2 d = surface.Domain();
  return std::make_unique<process::CoverageMap>(surface, d.min, d.max, layout.width_mm / 4);
}

// Halves `img` (each pixel the worst of four) until its longer side fits `max_side`.
void Shrink(CoverageImage& img, int max_side) {
  constexpr int kRank[] = {0, 1, 4, 5, 2, 3};
  while (std::max(img.width, img.height) > std::max(1, max_side)) {
    const int w = (img.width + 1) / 2, h = (img.height + 1) / 2;
    std::vector<CoverageState> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
                                  CoverageState::kNone);
    for (int y = 0; y < img.height; ++y) {
      for (int x = 0; x < img.width; ++x) {
        const CoverageState s = img.pixels[static_cast<std::size_t>(y * img.width + x)];
        CoverageState& d = px[static_cast<std::size_t>((y / 2) * w + x / 2)];
        if (kRank[static_cast<int>(s)] > kRank[static_cast<int>(d)]) d = s;
      }
    }
    img.pixels = std::move(px);
    img.width = w;
    img.height = h;
  }
}

class CoverageRule final : public Rule {
 public:
  CoverageRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.coverage",
             "area of each ply left bare (worst) or covered twice, beyond the band of one tow "
             "width along its boundary, percent of that area",
             "%"),
        plies_(&ctx.scene->plies),
        laid_(std::move(laid)),
        max_bare_(ctx.scene->limits.Value(scene::LimitKey::kAfpCoverageMaxBarePct)),
        max_doubled_(ctx.scene->limits.Value(scene::LimitKey::kAfpCoverageMaxDoubledPct)) {
    summary_.error_limit = max_bare_;
    mergeable_ = false;  // judged over whole plies (Rule::Mergeable)
  }

  void OnLine(const trace::LineRecord& record) override {
    if (record.ply != ply_ || record.course != course_) EndCourse();
    ply_ = record.ply;
    course_ = record.course;
    const LaidLine* line = laid_->Sample(record);
    if (line == nullptr || line->ply < 1) return;
    const scene::PlySpec* spec = SpecOf(line->ply);
    if (spec != nullptr && spec->boundary_uv.size() < 3) return;
    Ply& ply = plies_laid_[line->ply];
    if (!ply.map) {
      ply.map = spec != nullptr
                    ? process::MapForPly(laid_->Surface(), spec->boundary_uv, laid_->Layout())
                    : MapOverDomain(laid_->Surface(), laid_->Layout());
      ply.first_line = line->source_line;
    }
    ply.nominal_mm2 += (record.to.translation() - record.from.translation()).norm() *
                       std::popcount(line->tows) * laid_->Layout().width_mm;
    for (std::size_t i = 0; i + 1 < line->poses.size(); ++i) {
      const process::TowCross &a = line->poses[i].cross, &b = line->poses[i + 1].cross;
      if (!a.ok || !b.ok) continue;
      for (int t = 1; t <= laid_->Layout().tows; ++t) {
        if (!detail::TowLaid(line->tows, t)) continue;
        const auto k = static_cast<std::size_t>(t);
        ply.map->PaintQuad(
            {a.boundary_uv[k - 1], a.boundary_uv[k], b.boundary_uv[k], b.boundary_uv[k - 1]},
            line->source_line);
      }
    }
  }

  /// The plies' pictures, made at Finish (at most kImageSide pixels a side).
  const std::vector<CoverageImage>& Images() const { return images_; }
  static constexpr int kImageSide = 1600;

  void Finish(const RuleContext&) override {
    EndCourse();
    for (auto& [index, ply] : plies_laid_) {
      if (SpecOf(index) == nullptr) {
        FinishUndefinedPly(index, ply);
        continue;
      }
      const scene::PlySpec& spec = *SpecOf(index);
      const process::PlyCoverage cov =
          process::MeasurePly(*ply.map, spec.boundary_uv, laid_->Layout().width_mm);
      const auto [bare, doubled, outside] = process::CoveragePercent(cov);
      images_.push_back(ImageOf(*ply.map, spec, index));
      const int bare_line = LineNear(ply, cov.worst_bare_uv);
      const int doubled_line = LineNear(ply, cov.worst_doubled_uv);
      Counted();
      if (!summary_.worst_value || bare > *summary_.worst_value) {
        summary_.worst_value = bare;
        summary_.worst_line = bare_line;
      }
      const std::string name = spec.name.empty() ? "ply " + std::to_string(index) : spec.name;
      Figure(name + " bare", max_bare_, bare, bare_line);
      Figure(name + " doubled", max_doubled_, doubled, doubled_line);
      Figure(name + " laid outside", std::nullopt, outside, ply.first_line);
      if (bare > max_bare_) Fire(name, "bare", bare, max_bare_, bare_line, ply, cov);
      if (doubled > max_doubled_)
        Fire(name, "doubled", doubled, max_doubled_, doubled_line, ply, cov);
    }
  }

 private:
  struct Ply {
    std::unique_ptr<process::CoverageMap> map;
    int first_line = 0;
    /// Sum over laying lines of move length x laid tows x w, mm^2: what the tow masks say.
    double nominal_mm2 = 0.0;
  };

  // The scene's ply `index` (M70 P<index>), or nullptr for a ply the scene does not define
  // (`plan afp` lays its course as one).
  const scene::PlySpec* SpecOf(int index) const {
    return index >= 1 && index <= static_cast<int>(plies_->size())
               ? &(*plies_)[static_cast<std::size_t>(index) - 1]
               : nullptr;
  }

  // A ply without a boundary has no bare area: what it lays is measured (a figure: percent of
  // its moves' length x laid tows x w, 100 on a plane) and judged for material laid twice, as
  // percent of the laid area.
  void FinishUndefinedPly(int index, const Ply& ply) {
    const process::CoverageGrid& g = ply.map->Grid();
    double laid = 0.0, doubled = 0.0;
    Eigen::Vector2d worst_uv = Eigen::Vector2d::Zero();
    for (int iv = 0; iv < g.nv; ++iv) {
      for (int iu = 0; iu < g.nu; ++iu) {
        const int count = ply.map->Count(iu, iv);
        if (count == 0) continue;
        const double area = ply.map->CellArea(iu, iv);
        laid += area;
        if (count < 2) continue;
        doubled += area;
        worst_uv = ply.map->CellCentre(iu, iv);
      }
    }
    const double pct = laid > 0 ? 100.0 * doubled / laid : 0.0;
    const int line = doubled > 0 ? LineNear(ply, worst_uv) : ply.first_line;
    const std::string name = "ply " + std::to_string(index);  // not one of the scene's plies
    Counted();
    const double laid_pct = ply.nominal_mm2 > 0 ? 100.0 * laid / ply.nominal_mm2 : 0.0;
    Figure(name + " laid (of nominal)", std::nullopt, laid_pct, ply.first_line);
    Figure(name + " doubled", max_doubled_, pct, line);
    if (pct <= max_doubled_) return;
    char buf[300];
    std::snprintf(buf, sizeof(buf),
                  "%.3g %% of what %s lays is laid twice (limit %.3g %%), e.g. near (u, v) = "
                  "(%.1f, %.1f) mm, by the course this line lays",
                  pct, name.c_str(), max_doubled_, worst_uv.x(), worst_uv.y());
    Record(FindingSeverity::kError, pct, max_doubled_, line, 0, name + " doubled", buf, nullptr);
  }

  void EndCourse() {
    const auto it = plies_laid_.find(ply_);
    if (it != plies_laid_.end()) it->second.map->EndCourse();
  }

  // The ply's picture: each pixel a block of cells showing its worst state.
  CoverageImage ImageOf(const process::CoverageMap& map, const scene::PlySpec& spec,
                        int index) const {
    const process::CoverageGrid& g = map.Grid();
    const std::vector<std::uint8_t> cls =
        process::ClassifyCells(g, spec.boundary_uv, laid_->Layout().width_mm);
    const int block = std::max(1, (std::max(g.nu, g.nv) + kImageSide - 1) / kImageSide);
    CoverageImage img;
    img.ply = index;
    img.name = spec.name;
    img.width = (g.nu + block - 1) / block;
    img.height = (g.nv + block - 1) / block;
    img.lo_uv = g.origin_uv;
    img.hi_uv = g.origin_uv + Eigen::Vector2d(g.nu * g.cell_uv.x(), g.nv * g.cell_uv.y());
    img.pixels.assign(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height),
                      CoverageState::kNone);
    auto rank = [](CoverageState s) {
      constexpr int kRank[] = {0, 1, 4, 5, 2, 3};  // doubled > bare > band bare > outside > laid
      return kRank[static_cast<int>(s)];
    };
    for (int iv = 0; iv < g.nv; ++iv) {
      for (int iu = 0; iu < g.nu; ++iu) {
        const std::uint8_t c = cls[static_cast<std::size_t>(iv) * static_cast<std::size_t>(g.nu) +
                                   static_cast<std::size_t>(iu)];
        const int count = map.Count(iu, iv);
        const bool inside = c == 1 || c == 2;
        CoverageState s = CoverageState::kNone;
        if (inside && count == 0) s = c == 2 ? CoverageState::kBare : CoverageState::kBoundaryBare;
        if (inside && count == 1) s = CoverageState::kLaid;
        if (inside && count >= 2) s = CoverageState::kDoubled;
        if (!inside && count >= 1) s = CoverageState::kOutside;
        CoverageState& px = img.pixels[static_cast<std::size_t>(img.height - 1 - iv / block) *
                                           static_cast<std::size_t>(img.width) +
                                       static_cast<std::size_t>(iu / block)];
        if (rank(s) > rank(px)) px = s;
      }
    }
    return img;
  }

  static int LineNear(const Ply& ply, const Eigen::Vector2d& uv) {
    const int line = ply.map->NearestLine(uv);
    return line > 0 ? line : ply.first_line;
  }

  void Figure(const std::string& subject, std::optional<double> limit, double value, int line) {
    const std::size_t i = AddSubject(subject, limit, std::nullopt);
    SubjectFigure& f = summary_.subjects[i];
    f.checked = 1;
    f.worst_value = value;
    f.worst_line = line;
  }

  void Fire(const std::string& name, const char* what, double value, double limit, int line,
            const Ply& ply, const process::PlyCoverage& cov) {
    const Eigen::Vector2d uv = what[0] == 'b' ? cov.worst_bare_uv : cov.worst_doubled_uv;
    char buf[300];
    std::snprintf(buf, sizeof(buf),
                  "%.3g %% of ply %s is %s beyond the boundary band (limit %.3g %%); the worst "
                  "patch is near (u, v) = (%.1f, %.1f) mm, by the course this line lays%s",
                  value, name.c_str(), what, limit, uv.x(), uv.y(),
                  ply.map->Grid().coarsened ? " (coverage grid coarsened)" : "");
    Record(FindingSeverity::kError, value, limit, line, 0, name + " " + what, buf, nullptr);
  }

  const std::vector<scene::PlySpec>* plies_;
  std::shared_ptr<detail::LaidTows> laid_;
  double max_bare_, max_doubled_;
  std::map<int, Ply> plies_laid_;  ///< by ply number (M70 P<n>), the plies the programme lays
  int ply_ = 0, course_ = 0;       ///< the course being laid
  std::vector<CoverageImage> images_;
};

}  // namespace

std::vector<CoverageImage> CoverageImages(const Verifier& verifier, int max_side) {
  for (const auto& rule : verifier.Rules()) {
    if (const auto* c = dynamic_cast<const CoverageRule*>(rule.get())) {
      std::vector<CoverageImage> out = c->Images();
      for (CoverageImage& img : out) Shrink(img, max_side);
      return out;
    }
  }
  return {};
}

// Its picture is the coverage map (afp_coverage_image.h), not a close-up.
RuleEntry AfpCoverageRuleEntry() {
  return {"afp.coverage", CloseUpFamily::kNone, detail::RunsWhenLaying,
          [](const RuleContext& ctx, detail::RuleMaking& making) -> std::unique_ptr<Rule> {
            return std::make_unique<CoverageRule>(ctx, making.Laid(ctx));
          }};
}

}  // namespace stitchsim::verify
