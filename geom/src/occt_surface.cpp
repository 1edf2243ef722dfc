// The OCCT-backed Surface: a Geom_Surface over a parameter box, its parameters scaled to mm.
// Closest points are global: Newton from a start (the caller's, this thread's last foot point
// on the same surface, or the nearest cell centre of the projection index), then Newton from
// every cell of the index whose box lies nearer than the answer so far (on a closed wing, the
// other skin); the kernel's global search only when no descent converges.
#include "occt_surface.h"

#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "projection_index.h"
#include "stitchsim/geom/cad_surface.h"

namespace stitchsim::geom {
namespace detail {
namespace {

Eigen::Vector3d ToEigen(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }

// The projection index's cells: sized for this chord tolerance (mm), at least kIndexMinCells
// and at most kIndexMaxCells a side, at most kIndexMaxTotal in all (about 4 surface
// evaluations a cell when the surface is made).
constexpr double kIndexChordMm = 0.5;
constexpr int kIndexMinCells = 16;
constexpr int kIndexMaxCells = 512;
constexpr int kIndexMaxTotal = 8192;

class OcctSurface final : public Surface {
 public:
  OcctSurface(Handle(Geom_Surface) s, const ParamBox& box, bool flip, std::string kind)
      : s_(std::move(s)), box_(box), sign_(flip ? -1.0 : 1.0), kind_(std::move(kind)) {}

  // Scales the parameters and samples the start grid; false when degenerate.
  bool Init(std::string& error) {
    const double lu = IsoLength(true), lv = IsoLength(false);
    if (!(lu > 1e-9) || !(lv > 1e-9)) {
      error = "the surface is degenerate (an iso-curve of zero length)";
      return false;
    }
    scale_ = Eigen::Vector2d((box_.u1 - box_.u0) / lu, (box_.v1 - box_.v0) / lv);
    dom_.min = Eigen::Vector2d::Zero();
    dom_.max = Eigen::Vector2d(lu, lv);
    Eigen::Vector2i cells =
        TessellationCells(kIndexChordMm).cwiseMax(kIndexMinCells).cwiseMin(kIndexMaxCells);
    while (cells.prod() > kIndexMaxTotal) {
      const int longer = cells.x() >= cells.y() ? 0 : 1;
      cells[longer] = std::max(kIndexMinCells, cells[longer] / 2);
      if (cells.x() == kIndexMinCells && cells.y() == kIndexMinCells) break;
    }
    if (!index_.Build(*this, cells)) {
      error = "the surface does not evaluate over its domain";
      return false;
    }
    return true;
  }

  std::string Kind() const override { return kind_; }
  const Handle(Geom_Surface) & Geometry() const { return s_; }
  const ParamBox& Box() const { return box_; }
  bool Flipped() const { return sign_ < 0; }
  Domain2 Domain() const override { return dom_; }

  Eigen::Vector3d Point(const Eigen::Vector2d& uv) const override {
    try {
      const Eigen::Vector2d s = Param(uv);
      return ToEigen(s_->Value(s.x(), s.y()).XYZ());
    } catch (const Standard_Failure&) {
      return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    }
  }

  Eigen::Vector3d Normal(const Eigen::Vector2d& uv) const override {
    Eigen::Matrix<double, 3, 2> j = Jacobian(uv);
    Eigen::Vector3d n = j.col(0).cross(j.col(1));
    if (n.norm() < 1e-12) {
      // A collapsed edge (a pole): take the normal just inside the domain.
      const Eigen::Vector2d c = (dom_.min + dom_.max) / 2;
      j = Jacobian(uv + 1e-6 * (c - uv));
      n = j.col(0).cross(j.col(1));
    }
    return sign_ * n.normalized();
  }

  Eigen::Matrix<double, 3, 2> Jacobian(const Eigen::Vector2d& uv) const override {
    Eigen::Vector3d p;
    Eigen::Matrix<double, 3, 2> j;
    PointAndJacobian(uv, p, j);
    return j;
  }

