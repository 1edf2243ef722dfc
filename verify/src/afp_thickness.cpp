#include "afp_thickness.h"

#include <algorithm>
#include <cmath>

namespace stitchsim::verify::detail {

process::CoverageGrid LaminateGrid(const geom::Surface& surface,
                                   const std::vector<scene::PlySpec>& plies,
                                   const process::TowLayout& head) {
  const geom::Domain2 d = surface.Domain();
  Eigen::Vector2d lo = d.max, hi = d.min;
  for (const scene::PlySpec& ply : plies) {
    if (ply.boundary_uv.size() < 3)
      return process::GridOver(d.min, d.max, kThicknessCellMm, kThicknessMaxCells);
    for (const Eigen::Vector2d& p : ply.boundary_uv) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const double margin = (head.tows + 1) * head.width_mm;
  lo = (lo.array() - margin).matrix().cwiseMax(d.min);
  hi = (hi.array() + margin).matrix().cwiseMin(d.max);
  if (plies.empty() || (hi - lo).minCoeff() <= 0.0) {
    lo = d.min;
    hi = d.max;
  }
  return process::GridOver(lo, hi, kThicknessCellMm, kThicknessMaxCells);
}

ThicknessBelow::ThicknessBelow(const geom::Surface& surface,
                               const std::vector<scene::PlySpec>& plies,
                               const process::TowLayout& head)
    : plies_(&plies), grid_(LaminateGrid(surface, plies, head)) {}

double ThicknessBelow::PlyThickness(int ply) const {
  return ply >= 1 && ply <= static_cast<int>(plies_->size())
             ? (*plies_)[static_cast<std::size_t>(ply) - 1].thickness_mm
             : 0.0;
}

void ThicknessBelow::Lay(const LaidLine& line) {
  if (stack_.empty()) {  // the first laying line: the grid's memory is taken here
    const std::size_t n = static_cast<std::size_t>(grid_.nu) * static_cast<std::size_t>(grid_.nv);
    stack_.assign(n, 0.0);
    laid_.assign(n, 0);
    open_cover_.assign(n, 0);
  }
  if (have_open_ && line.ply != open_ply_) Commit();
  have_open_ = true;
  open_ply_ = line.ply;
  for (std::size_t i = 0; i + 1 < line.poses.size(); ++i) {
    const process::TowCross &a = line.poses[i].cross, &b = line.poses[i + 1].cross;
    if (!a.ok || !b.ok) continue;
    const int tows = static_cast<int>(std::min(a.boundary_uv.size(), b.boundary_uv.size())) - 1;
    for (int t = 1; t <= tows; ++t) {
      if (!TowLaid(line.tows, t)) continue;
      const auto k = static_cast<std::size_t>(t);
      process::CellsInQuad(
          grid_, {a.boundary_uv[k - 1], a.boundary_uv[k], b.boundary_uv[k], b.boundary_uv[k - 1]},
          quad_cells_);
      for (const std::size_t c : quad_cells_) {
        if (open_cover_[c] != 0) continue;
        open_cover_[c] = 1;
        open_cells_.push_back(c);
      }
    }
  }
}

void ThicknessBelow::Commit() {
  if (!have_open_) return;
  const double t = PlyThickness(open_ply_);
  std::optional<StackRange> range;
  for (const std::size_t c : open_cells_) {
    stack_[c] += t;
    laid_[c] = 1;
    open_cover_[c] = 0;
    const double s = stack_[c];
    if (!range) range = StackRange{s, s};
    range->min_mm = std::min(range->min_mm, s);
    range->max_mm = std::max(range->max_mm, s);
  }
  if (range) ply_stacks_[open_ply_] = *range;
  open_cells_.clear();
  have_open_ = false;
}

void ThicknessBelow::Finish() { Commit(); }

StackRange ThicknessBelow::Around(const Eigen::Vector2d& uv, double reach_mm) const {
  const Eigen::Vector2d c = (uv - grid_.origin_uv).cwiseQuotient(grid_.cell_uv);
  const auto cu = static_cast<int>(std::floor(c.x())), cv = static_cast<int>(std::floor(c.y()));
  const int ru = std::max(1, static_cast<int>(std::ceil(reach_mm / grid_.cell_uv.x())));
  const int rv = std::max(1, static_cast<int>(std::ceil(reach_mm / grid_.cell_uv.y())));
  std::optional<StackRange> range;
  for (int iv = std::max(0, cv - rv); !stack_.empty() && iv <= std::min(grid_.nv - 1, cv + rv);
       ++iv) {
    for (int iu = std::max(0, cu - ru); iu <= std::min(grid_.nu - 1, cu + ru); ++iu) {
      const double s = stack_[static_cast<std::size_t>(iv) * static_cast<std::size_t>(grid_.nu) +
                              static_cast<std::size_t>(iu)];
      if (!range) range = StackRange{s, s};
      range->min_mm = std::min(range->min_mm, s);
      range->max_mm = std::max(range->max_mm, s);
    }
  }
  return range.value_or(StackRange{});
}

std::optional<StackRange> ThicknessBelow::Whole() const {
  std::optional<StackRange> range;
  for (std::size_t c = 0; c < stack_.size(); ++c) {
    if (laid_[c] == 0) continue;
    if (!range) range = StackRange{stack_[c], stack_[c]};
    range->min_mm = std::min(range->min_mm, stack_[c]);
    range->max_mm = std::max(range->max_mm, stack_[c]);
  }
  return range;
}

}  // namespace stitchsim::verify::detail
