// Surfaces as one B-spline patch: the kernel's conversion for CAD surfaces, a bicubic
// interpolation at the Greville points of a clamped uniform knot vector for the rest (it
// reproduces every bicubic polynomial, so planes and cubic height fields come out exact).
#include "stitchsim/geom/surface_export.h"

#include <Eigen/LU>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <cmath>
#include <vector>

#include "occt_surface.h"

namespace stitchsim::geom {
namespace {

constexpr int kDegree = 3;
constexpr int kMaxGrid = 193;
constexpr int kCheckGrid = 64;

// Full clamped uniform knot vector on [0, 1] for `n` control points of degree 3.
std::vector<double> ClampedKnots(int n) {
  const int spans = n - kDegree;
  std::vector<double> k;
  for (int i = 0; i < kDegree; ++i) k.push_back(0.0);
  for (int i = 0; i <= spans; ++i) k.push_back(static_cast<double>(i) / spans);
  for (int i = 0; i < kDegree; ++i) k.push_back(1.0);
  return k;
}

// Value of the i-th degree-3 basis function at t (Cox-de Boor; the last span closed at 1).
double Basis(const std::vector<double>& k, int i, int p, double t) {
  if (p == 0) {
    const bool last = k[i + 1] == k.back() && k[i] < k[i + 1];
    return (k[i] <= t && (t < k[i + 1] || (last && t == k[i + 1]))) ? 1.0 : 0.0;
  }
  double v = 0.0;
  if (k[i + p] > k[i]) v += (t - k[i]) / (k[i + p] - k[i]) * Basis(k, i, p - 1, t);
  if (k[i + p + 1] > k[i + 1]) {
    v += (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) * Basis(k, i + 1, p - 1, t);
  }
  return v;
}

std::vector<double> Greville(const std::vector<double>& k, int n) {
  std::vector<double> g(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) g[i] = (k[i + 1] + k[i + 2] + k[i + 3]) / 3.0;
  return g;
}

// The bicubic patch with n x n control points through the surface at the Greville points.
std::optional<BSplineSpec> Interpolate(const Surface& surface, int n) {
  const Domain2 d = surface.Domain();
  const std::vector<double> knots = ClampedKnots(n);
  const std::vector<double> t = Greville(knots, n);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) a(i, j) = Basis(knots, j, kDegree, t[i]);
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
  BSplineSpec spec;
  spec.degree_u = spec.degree_v = kDegree;
  spec.poles.assign(n, std::vector<Eigen::Vector3d>(n));
  std::vector<Eigen::MatrixXd> x(3, Eigen::MatrixXd(n, n));  // x[c](i, j): (t_i, t_j)
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d p =
          surface.Point(d.min + (d.max - d.min).cwiseProduct(Eigen::Vector2d(t[i], t[j])));
      for (int c = 0; c < 3; ++c) x[c](i, j) = p[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    if (!x[c].allFinite()) return std::nullopt;
    const Eigen::MatrixXd q = lu.solve(x[c]);                       // along u
    const Eigen::MatrixXd p = lu.solve(q.transpose()).transpose();  // along v
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) spec.poles[i][j][c] = p(i, j);
    }
  }
  spec.knots_u.clear();
  for (int i = 0; i <= n - kDegree; ++i) {
    spec.knots_u.push_back(static_cast<double>(i) / (n - kDegree));
    spec.mults_u.push_back(i == 0 || i == n - kDegree ? kDegree + 1 : 1);
  }
  spec.knots_v = spec.knots_u;
  spec.mults_v = spec.mults_u;
  // Same (u, v) orientation as the surface: flip when its normal is against du x dv.
  const Eigen::Vector2d mid = (d.min + d.max) / 2;
  const Eigen::Matrix<double, 3, 2> j = surface.Jacobian(mid);
  spec.flip_normal = j.col(0).cross(j.col(1)).dot(surface.Normal(mid)) < 0;
  return spec;
}