  void PointAndJacobian(const Eigen::Vector2d& uv, Eigen::Vector3d& point,
                        Eigen::Matrix<double, 3, 2>& j) const override {
    try {
      const Eigen::Vector2d s = Param(uv);
      gp_Pnt p;
      gp_Vec du, dv;
      s_->D1(s.x(), s.y(), p, du, dv);
      point = ToEigen(p.XYZ());
      j.col(0) = ToEigen(du.XYZ()) * scale_.x();
      j.col(1) = ToEigen(dv.XYZ()) * scale_.y();
    } catch (const Standard_Failure&) {
      point.setConstant(std::numeric_limits<double>::quiet_NaN());
      j.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }

  SurfaceProjection Project(const Eigen::Vector3d& p) const override {
    thread_local const OcctSurface* hint_owner = nullptr;
    thread_local Eigen::Vector2d hint_uv;
    const Newton r = Closest(p, hint_owner == this ? &hint_uv : nullptr);
    hint_owner = this;
    hint_uv = r.uv;
    return Result(p, r);
  }

  SurfaceProjection ProjectFrom(const Eigen::Vector3d& p,
                                const Eigen::Vector2d& uv_start) const override {
    return Result(p, Closest(p, &uv_start));
  }

  Eigen::Vector2i TessellationCells(double chord_tol_mm) const override {
    // Bound the normal second derivatives over a grid to size cells for the chord tolerance,
    // each direction by its own curvature.
    double ku = 1e-12, kv = 1e-12;
    for (int i = 0; i <= 8; ++i) {
      for (int k = 0; k <= 8; ++k) {
        const Eigen::Vector2d uv = dom_.max.cwiseProduct(Eigen::Vector2d(i / 8.0, k / 8.0));
        const Second d = Derivatives(uv);
        const Eigen::Vector3d n = d.su.cross(d.sv).normalized();
        if (!n.allFinite()) continue;
        const double twist = std::abs(n.dot(d.suv));
        ku = std::max({ku, std::abs(n.dot(d.suu)), twist});
        kv = std::max({kv, std::abs(n.dot(d.svv)), twist});
      }
    }
    const Eigen::Vector2d ext = dom_.max - dom_.min;
    auto cells = [&](double len, double k) {
      const double h = std::sqrt(8.0 * chord_tol_mm / k);
      return std::clamp(static_cast<int>(std::ceil(len / h)), 1, 1024);
    };
    return Eigen::Vector2i(cells(ext.x(), ku), cells(ext.y(), kv));
  }

 private:
  struct Second {
    Eigen::Vector3d p, su, sv, suu, svv, suv;
  };
  struct Newton {
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    bool converged = false;
    bool inside = false;
  };

  Eigen::Vector2d Param(const Eigen::Vector2d& uv) const {
    const Eigen::Vector2d c = uv.cwiseMax(dom_.min).cwiseMin(dom_.max);
    return {box_.u0 + c.x() * scale_.x(), box_.v0 + c.y() * scale_.y()};
  }

  Second Derivatives(const Eigen::Vector2d& uv) const {
    Second d;
    try {
      const Eigen::Vector2d s = Param(uv);
      gp_Pnt p;
      gp_Vec du, dv, duu, dvv, duv;
      s_->D2(s.x(), s.y(), p, du, dv, duu, dvv, duv);
      d.p = ToEigen(p.XYZ());
      d.su = ToEigen(du.XYZ()) * scale_.x();
      d.sv = ToEigen(dv.XYZ()) * scale_.y();
      d.suu = ToEigen(duu.XYZ()) * (scale_.x() * scale_.x());
      d.svv = ToEigen(dvv.XYZ()) * (scale_.y() * scale_.y());
      d.suv = ToEigen(duv.XYZ()) * (scale_.x() * scale_.y());
    } catch (const Standard_Failure&) {
      d.p.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    return d;
  }

  // Length of the middle iso-curve along u (along_u) or v, by chords, in mm.
  double IsoLength(bool along_u) const {
    constexpr int n = 64;
    double len = 0.0;
    try {
      const double um = (box_.u0 + box_.u1) / 2, vm = (box_.v0 + box_.v1) / 2;
      Eigen::Vector3d prev;
      for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        const gp_Pnt q = along_u ? s_->Value(box_.u0 + t * (box_.u1 - box_.u0), vm)
                                 : s_->Value(um, box_.v0 + t * (box_.v1 - box_.v0));
        const Eigen::Vector3d e = ToEigen(q.XYZ());
        if (i > 0) len += (e - prev).norm();
        prev = e;
      }
    } catch (const Standard_Failure&) {
      return 0.0;
    }
    return len;
  }

  SurfaceProjection Result(const Eigen::Vector3d& p, const Newton& r) const {
    SurfaceProjection out;
    out.uv = r.uv;
    out.inside_domain = r.inside;
    out.point = Point(r.uv);
    out.normal = Normal(r.uv);
    out.signed_distance_mm = (p - out.point).dot(out.normal);
    return out;
  }

  // The closest point over the whole domain. The start (or the nearest cell centre) gives a
  // first answer at distance d; a nearer point can only lie in a cell whose box is nearer than
  // d, so each such cell away from the answer's own neighbourhood is descended from too and
  // the nearest answer kept. For a point on or near the surface that is no cell at all (the
  // boxes about the foot are its neighbourhood), except where another sheet passes within d.
  Newton Closest(const Eigen::Vector3d& p, const Eigen::Vector2d* start) const {
    Newton best;
    double best_d2 = std::numeric_limits<double>::infinity();
    const auto consider = [&](const Newton& r) {
      if (!r.converged) return;
      const double d2 = (Point(r.uv) - p).squaredNorm();
      if (d2 < best_d2) {
        best = r;
        best_d2 = d2;
      }
    };
    if (start != nullptr) consider(Descend(p, *start));
    if (!best.converged) consider(Descend(p, index_.NearestCentre(p)));
    if (!best.converged) return GlobalSearch(p);
    thread_local std::vector<ProjectionIndex::Near> near;
    index_.CellsWithin(p, std::sqrt(best_d2), near);
    const Eigen::Vector2i home = index_.CellOf(best.uv);
    for (const ProjectionIndex::Near& c : near) {
      if (!(c.box_d2 < best_d2)) break;  // nearest first: no later cell can hold a nearer point
      if ((c.cell - home).cwiseAbs().maxCoeff() <= 1) continue;
      consider(Descend(p, index_.CentreOf(c.cell)));
    }
    return best;
  }

  // Newton on |S(uv) - p|^2 with iterates kept in the domain. `inside`: the minimum is not
  // held at the domain boundary by the clamp.
  Newton Descend(const Eigen::Vector3d& p, Eigen::Vector2d uv) const {
    Newton out;
    for (int iter = 0; iter < 30; ++iter) {
      const Second d = Derivatives(uv);
      if (!d.p.allFinite()) return out;
      const Eigen::Vector3d r = d.p - p;
      const Eigen::Vector2d g(r.dot(d.su), r.dot(d.sv));
      Eigen::Matrix2d h;
      h << d.su.dot(d.su) + r.dot(d.suu), d.su.dot(d.sv) + r.dot(d.suv),
          d.su.dot(d.sv) + r.dot(d.suv), d.sv.dot(d.sv) + r.dot(d.svv);
      if (h.determinant() <= 0 || h(0, 0) <= 0) {
        // Not convex here: Gauss-Newton.
        h << d.su.dot(d.su), d.su.dot(d.sv), d.su.dot(d.sv), d.sv.dot(d.sv);
      }
      const Eigen::Vector2d step = -h.ldlt().solve(g);
      if (!step.allFinite()) return out;
      const Eigen::Vector2d next = (uv + step).cwiseMax(dom_.min).cwiseMin(dom_.max);
      const double moved = (next - uv).norm();
      const bool clamped = (next - (uv + step)).norm() > 1e-12;
      uv = next;
      if (moved < 1e-10) {
        out.uv = uv;
        out.converged = true;
        out.inside = !clamped;
        return out;
      }
    }
    return out;
  }

  Newton GlobalSearch(const Eigen::Vector3d& p) const {
    Newton out;
    out.uv = index_.NearestCentre(p);
    out.converged = true;
    try {
      GeomAPI_ProjectPointOnSurf proj(gp_Pnt(p.x(), p.y(), p.z()), s_, box_.u0, box_.u1, box_.v0,
                                      box_.v1);
      if (proj.NbPoints() > 0) {
        double su = 0, sv = 0;
        proj.LowerDistanceParameters(su, sv);
        const Eigen::Vector2d uv((su - box_.u0) / scale_.x(), (sv - box_.v0) / scale_.y());
        out.uv = uv.cwiseMax(dom_.min).cwiseMin(dom_.max);
        out.inside = dom_.Contains(uv, 1e-6);
      }
    } catch (const Standard_Failure&) {
      // keep the grid point
    }
    return out;
  }

  Handle(Geom_Surface) s_;
  ParamBox box_;
  double sign_;
  std::string kind_;
  Domain2 dom_;
  Eigen::Vector2d scale_ = Eigen::Vector2d::Ones();  // kernel parameter per mm
  ProjectionIndex index_;
};

}  // namespace

std::unique_ptr<Surface> MakeOcctSurface(const Handle(Geom_Surface) & surface, const ParamBox& box,
                                         bool flip_normal, std::string kind, std::string& error) {
  if (surface.IsNull()) {
    error = "no surface";
    return nullptr;
  }
  if (!std::isfinite(box.u0) || !std::isfinite(box.u1) || !std::isfinite(box.v0) ||
      !std::isfinite(box.v1) || !(box.u1 > box.u0) || !(box.v1 > box.v0)) {
    error = "the surface has an empty or unbounded parameter range";
    return nullptr;
  }
  auto s = std::make_unique<OcctSurface>(surface, box, flip_normal, std::move(kind));
  if (!s->Init(error)) return nullptr;
  return s;
}

bool OcctGeometry(const Surface& surface, Handle(Geom_Surface) & geometry, ParamBox& box,
                  bool& flip_normal) {
  const auto* s = dynamic_cast<const OcctSurface*>(&surface);
  if (!s) return false;
  geometry = s->Geometry();
  box = s->Box();
  flip_normal = s->Flipped();
  return true;
}

}  // namespace detail

namespace {

// Distinct knots and multiplicities of a clamped uniform knot vector for `n` poles.
void ClampedUniform(int n, int degree, std::vector<double>& knots, std::vector<int>& mults) {
  const int spans = n - degree;
  knots.clear();
  mults.clear();
  for (int i = 0; i <= spans; ++i) {
    knots.push_back(static_cast<double>(i) / spans);
    mults.push_back(i == 0 || i == spans ? degree + 1 : 1);
  }
}

// Checks one direction's knots against its pole count and degree.
bool CheckKnots(const std::vector<double>& knots, const std::vector<int>& mults, int n, int degree,
                const char* dir, std::string& error) {
  const std::string d = dir;
  if (knots.size() != mults.size() || knots.size() < 2) {
    error = "knots_" + d + " and multiplicities_" + d + " must have the same length, at least 2";
    return false;
  }
  int sum = 0;
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i]) || (i > 0 && !(knots[i] > knots[i - 1]))) {
      error = "knots_" + d + " must be finite and strictly increasing";
      return false;
    }
    const int maxm = (i == 0 || i + 1 == knots.size()) ? degree + 1 : degree;
    if (mults[i] < 1 || mults[i] > maxm) {
      error = "multiplicities_" + d + " must lie in 1.." + std::to_string(maxm) + " (end knots " +
              std::to_string(degree + 1) + ")";
      return false;
    }
    sum += mults[i];
  }
  if (sum != n + degree + 1) {
    error = "the multiplicities_" + d + " sum to " + std::to_string(sum) + "; " +
            std::to_string(n) + " poles of degree " + std::to_string(degree) + " need " +
            std::to_string(n + degree + 1);
    return false;
  }
  return true;
}

}  // namespace

