#pragma once
// The lofted NACA wing of naca.h as a CAD surface: a cubic (around the section) by linear
// (along the span) B-spline fitted to the sections, evaluated by the OpenCASCADE kernel
// behind the Surface interface (no kernel type appears here).

#include <memory>
#include <string>

#include "stitchsim/geom/naca.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {

/// Which part of the section contour the surface covers.
enum class WingSkin {
  kFull,   ///< s in [0, 1]: upper trailing edge, around the leading edge, lower trailing edge
  kUpper,  ///< s in [0, 0.5]: upper trailing edge to the leading edge
  kLower,  ///< s in [0.5, 1]: leading edge to the lower trailing edge
};

/// The wing's B-spline surface and how closely it follows the sections.
struct WingSurface {
  std::unique_ptr<Surface> surface;  ///< Kind() "wing"
  /// Largest distance (mm) between the fitted sections and Wing::Point, measured at the
  /// midpoints between the interpolated stations of the root and tip (the loft is linear
  /// in eta, so both are exact in between).
  double fit_error_mm = 0.0;
  int stations = 0;  ///< interpolated stations per section over the whole contour s in [0, 1]
};

/// Fits `spec`'s loft to better than `tolerance_mm`. (u, v) domain [0, Lu] x [0, Lv] in mm
/// (the middle iso-curves' lengths, cad_surface.h): u = Lu (s - s0) / (s1 - s0) around the
/// contour of `skin` (s0, s1 as WingSkin), v = Lv eta along the span. The normal points out
/// of the wing. nullptr in `surface` with `error` set for a bad spec (Wing::Make) or a fit
/// that misses the tolerance.
WingSurface MakeWingSurface(const WingSpec& spec, WingSkin skin, std::string& error,
                            double tolerance_mm = 0.005);

/// The section parameter range [s0, s1] of `skin`.
Eigen::Vector2d WingSkinRange(WingSkin skin);

}  // namespace stitchsim::geom
