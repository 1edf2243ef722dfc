#include "stitchsim/geom/surface.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace stitchsim::geom {

bool Domain2::Contains(const Eigen::Vector2d& uv, double tol_mm) const {
  return uv.x() >= min.x() - tol_mm && uv.x() <= max.x() + tol_mm && uv.y() >= min.y() - tol_mm &&
         uv.y() <= max.y() + tol_mm;
}

Eigen::Matrix<double, 3, 2> Surface::Jacobian(const Eigen::Vector2d& uv) const {
  // Central differences; analytic surfaces override this.
  constexpr double h = 1e-4;
  Eigen::Matrix<double, 3, 2> j;
  j.col(0) = (Point(uv + Eigen::Vector2d(h, 0)) - Point(uv - Eigen::Vector2d(h, 0))) / (2 * h);
  j.col(1) = (Point(uv + Eigen::Vector2d(0, h)) - Point(uv - Eigen::Vector2d(0, h))) / (2 * h);
  return j;
}

SurfaceProjection Surface::Project(const Eigen::Vector3d& p) const {
  // Gauss-Newton on |Point(uv) - p|^2 from the vertical foot point.
  const Domain2 dom = Domain();
  Eigen::Vector2d uv(p.x(), p.y());
  for (int iter = 0; iter < 50; ++iter) {
    const Eigen::Matrix<double, 3, 2> j = Jacobian(uv);
    const Eigen::Vector3d r = p - Point(uv);
    const Eigen::Vector2d step = (j.transpose() * j).ldlt().solve(j.transpose() * r);
    uv += step;
    if (step.norm() < 1e-12) break;
  }
  SurfaceProjection out;
  out.inside_domain = dom.Contains(uv, 1e-6);
  uv = uv.cwiseMax(dom.min).cwiseMin(dom.max);
  out.uv = uv;
  out.point = Point(uv);
  out.normal = Normal(uv);
  out.signed_distance_mm = (p - out.point).dot(out.normal);
  return out;
}

bool Surface::IntersectLine(const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                            Eigen::Vector3d& hit) const {
  // Newton on the signed distance along the line.
  const Eigen::Vector3d d = dir.normalized();
  double t = 0.0;
  for (int iter = 0; iter < 60; ++iter) {
    const Eigen::Vector3d q = p + t * d;
    const SurfaceProjection pr = Project(q);
    const double denom = d.dot(pr.normal);
    if (std::abs(denom) < 1e-9) return false;
    const double dt = -pr.signed_distance_mm / denom;
    t += dt;
    if (std::abs(dt) < 1e-11) {
      hit = p + t * d;
      return Project(hit).inside_domain;
    }
  }
  return false;
}

Eigen::Vector2i Surface::TessellationCells(double /*chord_tol_mm*/) const {
  return Eigen::Vector2i(64, 64);
}

namespace {

class Plane final : public Surface {
 public:
  Plane(double su, double sv) {
    dom_.min = Eigen::Vector2d(-su / 2, -sv / 2);
    dom_.max = Eigen::Vector2d(su / 2, sv / 2);
  }
  std::string Kind() const override { return "plane"; }
  bool IsHeightField() const override { return true; }
  Domain2 Domain() const override { return dom_; }
  Eigen::Vector3d Point(const Eigen::Vector2d& uv) const override {
    return Eigen::Vector3d(uv.x(), uv.y(), 0.0);
  }
  Eigen::Vector3d Normal(const Eigen::Vector2d&) const override { return Eigen::Vector3d::UnitZ(); }
  Eigen::Matrix<double, 3, 2> Jacobian(const Eigen::Vector2d&) const override {
    Eigen::Matrix<double, 3, 2> j;
    j << 1, 0, 0, 1, 0, 0;
    return j;
  }
  SurfaceProjection Project(const Eigen::Vector3d& p) const override {
    SurfaceProjection out;
    Eigen::Vector2d uv(p.x(), p.y());
    out.inside_domain = dom_.Contains(uv, 1e-6);
    uv = uv.cwiseMax(dom_.min).cwiseMin(dom_.max);
    out.uv = uv;
    out.point = Point(uv);
    out.normal = Eigen::Vector3d::UnitZ();
    out.signed_distance_mm = p.z();
    return out;
  }
  bool IntersectLine(const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                     Eigen::Vector3d& hit) const override {
    if (std::abs(dir.z()) < 1e-15) return false;
    hit = p - (p.z() / dir.z()) * dir;
    return dom_.Contains(hit.head<2>(), 1e-6);
  }
  Eigen::Vector2i TessellationCells(double) const override { return Eigen::Vector2i(1, 1); }

