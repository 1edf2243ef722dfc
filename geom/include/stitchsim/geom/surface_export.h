#pragma once
// Any surface as one B-spline patch, for export to STEP / IGES (WriteBSplineCad). CAD
// surfaces (wing, bspline, step, iges) give their own kernel surface over their domain,
// converted to B-spline form; the others are interpolated by a bicubic B-spline on a grid
// refined until it follows them within a tolerance (exact for a plane and for a polynomial
// height field of degree <= 3 in x and in y: such a patch is one Bezier patch).

#include <optional>
#include <string>

#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {

/// A B-spline patch standing for a surface over its whole (u, v) domain.
struct SurfaceBSpline {
  BSplineSpec spec;  ///< part frame, mm; its normal (after flip_normal) the surface's
  /// Largest distance (mm) from the surface's points on a grid (65 x 65, and the midpoints
  /// of the fitting grid) to the patch (an upper bound: for each, the nearer of the patch's
  /// point at the same fraction of its domain and the patch's closest point).
  double max_deviation_mm = 0.0;
  bool converted = false;  ///< the kernel's own surface (true) or an interpolation (false)
  int grid = 0;            ///< interpolated: the control net is grid x grid
};

/// The patch of `surface`; interpolations are refined (4, 7, 13, ... up to 193 control points
/// a side) until max_deviation_mm <= tolerance_mm, or the finest is returned. nullopt with
/// `error` set when the kernel fails or the surface does not evaluate over its domain.
std::optional<SurfaceBSpline> SurfaceToBSpline(const Surface& surface, double tolerance_mm,
                                               std::string& error);

}  // namespace stitchsim::geom
