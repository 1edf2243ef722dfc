#pragma once
// The HTML report's laid material (docs/report-format.md, "HTML report", "Laid tows"): the
// AFP strips of verify::LaidMaterial packed as base64 typed arrays for run/html/afp_view.js,
// thinned to a budget of values.

#include <cstddef>
#include <nlohmann/json.hpp>

#include "stitchsim/verify/afp_laid_material.h"

namespace stitchsim::run {

/// How the strips were thinned to fit.
struct LaidThinning {
  double tolerance_mm = 0.0;    ///< interior stations dropped within this of the straight chord
  bool outer_only = false;      ///< one ribbon per strip (its outermost laid tows' edges)
  std::size_t stride = 1;       ///< past every tolerance: every stride-th interior station kept
  bool per_tow_figures = true;  ///< steering radius, fibre angle per tow (else one a line)
  std::size_t stations_in = 0, stations_kept = 0;
  std::size_t values = 0;  ///< station floats written (fraction, tool, normal, boundaries)
};

/// The page's "laid" object, null when nothing was laid; `max_values` bounds the floats.
nlohmann::json PageLaidJson(const verify::LaidMaterial& laid, std::size_t max_values,
                            LaidThinning* thinning = nullptr);

}  // namespace stitchsim::run
