#pragma once
// The laminate's maps (issue 29; docs/report-format.md, "AFP laminate snapshots"): over the
// surface's (u, v), the stack thickness the programme's plies laid (afp.compaction's map) and
// the worst fibre-angle deviation of the tows laid there (afp.fiber_angle's), for the
// `verify --snapshots` pictures. Values only: run/ draws them.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "stitchsim/verify/verifier.h"

namespace stitchsim::verify {

/// One map, cropped to the (u, v) box of the cells laid.
struct LaminateMap {
  std::string name;   ///< "thickness" or "fiber_angle" (the picture's file name)
  std::string title;  ///< what the map shows, for the picture's title
  std::string unit;   ///< "mm" or "deg"
  int width = 0, height = 0;
  /// Row-major, row 0 at the largest v (top of the picture), column 0 at the smallest u; the
  /// largest value of the cells a pixel holds; NaN where nothing was laid.
  std::vector<float> values;
  /// The (u, v) box the pixels cover, mm (lo: the bottom left corner of the picture).
  Eigen::Vector2d lo_uv = Eigen::Vector2d::Zero(), hi_uv = Eigen::Vector2d::Zero();
  double min_value = 0.0, max_value = 0.0;  ///< over the pixels with a value
  bool coarsened = false;                   ///< the grid's cells are larger than 2 mm (cell budget)
};

/// The thickness map and the fibre-angle map of a finished verifier run (each absent when its
/// rule did not run or saw nothing laid), at most `max_side` pixels on the longer side.
std::vector<LaminateMap> LaminateMaps(const Verifier& verifier, int max_side = 900);

}  // namespace stitchsim::verify