 private:
  Domain2 dom_;
};

class Cylinder final : public Surface {
 public:
  Cylinder(double r, bool outside, double length, double arc) : r_(r), outside_(outside) {
    dom_.min = Eigen::Vector2d(-length / 2, -arc / 2);
    dom_.max = Eigen::Vector2d(length / 2, arc / 2);
  }
  std::string Kind() const override { return outside_ ? "cylinder-outside" : "cylinder-inside"; }
  Domain2 Domain() const override { return dom_; }
  Eigen::Vector3d Point(const Eigen::Vector2d& uv) const override {
    const double phi = uv.y() / r_;
    if (outside_) return Eigen::Vector3d(uv.x(), r_ * std::sin(phi), r_ * std::cos(phi) - r_);
    return Eigen::Vector3d(uv.x(), r_ * std::sin(phi), r_ - r_ * std::cos(phi));
  }
  Eigen::Vector3d Normal(const Eigen::Vector2d& uv) const override {
    const double phi = uv.y() / r_;
    if (outside_) return Eigen::Vector3d(0, std::sin(phi), std::cos(phi));
    return Eigen::Vector3d(0, -std::sin(phi), std::cos(phi));
  }
  Eigen::Matrix<double, 3, 2> Jacobian(const Eigen::Vector2d& uv) const override {
    const double phi = uv.y() / r_;
    Eigen::Matrix<double, 3, 2> j;
    if (outside_) {
      j << 1, 0, 0, std::cos(phi), 0, -std::sin(phi);
    } else {
      j << 1, 0, 0, std::cos(phi), 0, std::sin(phi);
    }
    return j;
  }
  SurfaceProjection Project(const Eigen::Vector3d& p) const override {
    SurfaceProjection out;
    double phi = 0.0;
    double dist = 0.0;
    if (outside_) {
      phi = std::atan2(p.y(), p.z() + r_);
      dist = std::hypot(p.y(), p.z() + r_) - r_;
    } else {
      phi = std::atan2(p.y(), r_ - p.z());
      dist = r_ - std::hypot(p.y(), p.z() - r_);
    }
    Eigen::Vector2d uv(p.x(), phi * r_);
    out.inside_domain = dom_.Contains(uv, 1e-6);
    uv = uv.cwiseMax(dom_.min).cwiseMin(dom_.max);
    out.uv = uv;
    out.point = Point(uv);
    out.normal = Normal(uv);
    out.signed_distance_mm = out.inside_domain ? dist : (p - out.point).dot(out.normal);
    return out;
  }
  bool IntersectLine(const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                     Eigen::Vector3d& hit) const override {
    // Circle in the yz-plane centred at (0, zc): |(y, z - zc)| = r.
    const double zc = outside_ ? -r_ : r_;
    const Eigen::Vector2d q(p.y(), p.z() - zc);
    const Eigen::Vector2d d(dir.y(), dir.z());
    const double a = d.squaredNorm();
    if (a < 1e-24) return false;
    const double b = 2 * q.dot(d);
    const double c = q.squaredNorm() - r_ * r_;
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return false;
    const double s = std::sqrt(disc);
    const double t1 = (-b - s) / (2 * a);
    const double t2 = (-b + s) / (2 * a);
    // Of the two crossings, take the one on the stitching side (crown side) nearest p.
    double best = std::numeric_limits<double>::infinity();
    bool found = false;
    for (double t : {t1, t2}) {
      const Eigen::Vector3d h = p + t * dir;
      const bool crown_side = outside_ ? (h.z() - zc) > 0 : (h.z() - zc) < 0;
      if (crown_side && std::abs(t) < std::abs(best)) {
        best = t;
        found = true;
      }
    }
    if (!found) return false;
    hit = p + best * dir;
    return true;
  }
  Eigen::Vector2i TessellationCells(double chord_tol_mm) const override {
    const double step = 2.0 * std::acos(std::max(-1.0, 1.0 - chord_tol_mm / r_));
    const double arc = (dom_.max.y() - dom_.min.y()) / r_;
    const int n = std::clamp(static_cast<int>(std::ceil(arc / std::max(step, 1e-6))), 1, 2048);
    return Eigen::Vector2i(1, n);
  }

