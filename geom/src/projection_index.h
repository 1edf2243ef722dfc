#pragma once
// Private to geom: the boxes of a surface's (u, v) grid cells, for closest-point searches that
// must be global (a closed wing's two skins lie close together near the trailing edge, and a
// descent from a start on one skin ends on that skin). Each cell's box holds its 3 x 3 samples,
// widened by twice the largest bulge of a midpoint from the straight line (or bilinear patch)
// through its corners, so the cell's piece of surface lies inside it; cells are grouped in
// blocks of 8 x 8 with a box each. Part frame, mm.

#include <Eigen/Core>
#include <vector>

#include "stitchsim/geom/surface.h"

namespace stitchsim::geom::detail {

class ProjectionIndex {
 public:
  /// Samples `s` over `cells` cells (u, v). False when a sample is not finite.
  bool Build(const Surface& s, const Eigen::Vector2i& cells);

  /// The centre (u, v) of the cell whose centre sample lies nearest `p`.
  Eigen::Vector2d NearestCentre(const Eigen::Vector3d& p) const;
  /// The cell (iu, iv) that holds `uv` (clamped to the grid).
  Eigen::Vector2i CellOf(const Eigen::Vector2d& uv) const;
  /// The centre (u, v) of cell `c`.
  Eigen::Vector2d CentreOf(const Eigen::Vector2i& c) const;

  /// A cell whose box lies nearer than a radius, and that squared distance.
  struct Near {
    Eigen::Vector2i cell;
    double box_d2 = 0.0;
  };
  /// The cells whose box lies nearer to `p` than `radius`, nearest first, into `out`.
  void CellsWithin(const Eigen::Vector3d& p, double radius, std::vector<Near>& out) const;

 private:
  struct Box {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero();
    Eigen::Vector3d hi = Eigen::Vector3d::Zero();
  };
  static double Distance2(const Box& b, const Eigen::Vector3d& p);

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d cell_ = Eigen::Vector2d::Ones();
  Eigen::Vector2i cells_ = Eigen::Vector2i::Zero();
  Eigen::Vector2i blocks_ = Eigen::Vector2i::Zero();
  std::vector<Box> cell_boxes_;           ///< iv * cells_u + iu
  std::vector<Box> block_boxes_;          ///< bv * blocks_u + bu
  std::vector<Eigen::Vector3d> centres_;  ///< each cell's centre sample
};

}  // namespace stitchsim::geom::detail