// The spec of a kernel B-spline.
BSplineSpec SpecOf(const Handle(Geom_BSplineSurface) & s, bool flip) {
  BSplineSpec spec;
  spec.degree_u = s->UDegree();
  spec.degree_v = s->VDegree();
  const bool rational = s->IsURational() || s->IsVRational();
  for (int i = 1; i <= s->NbUPoles(); ++i) {
    spec.poles.emplace_back();
    if (rational) spec.weights.emplace_back();
    for (int k = 1; k <= s->NbVPoles(); ++k) {
      const gp_Pnt p = s->Pole(i, k);
      spec.poles.back().emplace_back(p.X(), p.Y(), p.Z());
      if (rational) spec.weights.back().push_back(s->Weight(i, k));
    }
  }
  for (int i = 1; i <= s->NbUKnots(); ++i) {
    spec.knots_u.push_back(s->UKnot(i));
    spec.mults_u.push_back(s->UMultiplicity(i));
  }
  for (int i = 1; i <= s->NbVKnots(); ++i) {
    spec.knots_v.push_back(s->VKnot(i));
    spec.mults_v.push_back(s->VMultiplicity(i));
  }
  spec.flip_normal = flip;
  return spec;
}

// The kernel surface of a CAD surface over its box, as a B-spline; null if not a CAD surface.
std::optional<BSplineSpec> Convert(const Surface& surface) {
  Handle(Geom_Surface) geometry;
  detail::ParamBox box;
  bool flip = false;
  if (!detail::OcctGeometry(surface, geometry, box, flip)) return std::nullopt;
  Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(geometry);
  if (!b.IsNull()) {
    b = Handle(Geom_BSplineSurface)::DownCast(b->Copy());
    double u0, u1, v0, v1;
    b->Bounds(u0, u1, v0, v1);
    if (box.u0 > u0 || box.u1 < u1 || box.v0 > v0 || box.v1 < v1) {
      b->Segment(box.u0, box.u1, box.v0, box.v1);
    }
  } else {
    const Handle(Geom_RectangularTrimmedSurface) trimmed =
        new Geom_RectangularTrimmedSurface(geometry, box.u0, box.u1, box.v0, box.v1);
    b = GeomConvert::SurfaceToBSplineSurface(trimmed);
  }
  if (b.IsNull()) return std::nullopt;
  return SpecOf(b, flip);
}

// Largest distance from the surface's grid points (and the fitting grid's midpoints) to the
// patch: for each, the nearer of the patch's point at the same fraction of its domain (the
// patch's parameters are linear in the surface's) and its closest point (Project, which on a
// closed section such as a wing may settle on the far skin from a poor start). Both are
// points of the patch, so the smaller is still an upper bound of the true distance.
double Deviation(const Surface& surface, const Surface& patch, int fit_grid) {
  const Domain2 d = surface.Domain();
  const Domain2 pd = patch.Domain();
  double worst = 0.0;
  const auto check = [&](int count) {
    for (int i = 0; i <= count; ++i) {
      for (int k = 0; k <= count; ++k) {
        const Eigen::Vector2d f(i / static_cast<double>(count), k / static_cast<double>(count));
        const Eigen::Vector3d p = surface.Point(d.min + (d.max - d.min).cwiseProduct(f));
        const Eigen::Vector3d same = patch.Point(pd.min + (pd.max - pd.min).cwiseProduct(f));
        const double dist = std::min((same - p).norm(), (patch.Project(p).point - p).norm());
        worst = std::max(worst, std::isfinite(dist) ? dist : 1e300);
      }
    }
  };
  check(kCheckGrid);
  if (fit_grid > 0) check(2 * (fit_grid - 1));  // the midpoints between fitted points
  return worst;
}

}  // namespace

std::optional<SurfaceBSpline> SurfaceToBSpline(const Surface& surface, double tolerance_mm,
                                               std::string& error) {
  try {
    SurfaceBSpline out;
    if (std::optional<BSplineSpec> spec = Convert(surface)) {
      auto patch = MakeBSplineSurface(*spec, error);
      if (!patch) return std::nullopt;
      out.converted = true;
      out.spec = *spec;
      out.max_deviation_mm = Deviation(surface, *patch, 0);
      return out;
    }
    for (int n = 4; n <= kMaxGrid; n = 2 * n - 1) {
      std::optional<BSplineSpec> spec = Interpolate(surface, n);
      if (!spec) {
        error = "the surface does not evaluate over its domain";
        return std::nullopt;
      }
      auto patch = MakeBSplineSurface(*spec, error);
      if (!patch) return std::nullopt;
      out.grid = n;
      out.spec = *spec;
      out.max_deviation_mm = Deviation(surface, *patch, n);
      if (out.max_deviation_mm <= tolerance_mm) break;
    }
    return out;
  } catch (const Standard_Failure& e) {
    error = std::string("the kernel failed: ") + e.GetMessageString();
    return std::nullopt;
  }
}

}  // namespace stitchsim::geom
