#pragma once
// Private to verify: the laminate maps' data (stitchsim/verify/afp_laminate_maps.h) as the
// afp.* rules keep it, and how the maps are found among a verifier's rules.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "stitchsim/process/afp_coverage.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify::detail {

class ThicknessBelow;

/// A value per cell of a (u, v) grid, the largest painted there; NaN where nothing was.
struct WorstValueGrid {
  process::CoverageGrid grid;
  /// Row-major iv * nu + iu; empty until the first PaintMax (memory only when used).
  std::vector<float> values;
  std::vector<std::size_t> scratch;

  explicit WorstValueGrid(const process::CoverageGrid& g) : grid(g) {}
  /// Keeps `value` in the cells whose centre lies in the quad where it is larger.
  void PaintMax(const std::array<Eigen::Vector2d, 4>& quad_uv, double value) {
    if (values.empty()) {
      values.assign(static_cast<std::size_t>(grid.nu) * static_cast<std::size_t>(grid.nv),
                    std::numeric_limits<float>::quiet_NaN());
    }
    process::CellsInQuad(grid, quad_uv, scratch);
    for (const std::size_t c : scratch) {
      const auto v = static_cast<float>(value);
      if (!(values[c] >= v)) values[c] = v;  // NaN: nothing yet
    }
  }
};

/// afp.compaction's thickness map, or nullptr when `rule` is another rule.
const ThicknessBelow* ThicknessOf(const Rule& rule);
/// afp.fiber_angle's map of the worst deviation per cell (deg), or nullptr when `rule` is
/// another rule.
const WorstValueGrid* FiberAngleGridOf(const Rule& rule);

}  // namespace stitchsim::verify::detail