 private:
  double r_;
  bool outside_;
  Domain2 dom_;
};

class PolyHeightField final : public Surface {
 public:
  PolyHeightField(const Eigen::Matrix4d& c, const Domain2& d) : c_(c), dom_(d) {}
  std::string Kind() const override { return "polynomial"; }
  bool IsHeightField() const override { return true; }
  Domain2 Domain() const override { return dom_; }
  Eigen::Vector3d Point(const Eigen::Vector2d& uv) const override {
    return Eigen::Vector3d(uv.x(), uv.y(), Eval(uv, 0, 0));
  }
  Eigen::Vector3d Normal(const Eigen::Vector2d& uv) const override {
    return Eigen::Vector3d(-Eval(uv, 1, 0), -Eval(uv, 0, 1), 1.0).normalized();
  }
  Eigen::Matrix<double, 3, 2> Jacobian(const Eigen::Vector2d& uv) const override {
    Eigen::Matrix<double, 3, 2> j;
    j << 1, 0, 0, 1, Eval(uv, 1, 0), Eval(uv, 0, 1);
    return j;
  }
  Eigen::Vector2i TessellationCells(double chord_tol_mm) const override {
    // Bound the second derivative over a coarse grid to size cells for the chord tolerance.
    double kmax = 1e-12;
    for (int i = 0; i <= 8; ++i) {
      for (int k = 0; k <= 8; ++k) {
        const Eigen::Vector2d uv =
            dom_.min + (dom_.max - dom_.min).cwiseProduct(Eigen::Vector2d(i / 8.0, k / 8.0));
        kmax = std::max(
            {kmax, std::abs(Eval(uv, 2, 0)), std::abs(Eval(uv, 0, 2)), std::abs(Eval(uv, 1, 1))});
      }
    }
    const double h = std::sqrt(8.0 * chord_tol_mm / kmax);
    const Eigen::Vector2d ext = dom_.max - dom_.min;
    return Eigen::Vector2i(std::clamp(static_cast<int>(std::ceil(ext.x() / h)), 1, 512),
                           std::clamp(static_cast<int>(std::ceil(ext.y() / h)), 1, 512));
  }

 private:
  // d^(dx+dy) f / dx^dx dy^dy at uv.
  double Eval(const Eigen::Vector2d& uv, int dx, int dy) const {
    double sum = 0.0;
    for (int i = dx; i < 4; ++i) {
      for (int j = dy; j < 4; ++j) {
        if (c_(i, j) == 0.0) continue;
        double fi = 1.0;
        for (int k = 0; k < dx; ++k) fi *= (i - k);
        double fj = 1.0;
        for (int k = 0; k < dy; ++k) fj *= (j - k);
        sum += c_(i, j) * fi * fj * std::pow(uv.x(), i - dx) * std::pow(uv.y(), j - dy);
      }
    }
    return sum;
  }
  Eigen::Matrix4d c_;
  Domain2 dom_;
};

class MeshSurface final : public Surface {
 public:
  explicit MeshSurface(TriangleMesh mesh) : mesh_(std::move(mesh)) {
    dom_.min = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    dom_.max = -dom_.min;
    for (const auto& v : mesh_.vertices) {
      dom_.min = dom_.min.cwiseMin(v.head<2>());
      dom_.max = dom_.max.cwiseMax(v.head<2>());
    }
    // Area-weighted vertex normals, oriented upwards (+z: towards the head).
    vertex_normals_.assign(mesh_.vertices.size(), Eigen::Vector3d::Zero());
    for (const auto& t : mesh_.triangles) {
      Eigen::Vector3d n = (mesh_.vertices[t[1]] - mesh_.vertices[t[0]])
                              .cross(mesh_.vertices[t[2]] - mesh_.vertices[t[0]]);
      if (n.z() < 0) n = -n;
      for (int k = 0; k < 3; ++k) vertex_normals_[t[k]] += n;
    }
    for (auto& n : vertex_normals_) {
      n = n.norm() > 0 ? n.normalized() : Eigen::Vector3d::UnitZ();
    }
    // Uniform grid over (x, y) for point location.
    const Eigen::Vector2d ext = (dom_.max - dom_.min).cwiseMax(1e-9);
    const double cells = std::max(1.0, std::sqrt(static_cast<double>(mesh_.triangles.size())));
    grid_n_ =
        Eigen::Vector2i(std::max(1, static_cast<int>(cells)), std::max(1, static_cast<int>(cells)));
    cell_size_ = ext.cwiseQuotient(grid_n_.cast<double>());
    grid_.assign(static_cast<std::size_t>(grid_n_.x() * grid_n_.y()), {});
    for (std::size_t ti = 0; ti < mesh_.triangles.size(); ++ti) {
      Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
      Eigen::Vector2d hi = -lo;
      for (int k = 0; k < 3; ++k) {
        lo = lo.cwiseMin(mesh_.vertices[mesh_.triangles[ti][k]].head<2>());
        hi = hi.cwiseMax(mesh_.vertices[mesh_.triangles[ti][k]].head<2>());
      }
      const Eigen::Vector2i a = CellOf(lo);
      const Eigen::Vector2i b = CellOf(hi);
      for (int i = a.x(); i <= b.x(); ++i) {
        for (int j = a.y(); j <= b.y(); ++j) grid_[Index(i, j)].push_back(ti);
      }
    }
  }
  std::string Kind() const override { return "mesh"; }
  bool IsHeightField() const override { return true; }
  bool CoversDomain() const override { return false; }
  Domain2 Domain() const override { return dom_; }
  Eigen::Vector3d Point(const Eigen::Vector2d& uv) const override {
    const Hit h = Locate(uv);
    return Eigen::Vector3d(uv.x(), uv.y(), h.z);
  }
  Eigen::Vector3d Normal(const Eigen::Vector2d& uv) const override {
    const Hit h = Locate(uv);
    const auto& t = mesh_.triangles[h.triangle];
    Eigen::Vector3d n = h.bary[0] * vertex_normals_[t[0]] + h.bary[1] * vertex_normals_[t[1]] +
                        h.bary[2] * vertex_normals_[t[2]];
    return n.normalized();
  }

