#pragma once
// Stitching surfaces. Every surface is parametrised over a 2D domain (u, v) in millimetres
// so that paths can be drawn "on the surface": a path is a 2D curve in (u, v), lifted onto
// the surface. Positions are in the part frame, millimetres. Normals are unit vectors that
// point away from the mold, towards the head.

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace stitchsim::geom {

/// Axis-aligned rectangle of the (u, v) domain, millimetres.
struct Domain2 {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  Eigen::Vector2d max = Eigen::Vector2d::Zero();
  bool Contains(const Eigen::Vector2d& uv, double tol_mm = 1e-9) const;
};

/// Result of a closest-point query.
struct SurfaceProjection {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();       ///< parameter of the foot point (mm)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< foot point, part frame (mm)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit normal at the foot point
  double signed_distance_mm = 0.0;  ///< query point minus foot point, along the normal
  bool inside_domain = true;        ///< false if the foot point was clamped to the domain
};

/// Triangle mesh: vertices (mm, part frame) and counter-clockwise triangles (outward normals).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
};

class Surface {
 public:
  virtual ~Surface() = default;
  /// The surface type for messages ("plane", "mesh", ...); ask the capabilities below
  /// instead of comparing it.
  virtual std::string Kind() const = 0;
  /// True if u = x and v = y of the part frame and the surface is single-valued over
  /// (x, y): a point's height above it is z minus Point(x, y).z().
  virtual bool IsHeightField() const { return false; }
  /// True if every (u, v) of Domain() lies on the surface. False for a mesh, whose domain is
  /// the bounding box of its vertices (Point() extrapolates outside its triangles).
  virtual bool CoversDomain() const { return true; }
  virtual Domain2 Domain() const = 0;
  /// Point on the surface at (u, v), part frame, mm.
  virtual Eigen::Vector3d Point(const Eigen::Vector2d& uv) const = 0;
  /// Unit normal at (u, v), pointing towards the head.
  virtual Eigen::Vector3d Normal(const Eigen::Vector2d& uv) const = 0;
  /// d Point / d(u, v) (columns: du, dv).
  virtual Eigen::Matrix<double, 3, 2> Jacobian(const Eigen::Vector2d& uv) const;
  /// Point and Jacobian at once (a kernel surface evaluates both in one call; the local
  /// projections of surface_walk.h need both at every iteration).
  virtual void PointAndJacobian(const Eigen::Vector2d& uv, Eigen::Vector3d& point,
                                Eigen::Matrix<double, 3, 2>& jacobian) const {
    point = Point(uv);
    jacobian = Jacobian(uv);
  }
  /// Closest point on the surface to `p` (part frame, mm). Global on every surface whose
  /// sheets can pass near each other (a closed wing's skins): never a local minimum from a
  /// far start.
  virtual SurfaceProjection Project(const Eigen::Vector3d& p) const;
  /// The same closest point, searched from `uv_start` first (a neighbouring point's foot):
  /// the start makes the search faster, it never decides which sheet the foot is on.
  virtual SurfaceProjection ProjectFrom(const Eigen::Vector3d& p,
                                        const Eigen::Vector2d& /*uv_start*/) const {
    return Project(p);
  }
  /// Where the line p + t*dir crosses the surface nearest to p; false if it does not.
  virtual bool IntersectLine(const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                             Eigen::Vector3d& hit) const;
  /// Grid resolution (cells along u and v) that tessellates the surface to `chord_tol_mm`.
  virtual Eigen::Vector2i TessellationCells(double chord_tol_mm) const;
};

/// Plane z = 0 of the part frame, normal +z, domain centred on the origin.
std::unique_ptr<Surface> MakePlane(double size_u_mm, double size_v_mm);

/// Cylinder with its axis parallel to part x. u = axial position, v = arc length around
/// the circumference measured from the crown (the point at the part origin). `outside`:
/// convex (axis at z = -r, normal outward); inside: concave (axis at z = +r, normal towards
/// the axis). Domain: u in [-length/2, length/2], v in [-arc/2, arc/2].
std::unique_ptr<Surface> MakeCylinder(double radius_mm, bool outside, double length_mm,
                                      double arc_length_mm);

/// Height field z = sum c[i][j] x^i y^j over a rectangle (x, y in mm, z in mm). u = x, v = y.
/// Coefficients are in millimetre units already (c[i][j] has units mm^(1-i-j)).
std::unique_ptr<Surface> MakePolynomialHeightField(const Eigen::Matrix4d& coeff_mm,
                                                   const Domain2& domain);

/// A triangle mesh used as a height field: u = x, v = y, z from the triangle above (x, y).
/// Normals are interpolated vertex normals. The mesh must be single-valued over (x, y).
std::unique_ptr<Surface> MakeMeshSurface(TriangleMesh mesh);

/// Tessellates a closed slab between the surface and the surface offset along the normal by
/// `offset_bottom_mm` .. `offset_top_mm` (a solid with side walls). Used for the mold
/// (e.g. -depth..0) and the preform (0..thickness).
TriangleMesh TessellateSlab(const Surface& surface, const Domain2& domain, double offset_bottom_mm,
                            double offset_top_mm, double chord_tol_mm);

/// The same slab cut into closed tiles no larger than `max_tile_mm` in (u, v), each tessellated
/// as finely as the whole slab would be. Collision checking uses tiles so that a broad phase
/// can drop the far parts of a large part by their bounding boxes.
std::vector<TriangleMesh> TessellateSlabTiles(const Surface& surface, const Domain2& domain,
                                              double offset_bottom_mm, double offset_top_mm,
                                              double chord_tol_mm, double max_tile_mm);

}  // namespace stitchsim::geom