Handle(Geom_BSplineSurface) detail::BuildBSpline(const BSplineSpec& spec, std::string& error) {
  const int nu = static_cast<int>(spec.poles.size());
  const int nv = nu > 0 ? static_cast<int>(spec.poles[0].size()) : 0;
  if (spec.degree_u < 1 || spec.degree_v < 1 || spec.degree_u > 9 || spec.degree_v > 9) {
    error = "degrees must lie in 1..9";
    return {};
  }
  if (nu < spec.degree_u + 1 || nv < spec.degree_v + 1) {
    error = "the control net needs at least degree + 1 rows and columns (" +
            std::to_string(spec.degree_u + 1) + " x " + std::to_string(spec.degree_v + 1) +
            "), got " + std::to_string(nu) + " x " + std::to_string(nv);
    return {};
  }
  const bool rational = !spec.weights.empty();
  if (rational && static_cast<int>(spec.weights.size()) != nu) {
    error = "weights must have one row per control-net row";
    return {};
  }
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i) {
    const auto& row = spec.poles[static_cast<std::size_t>(i)];
    if (static_cast<int>(row.size()) != nv) {
      error = "control-net row " + std::to_string(i) + " has " + std::to_string(row.size()) +
              " points; row 0 has " + std::to_string(nv);
      return {};
    }
    if (rational && spec.weights[static_cast<std::size_t>(i)].size() != row.size()) {
      error = "weights row " + std::to_string(i) + " must have " + std::to_string(nv) + " values";
      return {};
    }
    for (int k = 0; k < nv; ++k) {
      const Eigen::Vector3d& q = row[static_cast<std::size_t>(k)];
      const double w = rational ? spec.weights[static_cast<std::size_t>(i)][k] : 1.0;
      if (!q.allFinite() || !std::isfinite(w) || !(w > 0)) {
        error = "control point (" + std::to_string(i) + ", " + std::to_string(k) +
                ") must be finite with a weight > 0";
        return {};
      }
      poles.SetValue(i + 1, k + 1, gp_Pnt(q.x(), q.y(), q.z()));
      weights.SetValue(i + 1, k + 1, w);
    }
  }
  std::vector<double> ku = spec.knots_u, kv = spec.knots_v;
  std::vector<int> mu = spec.mults_u, mv = spec.mults_v;
  if (ku.empty() && mu.empty()) ClampedUniform(nu, spec.degree_u, ku, mu);
  if (kv.empty() && mv.empty()) ClampedUniform(nv, spec.degree_v, kv, mv);
  if (!CheckKnots(ku, mu, nu, spec.degree_u, "u", error) ||
      !CheckKnots(kv, mv, nv, spec.degree_v, "v", error)) {
    return {};
  }
  auto to_real = [](const std::vector<double>& k) {
    TColStd_Array1OfReal a(1, static_cast<int>(k.size()));
    for (std::size_t i = 0; i < k.size(); ++i) a.SetValue(static_cast<int>(i) + 1, k[i]);
    return a;
  };
  auto to_int = [](const std::vector<int>& m) {
    TColStd_Array1OfInteger a(1, static_cast<int>(m.size()));
    for (std::size_t i = 0; i < m.size(); ++i) a.SetValue(static_cast<int>(i) + 1, m[i]);
    return a;
  };
  try {
    Handle(Geom_BSplineSurface) s;
    if (rational) {
      s = new Geom_BSplineSurface(poles, weights, to_real(ku), to_real(kv), to_int(mu), to_int(mv),
                                  spec.degree_u, spec.degree_v);
    } else {
      s = new Geom_BSplineSurface(poles, to_real(ku), to_real(kv), to_int(mu), to_int(mv),
                                  spec.degree_u, spec.degree_v);
    }
    return s;
  } catch (const Standard_Failure& e) {
    error = std::string("the kernel rejects the B-spline: ") + e.GetMessageString();
    return {};
  }
}

std::unique_ptr<Surface> MakeBSplineSurface(const BSplineSpec& spec, std::string& error) {
  const Handle(Geom_BSplineSurface) s = detail::BuildBSpline(spec, error);
  if (s.IsNull()) return nullptr;
  detail::ParamBox box;
  s->Bounds(box.u0, box.u1, box.v0, box.v1);
  return detail::MakeOcctSurface(s, box, spec.flip_normal, "bspline", error);
}

}  // namespace stitchsim::geom
