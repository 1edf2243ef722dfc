// The NACA loft as a kernel B-spline: each of the root and tip sections interpolated by a
// cubic through stations evenly spaced in s (cosine spaced in x, dense at the leading edge),
// with the same parameters so that both curves share one knot vector; the surface is the
// ruled (degree 1) B-spline between their control polygons, which is the loft exactly.
#include "stitchsim/geom/wing_surface.h"

#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <algorithm>
#include <cmath>

#include "occt_surface.h"

namespace stitchsim::geom {
namespace {

constexpr int kFirstStations = 129;
constexpr int kMaxStations = 8193;

// The cubic through `n` stations s = i / (n - 1) of the root or tip section.
Handle(Geom_BSplineCurve) FitSection(const Wing& wing, bool tip, int n) {
  Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n);
  Handle(TColStd_HArray1OfReal) params = new TColStd_HArray1OfReal(1, n);
  for (int i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) / (n - 1);
    const Eigen::Vector3d p = wing.SectionPoint(tip, s);
    points->SetValue(i + 1, gp_Pnt(p.x(), p.y(), p.z()));
    params->SetValue(i + 1, s);
  }
  GeomAPI_Interpolate fit(points, params, false, 1e-9);
  fit.Perform();
  if (!fit.IsDone()) return {};
  return fit.Curve();
}

// Largest distance between the fitted section and the wing midway between the stations.
double SectionError(const Wing& wing, bool tip, const Handle(Geom_BSplineCurve) & curve, int n) {
  double worst = 0.0;
  for (int i = 0; i + 1 < n; ++i) {
    const double s = (i + 0.5) / (n - 1);
    const gp_Pnt q = curve->Value(s);
    const Eigen::Vector3d fitted(q.X(), q.Y(), q.Z());
    worst = std::max(worst, (fitted - wing.SectionPoint(tip, s)).norm());
  }
  return worst;
}

bool SameKnots(const Handle(Geom_BSplineCurve) & a, const Handle(Geom_BSplineCurve) & b) {
  if (a->NbKnots() != b->NbKnots() || a->NbPoles() != b->NbPoles() || a->Degree() != b->Degree()) {
    return false;
  }
  for (int i = 1; i <= a->NbKnots(); ++i) {
    if (a->Knot(i) != b->Knot(i) || a->Multiplicity(i) != b->Multiplicity(i)) return false;
  }
  return true;
}

// The ruled B-spline between two sections with one knot vector.
Handle(Geom_BSplineSurface)
    Ruled(const Handle(Geom_BSplineCurve) & root, const Handle(Geom_BSplineCurve) & tip) {
  const int n = root->NbPoles();
  TColgp_Array2OfPnt poles(1, n, 1, 2);
  for (int i = 1; i <= n; ++i) {
    poles.SetValue(i, 1, root->Pole(i));
    poles.SetValue(i, 2, tip->Pole(i));
  }
  TColStd_Array1OfReal knots_u(1, root->NbKnots());
  TColStd_Array1OfInteger mults_u(1, root->NbKnots());
  root->Knots(knots_u);
  root->Multiplicities(mults_u);
  TColStd_Array1OfReal knots_v(1, 2);
  TColStd_Array1OfInteger mults_v(1, 2);
  knots_v.SetValue(1, 0.0);
  knots_v.SetValue(2, 1.0);
  mults_v.SetValue(1, 2);
  mults_v.SetValue(2, 2);
  return new Geom_BSplineSurface(poles, knots_u, knots_v, mults_u, mults_v, root->Degree(), 1);
}

}  // namespace

Eigen::Vector2d WingSkinRange(WingSkin skin) {
  switch (skin) {
    case WingSkin::kUpper:
      return {0.0, 0.5};
    case WingSkin::kLower:
      return {0.5, 1.0};
    case WingSkin::kFull:
      break;
  }
  return {0.0, 1.0};
}

WingSurface MakeWingSurface(const WingSpec& spec, WingSkin skin, std::string& error,
                            double tolerance_mm) {
  WingSurface out;
  const std::optional<Wing> wing = Wing::Make(spec, error);
  if (!wing) return out;
  try {
    Handle(Geom_BSplineCurve) root, tip;
    for (int n = kFirstStations; n <= kMaxStations; n = 2 * n - 1) {
      root = FitSection(*wing, false, n);
      tip = FitSection(*wing, true, n);
      if (root.IsNull() || tip.IsNull()) {
        error = "the kernel cannot interpolate the wing sections";
        return out;
      }
      out.stations = n;
      out.fit_error_mm =
          std::max(SectionError(*wing, false, root, n), SectionError(*wing, true, tip, n));
      if (out.fit_error_mm <= tolerance_mm) break;
    }
    if (!(out.fit_error_mm <= tolerance_mm)) {
      error = "the wing sections cannot be fitted to " + std::to_string(tolerance_mm) +
              " mm (best " + std::to_string(out.fit_error_mm) + " mm)";
      return out;
    }
    if (!SameKnots(root, tip)) {
      error = "the kernel fitted the root and tip sections with different knots";
      return out;
    }
    const Handle(Geom_BSplineSurface) s = Ruled(root, tip);
    const Eigen::Vector2d range = WingSkinRange(skin);
    const detail::ParamBox box{range.x(), range.y(), 0.0, 1.0};
    // The kernel's normal dP/ds x dP/deta points into the wing: flipped.
    out.surface = detail::MakeOcctSurface(s, box, true, "wing", error);
  } catch (const Standard_Failure& e) {
    error = std::string("the kernel failed to build the wing: ") + e.GetMessageString();
    out.surface.reset();
  }
  return out;
}

}  // namespace stitchsim::geom
