// afp.coverage: how much of each ply the programme covers (process::CoverageMap). A line's
// laid tows are painted as quads between its consecutive sampled poses into the course being
// laid; the course is counted when the line's ply or course changes. Each ply the programme
// lays (M70 P<n> = the n-th ply of the scene) is measured at the end against its boundary:
// bare and doubled area beyond the band of one tow width along the boundary (where the ply's
// coverage policy governs), as percent of the ply's area beyond that band; material laid
// outside is reported as a figure. A finding names the line that laid the course nearest the
// worst bare (doubled) patch.
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "stitchsim/process/afp_coverage.h"

namespace stitchsim::verify {
namespace {

using detail::LaidLine;

// The map over a ply's boundary box, widened by one course and a tow width on every side so
// material laid just outside is counted.
std::unique_ptr<process::CoverageMap> MapFor(const geom::Surface& surface,
                                             const scene::PlySpec& ply,
                                             const process::TowLayout& layout) {
  Eigen::Vector2d lo = ply.boundary_uv.front(), hi = lo;
  for (const auto& p : ply.boundary_uv) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double margin = (layout.tows + 1) * layout.width_mm;
  return std::make_unique<process::CoverageMap>(surface, lo.array() - margin, hi.array() + margin,
                                                layout.width_mm / 4);
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
  }

  void OnLine(const trace::LineRecord& record) override {
    if (record.ply != ply_ || record.course != course_) EndCourse();
    ply_ = record.ply;
    course_ = record.course;
    const LaidLine* line = laid_->Sample(record);
    if (line == nullptr || line->ply < 1 || line->ply > static_cast<int>(plies_->size())) return;
    const scene::PlySpec& spec = (*plies_)[static_cast<std::size_t>(line->ply) - 1];
    if (spec.boundary_uv.size() < 3) return;
    Ply& ply = plies_laid_[line->ply];
    if (!ply.map)
      ply.map = MapFor(laid_->Surface(), spec, laid_->Layout()), ply.first_line = line->source_line;
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

  void Finish(const RuleContext&) override {
    EndCourse();
    for (auto& [index, ply] : plies_laid_) {
      const scene::PlySpec& spec = (*plies_)[static_cast<std::size_t>(index) - 1];
      const process::PlyCoverage cov =
          process::MeasurePly(*ply.map, spec.boundary_uv, laid_->Layout().width_mm);
      const double area = cov.ply_area_beyond_band_mm2;
      const double bare = area > 0 ? 100.0 * cov.bare_beyond_band_mm2 / area : 0.0;
      const double doubled = area > 0 ? 100.0 * cov.doubled_beyond_band_mm2 / area : 0.0;
      const double outside = area > 0 ? 100.0 * cov.laid_outside_beyond_band_mm2 / area : 0.0;
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
  };

  void EndCourse() {
    const auto it = plies_laid_.find(ply_);
    if (it != plies_laid_.end()) it->second.map->EndCourse();
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
};

}  // namespace

std::unique_ptr<Rule> MakeAfpCoverageRule(const RuleContext& ctx,
                                          std::shared_ptr<detail::LaidTows> laid) {
  return std::make_unique<CoverageRule>(ctx, std::move(laid));
}

}  // namespace stitchsim::verify
