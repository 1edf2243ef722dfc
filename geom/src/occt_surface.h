#pragma once
// Private to geom: the OCCT-backed Surface over any Geom_Surface (occt_surface.cpp), shared
// by the B-spline maker and the STEP / IGES reader (cad_file.cpp).

#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <memory>
#include <string>

#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::geom::detail {

/// Kernel parameter bounds of a face or patch.
struct ParamBox {
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
};

/// `surface` over `box`, scaled to a (u, v) domain in mm; nullptr with `error` set when the
/// box is empty or degenerate or the kernel fails.
std::unique_ptr<Surface> MakeOcctSurface(const Handle(Geom_Surface) & surface, const ParamBox& box,
                                         bool flip_normal, std::string kind, std::string& error);

/// The kernel surface behind `surface`, its parameter box and whether its normal is flipped,
/// when `surface` is one MakeOcctSurface made; false otherwise.
bool OcctGeometry(const Surface& surface, Handle(Geom_Surface) & geometry, ParamBox& box,
                  bool& flip_normal);

/// The kernel B-spline of `spec` (validated), or null with `error` set.
Handle(Geom_BSplineSurface) BuildBSpline(const BSplineSpec& spec, std::string& error);

}  // namespace stitchsim::geom::detail
