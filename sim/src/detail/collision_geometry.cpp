#include "detail/collision_geometry.h"

#include <Eigen/Eigenvalues>
#include <vector>

namespace stitchsim::sim::detail {
namespace {

// A closed box as a mesh (for the support probe).
geom::TriangleMesh BoxMesh(double h) {
  geom::TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h);
  }
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f) m.triangles.emplace_back(t[0], t[1], t[2]);
  return m;
}

std::string ProbePair(const Geometry& a, const Geometry& b) {
  fcl::CollisionObjectd oa(a, fcl::Transform3d::Identity());
  fcl::CollisionObjectd ob(b, fcl::Transform3d::Identity());
  fcl::CollisionRequestd creq(1, true);
  fcl::CollisionResultd cres;
  fcl::collide(&oa, &ob, creq, cres);
  if (!cres.isCollision()) return "overlapping shapes reported clear";
  fcl::Transform3d far = fcl::Transform3d::Identity();
  far.translation() = fcl::Vector3d(3.0, 0.0, 0.0);
  ob.setTransform(far);
  ob.computeAABB();
  fcl::DistanceRequestd dreq;
  fcl::DistanceResultd dres;
  fcl::distance(&oa, &ob, dreq, dres);
  if (!(dres.min_distance > 1.0 && dres.min_distance < 3.0)) return "distance query failed";
  return {};
}

Geometry ProbeShape(const fcl::CollisionGeometryd& g) {
  if (g.getObjectType() == fcl::OT_BVH) return MakeMesh(BoxMesh(0.1));
  switch (g.getNodeType()) {
    case fcl::GEOM_BOX:
      return std::make_shared<fcl::Boxd>(0.2, 0.2, 0.2);
    case fcl::GEOM_SPHERE:
      return std::make_shared<fcl::Sphered>(0.1);
    case fcl::GEOM_CAPSULE:
      return std::make_shared<fcl::Capsuled>(0.1, 0.2);
    case fcl::GEOM_CYLINDER:
      return std::make_shared<fcl::Cylinderd>(0.1, 0.2);
    default:
      return nullptr;
  }
}

}  // namespace

Obb FitObb(const geom::TriangleMesh& mesh_m) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : mesh_m.vertices) mean += v;
  mean /= static_cast<double>(std::max<std::size_t>(1, mesh_m.vertices.size()));
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& v : mesh_m.vertices) cov += (v - mean) * (v - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Matrix3d r = eig.eigenvectors();
  if (r.determinant() < 0) r.col(0) = -r.col(0);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& v : mesh_m.vertices) {
    const Eigen::Vector3d p = r.transpose() * (v - mean);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {mean + r * (0.5 * (lo + hi)), r, 0.5 * (hi - lo)};
}

Geometry MakePrimitive(MjcfShape shape, const Eigen::Vector3d& s) {
  Geometry g;
  switch (shape) {
    case MjcfShape::kBox:
      g = std::make_shared<fcl::Boxd>(2 * s.x(), 2 * s.y(), 2 * s.z());
      break;
    case MjcfShape::kSphere:
      g = std::make_shared<fcl::Sphered>(s.x());
      break;
    case MjcfShape::kCapsule:
      g = std::make_shared<fcl::Capsuled>(s.x(), 2 * s.y());
      break;
    case MjcfShape::kCylinder:
      g = std::make_shared<fcl::Cylinderd>(s.x(), 2 * s.y());
      break;
    case MjcfShape::kPlane:
      return nullptr;
  }
  g->computeLocalAABB();  // the model reads it before any FCL object (which would compute it)
  return g;
}

Geometry MakeMesh(const geom::TriangleMesh& mesh_m) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> points(mesh_m.vertices.begin(), mesh_m.vertices.end());
  std::vector<fcl::Triangle> tris;
  tris.reserve(mesh_m.triangles.size());
  for (const auto& t : mesh_m.triangles) {
    tris.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                      static_cast<std::size_t>(t[2]));
  }
  model->beginModel(static_cast<int>(tris.size()), static_cast<int>(points.size()));
  model->addSubModel(points, tris);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

geom::TriangleMesh ScaledMesh(const geom::TriangleMesh& mm, double scale) {
  geom::TriangleMesh out = mm;
  for (auto& v : out.vertices) v *= scale;
  return out;
}

std::string ProbeFclSupport(const fcl::CollisionGeometryd& a, const fcl::CollisionGeometryd& b) {
  const Geometry pa = ProbeShape(a), pb = ProbeShape(b);
  return pa && pb ? ProbePair(pa, pb) : "shape type not mapped";
}

}  // namespace stitchsim::sim::detail