 private:
  struct Hit {
    std::size_t triangle = 0;
    Eigen::Vector3d bary = Eigen::Vector3d(1, 0, 0);
    double z = 0.0;
  };
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const {
    Eigen::Vector2d f = (p - dom_.min).cwiseQuotient(cell_size_);
    return Eigen::Vector2i(std::clamp(static_cast<int>(std::floor(f.x())), 0, grid_n_.x() - 1),
                           std::clamp(static_cast<int>(std::floor(f.y())), 0, grid_n_.y() - 1));
  }
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(i * grid_n_.y() + j); }
  bool Barycentric(std::size_t ti, const Eigen::Vector2d& p, Eigen::Vector3d& bary) const {
    const auto& t = mesh_.triangles[ti];
    const Eigen::Vector2d a = mesh_.vertices[t[0]].head<2>();
    const Eigen::Vector2d b = mesh_.vertices[t[1]].head<2>();
    const Eigen::Vector2d c = mesh_.vertices[t[2]].head<2>();
    const double det = (b - a).x() * (c - a).y() - (c - a).x() * (b - a).y();
    if (std::abs(det) < 1e-18) return false;
    const double l1 = ((p - a).x() * (c - a).y() - (c - a).x() * (p - a).y()) / det;
    const double l2 = ((b - a).x() * (p - a).y() - (p - a).x() * (b - a).y()) / det;
    bary = Eigen::Vector3d(1 - l1 - l2, l1, l2);
    return true;
  }
  Hit Locate(const Eigen::Vector2d& uv) const {
    Hit best;
    double best_violation = std::numeric_limits<double>::infinity();
    auto consider = [&](std::size_t ti) {
      Eigen::Vector3d bary;
      if (!Barycentric(ti, uv, bary)) return;
      const double violation = std::max(0.0, -bary.minCoeff());
      if (violation < best_violation) {
        best_violation = violation;
        best.triangle = ti;
        best.bary = bary;
      }
    };
    for (std::size_t ti : grid_[Index(CellOf(uv).x(), CellOf(uv).y())]) consider(ti);
    if (best_violation > 1e-12) {
      for (std::size_t ti = 0; ti < mesh_.triangles.size(); ++ti) consider(ti);
    }
    const auto& t = mesh_.triangles[best.triangle];
    best.z = best.bary[0] * mesh_.vertices[t[0]].z() + best.bary[1] * mesh_.vertices[t[1]].z() +
             best.bary[2] * mesh_.vertices[t[2]].z();
    return best;
  }

  TriangleMesh mesh_;
  std::vector<Eigen::Vector3d> vertex_normals_;
  Domain2 dom_;
  Eigen::Vector2i grid_n_;
  Eigen::Vector2d cell_size_;
  std::vector<std::vector<std::size_t>> grid_;
};

}  // namespace

std::unique_ptr<Surface> MakePlane(double su, double sv) { return std::make_unique<Plane>(su, sv); }

std::unique_ptr<Surface> MakeCylinder(double r, bool outside, double length, double arc) {
  return std::make_unique<Cylinder>(r, outside, length, arc);
}

std::unique_ptr<Surface> MakePolynomialHeightField(const Eigen::Matrix4d& c, const Domain2& d) {
  return std::make_unique<PolyHeightField>(c, d);
}

