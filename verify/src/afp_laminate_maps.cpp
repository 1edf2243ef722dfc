#include "stitchsim/verify/afp_laminate_maps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "afp_thickness.h"
#include "afp_value_grid.h"

namespace stitchsim::verify {
namespace {

// The picture of per-cell `cells` (NaN: none) on `grid`: cropped to the cells with a value,
// each pixel the largest of a block of cells, at most `max_side` pixels a side.
LaminateMap MapOfCells(const process::CoverageGrid& grid, const std::vector<float>& cells,
                       int max_side) {
  LaminateMap map;
  map.coarsened = grid.coarsened;
  if (cells.empty()) return map;
  int u0 = grid.nu, v0 = grid.nv, u1 = -1, v1 = -1;
  for (int iv = 0; iv < grid.nv; ++iv) {
    for (int iu = 0; iu < grid.nu; ++iu) {
      if (std::isnan(cells[static_cast<std::size_t>(iv) * static_cast<std::size_t>(grid.nu) +
                           static_cast<std::size_t>(iu)])) {
        continue;
      }
      u0 = std::min(u0, iu), v0 = std::min(v0, iv), u1 = std::max(u1, iu), v1 = std::max(v1, iv);
    }
  }
  if (u1 < 0) return map;
  const int nu = u1 - u0 + 1, nv = v1 - v0 + 1;
  const int block = std::max(1, (std::max(nu, nv) + max_side - 1) / std::max(1, max_side));
  map.width = (nu + block - 1) / block;
  map.height = (nv + block - 1) / block;
  map.lo_uv = grid.origin_uv + Eigen::Vector2d(u0 * grid.cell_uv.x(), v0 * grid.cell_uv.y());
  map.hi_uv = map.lo_uv + Eigen::Vector2d(map.width * block * grid.cell_uv.x(),
                                          map.height * block * grid.cell_uv.y());
  map.values.assign(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height),
                    std::numeric_limits<float>::quiet_NaN());
  bool first = true;
  for (int iv = v0; iv <= v1; ++iv) {
    for (int iu = u0; iu <= u1; ++iu) {
      const float c = cells[static_cast<std::size_t>(iv) * static_cast<std::size_t>(grid.nu) +
                            static_cast<std::size_t>(iu)];
      if (std::isnan(c)) continue;
      float& px = map.values[static_cast<std::size_t>(map.height - 1 - (iv - v0) / block) *
                                 static_cast<std::size_t>(map.width) +
                             static_cast<std::size_t>((iu - u0) / block)];
      if (!(px >= c)) px = c;
      map.min_value = first ? c : std::min(map.min_value, static_cast<double>(c));
      map.max_value = first ? c : std::max(map.max_value, static_cast<double>(c));
      first = false;
    }
  }
  return map;
}

}  // namespace

std::vector<LaminateMap> LaminateMaps(const Verifier& verifier, int max_side) {
  std::vector<LaminateMap> out;
  for (const auto& rule : verifier.Rules()) {
    if (const detail::ThicknessBelow* below = detail::ThicknessOf(*rule)) {
      std::vector<float> cells(below->Stack().size(), std::numeric_limits<float>::quiet_NaN());
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (below->Laid()[c] != 0) cells[c] = static_cast<float>(below->Stack()[c]);
      }
      LaminateMap map = MapOfCells(below->Grid(), cells, max_side);
      map.name = "thickness";
      map.title = "laminate thickness laid";
      map.unit = "mm";
      if (map.width > 0) out.push_back(std::move(map));
    }
    if (const detail::WorstValueGrid* angles = detail::FiberAngleGridOf(*rule)) {
      LaminateMap map = MapOfCells(angles->grid, angles->values, max_side);
      map.name = "fiber_angle";
      map.title = "worst fibre-angle deviation over the plies";
      map.unit = "deg";
      if (map.width > 0) out.push_back(std::move(map));
    }
  }
  return out;
}

}  // namespace stitchsim::verify
