#include "stitchsim/process/afp_coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stitchsim::process {
namespace {

// True when p lies in the quad (either winding; a degenerate quad holds nothing), by the even-odd
// crossing test so a slightly non-convex quad still paints sensibly.
bool InQuad(const std::array<Eigen::Vector2d, 4>& q, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = 3; i < 4; j = i++) {
    if ((q[i].y() > p.y()) != (q[j].y() > p.y())) {
      const double x =
          q[j].x() + (p.y() - q[j].y()) * (q[i].x() - q[j].x()) / (q[i].y() - q[j].y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

}  // namespace

CoverageGrid GridOver(const Eigen::Vector2d& lo_uv, const Eigen::Vector2d& hi_uv, double max_cell,
                      std::size_t max_cells) {
  CoverageGrid grid;
  const Eigen::Vector2d size = (hi_uv - lo_uv).cwiseMax(1e-9);
  double cell = max_cell;
  const double wanted = std::ceil(size.x() / cell) * std::ceil(size.y() / cell);
  if (wanted > static_cast<double>(max_cells)) {
    cell = std::sqrt(size.x() * size.y() / static_cast<double>(max_cells)) * 1.01;
    grid.coarsened = true;
  }
  grid.origin_uv = lo_uv;
  grid.nu = std::max(1, static_cast<int>(std::ceil(size.x() / cell - 1e-9)));
  grid.nv = std::max(1, static_cast<int>(std::ceil(size.y() / cell - 1e-9)));
  grid.cell_uv = Eigen::Vector2d(cell, cell);
  return grid;
}

CoverageMap::CoverageMap(const geom::Surface& surface, const Eigen::Vector2d& lo_uv,
                         const Eigen::Vector2d& hi_uv, double max_cell, std::size_t max_cells)
    : surface_(&surface), grid_(GridOver(lo_uv, hi_uv, max_cell, max_cells)) {
  const std::size_t n = static_cast<std::size_t>(grid_.nu) * static_cast<std::size_t>(grid_.nv);
  counts_.assign(n, 0);
  in_course_.assign(n, 0);
  lines_.assign(n, 0);
}

Eigen::Vector2d CoverageMap::CellCentre(int iu, int iv) const {
  return grid_.origin_uv +
         Eigen::Vector2d((iu + 0.5) * grid_.cell_uv.x(), (iv + 0.5) * grid_.cell_uv.y());
}

double CoverageMap::CellArea(int iu, int iv) const {
  const Eigen::Matrix<double, 3, 2> j = surface_->Jacobian(CellCentre(iu, iv));
  return j.col(0).cross(j.col(1)).norm() * grid_.cell_uv.x() * grid_.cell_uv.y();
}

void CellsInQuad(const CoverageGrid& grid, const std::array<Eigen::Vector2d, 4>& quad_uv,
                 std::vector<std::size_t>& cells) {
  cells.clear();
  Eigen::Vector2d lo = quad_uv[0], hi = quad_uv[0];
  for (const auto& p : quad_uv) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d a = (lo - grid.origin_uv).cwiseQuotient(grid.cell_uv);
  const Eigen::Vector2d b = (hi - grid.origin_uv).cwiseQuotient(grid.cell_uv);
  const int iu0 = std::max(0, static_cast<int>(std::floor(a.x() - 0.5)));
  const int iv0 = std::max(0, static_cast<int>(std::floor(a.y() - 0.5)));
  const int iu1 = std::min(grid.nu - 1, static_cast<int>(std::ceil(b.x())));
  const int iv1 = std::min(grid.nv - 1, static_cast<int>(std::ceil(b.y())));
  for (int iv = iv0; iv <= iv1; ++iv) {
    for (int iu = iu0; iu <= iu1; ++iu) {
      const Eigen::Vector2d centre =
          grid.origin_uv +
          Eigen::Vector2d((iu + 0.5) * grid.cell_uv.x(), (iv + 0.5) * grid.cell_uv.y());
      if (!InQuad(quad_uv, centre)) continue;
      cells.push_back(static_cast<std::size_t>(iv) * static_cast<std::size_t>(grid.nu) +
                      static_cast<std::size_t>(iu));
    }
  }
}

void CoverageMap::PaintQuad(const std::array<Eigen::Vector2d, 4>& quad_uv, int source_line) {
  CellsInQuad(grid_, quad_uv, quad_cells_);
  for (const std::size_t k : quad_cells_) {
    lines_[k] = source_line;
    if (in_course_[k] != 0) continue;
    in_course_[k] = 1;
    course_cells_.push_back(static_cast<std::uint32_t>(k));
  }
}

void CoverageMap::EndCourse() {
  for (const std::uint32_t k : course_cells_) {
    if (counts_[k] < 255) ++counts_[k];
    in_course_[k] = 0;
  }
  course_cells_.clear();
}

int CoverageMap::NearestLine(const Eigen::Vector2d& uv) const {
  const Eigen::Vector2d c = (uv - grid_.origin_uv).cwiseQuotient(grid_.cell_uv);
  const int cu = std::clamp(static_cast<int>(c.x()), 0, grid_.nu - 1);
  const int cv = std::clamp(static_cast<int>(c.y()), 0, grid_.nv - 1);
  int best_line = 0;
  double best = std::numeric_limits<double>::infinity();
  // Rings of growing radius; a ring beyond the best distance found cannot hold a nearer cell.
  for (int r = 0; r < std::max(grid_.nu, grid_.nv); ++r) {
    if ((r - 1) * std::min(grid_.cell_uv.x(), grid_.cell_uv.y()) > best) break;
    for (int iv = std::max(0, cv - r); iv <= std::min(grid_.nv - 1, cv + r); ++iv) {
      const bool edge_row = iv == cv - r || iv == cv + r;
      for (int iu = std::max(0, cu - r); iu <= std::min(grid_.nu - 1, cu + r);
           iu += (edge_row || r == 0) ? 1 : 2 * r) {
        if (counts_[Index(iu, iv)] == 0) continue;
        const double d = (CellCentre(iu, iv) - uv).norm();
        if (d < best) best = d, best_line = lines_[Index(iu, iv)];
      }
    }
  }
  return best_line;
}

std::vector<std::uint8_t> ClassifyCells(const CoverageGrid& grid,
                                        const std::vector<Eigen::Vector2d>& boundary_uv,
                                        double band) {
  const std::size_t n = static_cast<std::size_t>(grid.nu) * static_cast<std::size_t>(grid.nv);
  std::vector<std::uint8_t> cls(n, 0);
  const std::size_t m = boundary_uv.size();
  if (m < 3) return cls;
  std::vector<double> cross;
  std::vector<std::uint8_t> in_band(static_cast<std::size_t>(grid.nu));
  for (int iv = 0; iv < grid.nv; ++iv) {
    const double v = grid.origin_uv.y() + (iv + 0.5) * grid.cell_uv.y();
    auto column = [&](double u) { return (u - grid.origin_uv.x()) / grid.cell_uv.x() - 0.5; };
    // Inside: spans between the sorted crossings of the row's centre line (even-odd).
    cross.clear();
    std::fill(in_band.begin(), in_band.end(), 0);
    for (std::size_t i = 0, j = m - 1; i < m; j = i++) {
      const Eigen::Vector2d &a = boundary_uv[j], &b = boundary_uv[i];
      if ((a.y() > v) != (b.y() > v)) {
        cross.push_back(a.x() + (v - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
      }
      // The band: the row's points within `band` of segment a-b form one interval.
      if (std::min(a.y(), b.y()) - band > v || std::max(a.y(), b.y()) + band < v) continue;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Eigen::Vector2d& e : {a, b}) {  // the two end discs
        const double dv = v - e.y();
        if (std::abs(dv) > band) continue;
        const double h = std::sqrt(band * band - dv * dv);
        lo = std::min(lo, e.x() - h), hi = std::max(hi, e.x() + h);
      }
      const Eigen::Vector2d d = b - a;
      const double len = d.norm();
      if (len > 1e-12 && std::abs(d.y()) > 1e-12) {  // the strip beside the segment
        const Eigen::Vector2d nrm(-d.y() / len, d.x() / len);
        for (double s : {-band, band}) {
          const double t = (v - a.y() - s * nrm.y()) / d.y();
          if (t >= 0.0 && t <= 1.0) {
            const double u = a.x() + s * nrm.x() + t * d.x();
            lo = std::min(lo, u), hi = std::max(hi, u);
          }
        }
      } else if (len > 1e-12 && std::abs(v - a.y()) <= band) {  // a horizontal segment
        lo = std::min(lo, std::min(a.x(), b.x())), hi = std::max(hi, std::max(a.x(), b.x()));
      }
      if (lo > hi) continue;
      const int c0 = std::max(0, static_cast<int>(std::ceil(column(lo))));
      const int c1 = std::min(grid.nu - 1, static_cast<int>(std::floor(column(hi))));
      for (int c = c0; c <= c1; ++c) in_band[static_cast<std::size_t>(c)] = 1;
    }
    std::sort(cross.begin(), cross.end());
    const std::size_t row = static_cast<std::size_t>(iv) * static_cast<std::size_t>(grid.nu);
    for (int iu = 0; iu < grid.nu; ++iu) {
      cls[row + static_cast<std::size_t>(iu)] = in_band[static_cast<std::size_t>(iu)] ? 3 : 0;
    }
    for (std::size_t k = 0; k + 1 < cross.size(); k += 2) {
      const int c0 = std::max(0, static_cast<int>(std::ceil(column(cross[k]))));
      const int c1 = std::min(grid.nu - 1, static_cast<int>(std::floor(column(cross[k + 1]))));
      for (int c = c0; c <= c1; ++c) {
        cls[row + static_cast<std::size_t>(c)] = in_band[static_cast<std::size_t>(c)] ? 1 : 2;
      }
    }
  }
  return cls;
}

PlyCoverage MeasurePly(const CoverageMap& map, const std::vector<Eigen::Vector2d>& boundary_uv,
                       double band) {
  const CoverageGrid& g = map.Grid();
  const std::vector<std::uint8_t> cls = ClassifyCells(g, boundary_uv, band);
  PlyCoverage out;
  // Blocks about one band wide: the worst patch is the block with the most bare (doubled) area.
  const int b = std::max(1, static_cast<int>(std::lround(band / g.cell_uv.x())));
  const int bu = (g.nu + b - 1) / b, bv = (g.nv + b - 1) / b;
  std::vector<double> bare(static_cast<std::size_t>(bu) * static_cast<std::size_t>(bv), 0.0);
  std::vector<double> doubled(bare.size(), 0.0);
  for (int iv = 0; iv < g.nv; ++iv) {
    for (int iu = 0; iu < g.nu; ++iu) {
      const std::uint8_t c = cls[static_cast<std::size_t>(iv) * static_cast<std::size_t>(g.nu) +
                                 static_cast<std::size_t>(iu)];
      const int count = map.Count(iu, iv);
      const bool inside = c == 1 || c == 2, beyond = c == 2 || c == 0;
      if (!inside && count == 0) continue;
      const double a = map.CellArea(iu, iv);
      if (!inside) {
        out.laid_outside_mm2 += a;
        if (beyond) out.laid_outside_beyond_band_mm2 += a;
        continue;
      }
      const std::size_t block = static_cast<std::size_t>(iv / b) * static_cast<std::size_t>(bu) +
                                static_cast<std::size_t>(iu / b);
      out.ply_area_mm2 += a;
      if (beyond) out.ply_area_beyond_band_mm2 += a;
      if (count == 0) {
        out.bare_mm2 += a;
        if (beyond) out.bare_beyond_band_mm2 += a, bare[block] += a;
      } else if (count >= 2) {
        out.doubled_mm2 += a;
        if (beyond) out.doubled_beyond_band_mm2 += a, doubled[block] += a;
      }
    }
  }
  auto centre_of = [&](const std::vector<double>& per_block) {
    const std::size_t k = static_cast<std::size_t>(
        std::max_element(per_block.begin(), per_block.end()) - per_block.begin());
    const int ku = static_cast<int>(k % static_cast<std::size_t>(bu));
    const int kv = static_cast<int>(k / static_cast<std::size_t>(bu));
    const int iu = std::min(g.nu - 1, ku * b + b / 2), iv = std::min(g.nv - 1, kv * b + b / 2);
    return map.CellCentre(iu, iv);
  };
  out.worst_bare_uv = centre_of(bare);
  out.worst_doubled_uv = centre_of(doubled);
  return out;
}

std::unique_ptr<CoverageMap> MapForPly(const geom::Surface& surface,
                                       const std::vector<Eigen::Vector2d>& boundary_uv,
                                       const TowLayout& head) {
  Eigen::Vector2d lo = boundary_uv.front(), hi = lo;
  for (const auto& p : boundary_uv) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double margin = (head.tows + 1) * head.width_mm;
  return std::make_unique<CoverageMap>(surface, lo.array() - margin, hi.array() + margin,
                                       head.width_mm / 4);
}

PlyCoveragePct CoveragePercent(const PlyCoverage& c) {
  const double area = c.ply_area_beyond_band_mm2;
  if (!(area > 0)) return {};
  return {100.0 * c.bare_beyond_band_mm2 / area, 100.0 * c.doubled_beyond_band_mm2 / area,
          100.0 * c.laid_outside_beyond_band_mm2 / area};
}

}  // namespace stitchsim::process
