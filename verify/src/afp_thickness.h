#pragma once
// Private to verify: the thickness an AFP programme's earlier plies laid, verify's own route
// (issue 29; docs/report-format.md, afp.compaction and "Laydown"). A grid over the surface's
// (u, v) domain (cells of at most kThicknessCellMm, coarsened past a cell budget); each laying
// line's tows paint their quads (between consecutive sampled poses, afp_laid.h) into the cover
// of the line's ply (M70 P<n>): a cell covered twice by one ply counts once. When a laying line
// of another ply comes (or the programme ends), the open ply's cover is committed: each cell
// it covers gains the ply's thickness (scene::PlySpec::thickness_mm; a ply the scene does not
// define lays no thickness). Plies are taken in programme order; a ply laid again after
// another is a new cover. Nothing here reads the planner.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "afp_laid.h"
#include "stitchsim/process/afp_coverage.h"
#include "stitchsim/scene/ply.h"

namespace stitchsim::verify::detail {

/// Largest cell of the thickness and fibre-angle grids, (u, v) mm.
inline constexpr double kThicknessCellMm = 2.0;
/// Cell budget of those grids (about 10 bytes a cell for the thickness map).
inline constexpr std::size_t kThicknessMaxCells = 4'000'000;

/// The grid the thickness and fibre-angle maps use: over the (u, v) box of the scene's plies'
/// boundaries widened by the head's width and a tow on every side (as afp.coverage's maps),
/// within the surface's domain; over the whole domain when a ply has no boundary. Material
/// laid beyond that box is not counted (afp.coverage reports it as laid outside).
process::CoverageGrid LaminateGrid(const geom::Surface& surface,
                                   const std::vector<scene::PlySpec>& plies,
                                   const process::TowLayout& head);

/// Smallest and largest stack thickness over a set of cells, mm.
struct StackRange {
  double min_mm = 0.0;
  double max_mm = 0.0;
};

class ThicknessBelow {
 public:
  /// `plies` (the scene's) and `surface` must outlive the map.
  ThicknessBelow(const geom::Surface& surface, const std::vector<scene::PlySpec>& plies,
                 const process::TowLayout& head);

  /// Adds `line`'s laid tows to the cover of its ply, committing the open ply's cover first
  /// when `line` is of another ply. Around() is not changed by the line itself.
  void Lay(const LaidLine& line);
  /// Commits the open ply (the programme's end).
  void Finish();

  /// The committed thickness over the cells within `reach_mm` of the cell holding `uv` along
  /// u and v (at least its eight neighbours), smallest and largest (mm; {0, 0} outside the
  /// domain): a foot near the edge of a ply below (a course ending where the one below ends, a
  /// tow's cut, a pad-up's step) reads both sides.
  StackRange Around(const Eigen::Vector2d& uv, double reach_mm = 0.0) const;
  /// The thickness a ply lays (mm): its PlySpec's, 0 for a ply the scene does not define.
  double PlyThickness(int ply) const;

  /// Per committed ply (M70 P<n>; the last commit of a ply laid twice): the stack over the
  /// cells it covered, just after it was committed.
  const std::map<int, StackRange>& PlyStacks() const { return ply_stacks_; }
  /// The stack over every cell any ply covered, as committed so far; nullopt if none.
  std::optional<StackRange> Whole() const;

  const process::CoverageGrid& Grid() const { return grid_; }
  /// Per cell (row-major iv * nu + iu) the committed thickness, mm (empty before the first
  /// laying line).
  const std::vector<double>& Stack() const { return stack_; }
  /// Per cell, 1 where some committed ply covered it.
  const std::vector<std::uint8_t>& Laid() const { return laid_; }

 private:
  void Commit();

  const std::vector<scene::PlySpec>* plies_;
  process::CoverageGrid grid_;
  std::vector<double> stack_;
  std::vector<std::uint8_t> laid_;
  std::vector<std::uint8_t> open_cover_;  ///< the open ply's cover
  std::vector<std::size_t> open_cells_;   ///< the cells set in open_cover_
  std::vector<std::size_t> quad_cells_;   ///< scratch
  int open_ply_ = 0;
  bool have_open_ = false;
  std::map<int, StackRange> ply_stacks_;
};

}  // namespace stitchsim::verify::detail
