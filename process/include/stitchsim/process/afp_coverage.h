#pragma once
// How much of a ply an AFP programme covers (docs/afp.md, "Coverage"): a grid over a (u, v)
// box of the surface, each laid tow quad painted into the course being laid, the course added
// to the per-cell counts when it ends (tows of one course never overlap each other), then per
// ply polygon the area bare inside, doubled inside and laid outside, with and without the band
// of one tow width along the boundary where the ply's coverage policy governs. Shared by the
// afp.coverage rule and the AFP snapshot. Areas in mm^2 (cells weighted by |Su x Sv|).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/process/afp_tows.h"

namespace stitchsim::process {

/// The grid's geometry: cell (iu, iv) spans origin + [iu, iu + 1) x [iv, iv + 1) cells.
struct CoverageGrid {
  Eigen::Vector2d origin_uv = Eigen::Vector2d::Zero();  ///< lower corner of cell (0, 0)
  Eigen::Vector2d cell_uv = Eigen::Vector2d::Ones();    ///< cell size along u and v
  int nu = 0, nv = 0;
  bool coarsened = false;  ///< the asked cell size would exceed the cell budget
};

/// A grid over [lo_uv, hi_uv] with square cells of at most `max_cell` (u, v units), coarsened
/// (`coarsened` set) to stay within `max_cells`.
CoverageGrid GridOver(const Eigen::Vector2d& lo_uv, const Eigen::Vector2d& hi_uv, double max_cell,
                      std::size_t max_cells);

/// The cells of `grid` whose centre lies in the quad (corners in order around it, either
/// winding; even-odd test), row-major indices iv * nu + iu, into `cells` (cleared first).
void CellsInQuad(const CoverageGrid& grid, const std::array<Eigen::Vector2d, 4>& quad_uv,
                 std::vector<std::size_t>& cells);

/// About 6 bytes a cell (7 while measuring): 7 M cells stay under 50 MB.
inline constexpr std::size_t kCoverageMaxCells = 7'000'000;

class CoverageMap {
 public:
  /// A grid over [lo_uv, hi_uv] with cells of at most `max_cell` (u, v units) each way,
  /// coarsened (Grid().coarsened) to stay within `max_cells`. `surface` must outlive the map.
  CoverageMap(const geom::Surface& surface, const Eigen::Vector2d& lo_uv,
              const Eigen::Vector2d& hi_uv, double max_cell,
              std::size_t max_cells = kCoverageMaxCells);

  const CoverageGrid& Grid() const { return grid_; }
  /// Paints the cells whose centre lies in the quad (corners in order around it) into the
  /// current course, remembering `source_line` as the line that laid them.
  void PaintQuad(const std::array<Eigen::Vector2d, 4>& quad_uv, int source_line);
  /// Adds the current course to the counts and starts an empty one.
  void EndCourse();

  /// Courses that covered cell (iu, iv) (ended courses only; saturates at 255).
  int Count(int iu, int iv) const { return counts_[Index(iu, iv)]; }
  /// The last line that painted cell (iu, iv), 0 if none.
  int LineAt(int iu, int iv) const { return lines_[Index(iu, iv)]; }
  Eigen::Vector2d CellCentre(int iu, int iv) const;
  /// Surface area of cell (iu, iv), mm^2 (|Su x Sv| at its centre times its (u, v) area).
  double CellArea(int iu, int iv) const;
  /// The line that painted the covered cell nearest `uv` (in (u, v)), 0 if nothing is covered.
  int NearestLine(const Eigen::Vector2d& uv) const;

 private:
  std::size_t Index(int iu, int iv) const {
    return static_cast<std::size_t>(iv) * static_cast<std::size_t>(grid_.nu) +
           static_cast<std::size_t>(iu);
  }

  const geom::Surface* surface_;
  CoverageGrid grid_;
  std::vector<std::uint8_t> counts_;
  std::vector<std::uint8_t> in_course_;
  std::vector<std::int32_t> lines_;
  std::vector<std::uint32_t> course_cells_;  ///< cells painted by the current course
  std::vector<std::size_t> quad_cells_;      ///< PaintQuad's scratch
};

/// One ply's coverage, mm^2. "Beyond band": more than `band` (u, v units) from the boundary.
struct PlyCoverage {
  double ply_area_mm2 = 0.0;                                          ///< inside the boundary
  double ply_area_beyond_band_mm2 = 0.0;                              ///< inside, beyond the band
  double bare_mm2 = 0.0, bare_beyond_band_mm2 = 0.0;                  ///< inside, count 0
  double doubled_mm2 = 0.0, doubled_beyond_band_mm2 = 0.0;            ///< inside, count >= 2
  double laid_outside_mm2 = 0.0, laid_outside_beyond_band_mm2 = 0.0;  ///< outside, count >= 1
  /// Centre of the band-wide block holding the most bare (doubled) area beyond the band;
  /// meaningful when that area is > 0.
  Eigen::Vector2d worst_bare_uv = Eigen::Vector2d::Zero();
  Eigen::Vector2d worst_doubled_uv = Eigen::Vector2d::Zero();
};

/// Measures `map` against the closed polygon `boundary_uv` with a band of `band` along it.
PlyCoverage MeasurePly(const CoverageMap& map, const std::vector<Eigen::Vector2d>& boundary_uv,
                       double band);

/// The map a ply is measured on (the afp.coverage rule, and the ply planner's check of its own
/// plan): the ply's (u, v) box widened by the head's width and a tow on every side, so that
/// material laid just outside is counted; cells of a quarter tow width.
std::unique_ptr<CoverageMap> MapForPly(const geom::Surface& surface,
                                       const std::vector<Eigen::Vector2d>& boundary_uv,
                                       const TowLayout& head);

/// A ply's figures as afp.coverage judges them: percent of the ply's area beyond the band of
/// one tow width along its boundary.
struct PlyCoveragePct {
  double bare = 0.0;
  double doubled = 0.0;
  double laid_outside = 0.0;
};
PlyCoveragePct CoveragePercent(const PlyCoverage& coverage);

/// Per cell of `map`'s grid, the cell's relation to the polygon: 0 outside, 1 inside in the
/// band, 2 inside beyond the band, 3 outside in the band (row-major, iv * nu + iu).
std::vector<std::uint8_t> ClassifyCells(const CoverageGrid& grid,
                                        const std::vector<Eigen::Vector2d>& boundary_uv,
                                        double band);

}  // namespace stitchsim::process