std::unique_ptr<Surface> MakeMeshSurface(TriangleMesh mesh) {
  return std::make_unique<MeshSurface>(std::move(mesh));
}

namespace {

TriangleMesh SlabCells(const Surface& surface, const Domain2& domain, double off_bottom,
                       double off_top, int nu, int nv) {
  TriangleMesh m;
  auto grid_uv = [&](int i, int j) {
    return Eigen::Vector2d(domain.min.x() + (domain.max.x() - domain.min.x()) * i / nu,
                           domain.min.y() + (domain.max.y() - domain.min.y()) * j / nv);
  };
  // Layer 0: bottom, layer 1: top.
  for (int layer = 0; layer < 2; ++layer) {
    const double off = layer == 0 ? off_bottom : off_top;
    for (int i = 0; i <= nu; ++i) {
      for (int j = 0; j <= nv; ++j) {
        const Eigen::Vector2d uv = grid_uv(i, j);
        m.vertices.push_back(surface.Point(uv) + off * surface.Normal(uv));
      }
    }
  }
  const int per_layer = (nu + 1) * (nv + 1);
  auto vid = [&](int layer, int i, int j) { return layer * per_layer + i * (nv + 1) + j; };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      // Top faces counter-clockwise seen from +normal; bottom reversed.
      m.triangles.emplace_back(vid(1, i, j), vid(1, i + 1, j), vid(1, i + 1, j + 1));
      m.triangles.emplace_back(vid(1, i, j), vid(1, i + 1, j + 1), vid(1, i, j + 1));
      m.triangles.emplace_back(vid(0, i, j), vid(0, i + 1, j + 1), vid(0, i + 1, j));
      m.triangles.emplace_back(vid(0, i, j), vid(0, i, j + 1), vid(0, i + 1, j + 1));
    }
  }
  // Side walls around the boundary loop (counter-clockwise in (u, v)).
  std::vector<Eigen::Vector2i> loop;
  for (int i = 0; i < nu; ++i) loop.emplace_back(i, 0);
  for (int j = 0; j < nv; ++j) loop.emplace_back(nu, j);
  for (int i = nu; i > 0; --i) loop.emplace_back(i, nv);
  for (int j = nv; j > 0; --j) loop.emplace_back(0, j);
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Eigen::Vector2i a = loop[k];
    const Eigen::Vector2i b = loop[(k + 1) % loop.size()];
    m.triangles.emplace_back(vid(0, a.x(), a.y()), vid(0, b.x(), b.y()), vid(1, b.x(), b.y()));
    m.triangles.emplace_back(vid(0, a.x(), a.y()), vid(1, b.x(), b.y()), vid(1, a.x(), a.y()));
  }
  return m;
}

}  // namespace

TriangleMesh TessellateSlab(const Surface& surface, const Domain2& domain, double off_bottom,
                            double off_top, double chord_tol_mm) {
  const Eigen::Vector2i cells = surface.TessellationCells(chord_tol_mm);
  return SlabCells(surface, domain, off_bottom, off_top, cells.x(), cells.y());
}

std::vector<TriangleMesh> TessellateSlabTiles(const Surface& surface, const Domain2& domain,
                                              double off_bottom, double off_top,
                                              double chord_tol_mm, double max_tile_mm) {
  const Eigen::Vector2i cells = surface.TessellationCells(chord_tol_mm);
  const Eigen::Vector2d ext = domain.max - domain.min;
  auto tiles_along = [&](double e) {
    return std::clamp(static_cast<int>(std::ceil(e / std::max(max_tile_mm, 1e-3))), 1, 256);
  };
  const int tu = tiles_along(ext.x()), tv = tiles_along(ext.y());
  const int cu = std::max(1, (cells.x() + tu - 1) / tu),
            cv = std::max(1, (cells.y() + tv - 1) / tv);
  std::vector<TriangleMesh> out;
  out.reserve(static_cast<std::size_t>(tu * tv));
  for (int i = 0; i < tu; ++i) {
    for (int j = 0; j < tv; ++j) {
      Domain2 d;
      d.min = domain.min + ext.cwiseProduct(Eigen::Vector2d(double(i) / tu, double(j) / tv));
      d.max =
          domain.min + ext.cwiseProduct(Eigen::Vector2d(double(i + 1) / tu, double(j + 1) / tv));
      out.push_back(SlabCells(surface, d, off_bottom, off_top, cu, cv));
    }
  }
  return out;
}

}  // namespace stitchsim::geom
