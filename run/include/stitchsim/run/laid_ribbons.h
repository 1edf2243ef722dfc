#pragma once
// The laid material of an AFP programme as ribbons on the part for the overview snapshot
// (snapshot_folder.cpp; public for its tests): flat ribbons (render::Overlay::normals) through the
// laid tows, coloured by ply, thinned to a budget of segments.

#include <cstddef>
#include <vector>

#include "stitchsim/render/text.h"
#include "stitchsim/run/scene_render.h"
#include "stitchsim/verify/afp_laid_material.h"

namespace stitchsim::run {

/// The ribbons and what the legend says of them.
struct LaidRibbons {
  std::vector<RenderRequest::PointSet> sets;  ///< one per line and tow group; label afp_ply_<n>
  /// One per ply drawn, the top first (at most kMaxPlyEntries, then "..."); then a line
  /// naming the plies not drawn, if any.
  std::vector<render::LegendEntry> legend;
  /// The lowest plies (M70 P, stack order), under the ones drawn, left out for the budget.
  std::vector<int> hidden_plies;
  int tows_per_ribbon = 1;   ///< head tows one ribbon stands for
  int station_step = 1;      ///< every this many stations of a line drawn
  std::size_t segments = 0;  ///< flat boxes drawn
};

inline constexpr std::size_t kMaxPlyEntries = 8;
/// Ribbons this far above `base_mm` (the preform slab's top the scene model draws; mm) and
/// each later ply this much higher, so the part's facets do not hide them.
inline constexpr double kRibbonLiftMm = 0.5;
inline constexpr double kRibbonPlyStepMm = 0.2;

/// Ribbons for `laid`: each line's laid tows merged `tows_per_ribbon` at a time (1, 2, 4, ..:
/// the fewest that keep the segments within `budget`; a group as wide as its first to last
/// laid tow); when one ribbon per line still passes it, the lowest plies left out (the top
/// one always drawn), then every `station_step`-th station (the line's ends kept).
LaidRibbons MakeLaidRibbons(const verify::LaidMaterial& laid, std::size_t budget,
                            double base_mm = 0.0);

/// A ply's ribbon colour (RGBA in [0, 1]); 12 colours, repeated.
std::array<float, 4> PlyColour(int ply);

}  // namespace stitchsim::run
