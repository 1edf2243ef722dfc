#pragma once
// FCL geometry for the collision world (docs/collision.md): primitives and part meshes, the
// oriented boxes of the broad phase, and the probe that makes an unsupported FCL pair an
// error. The box helpers are inline: they run for every candidate pair of every query.

#include <fcl/fcl.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "detail/collision_mjcf.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::sim::detail {

using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

/// An oriented box bounding a body at its current pose: its geometry's local bounding box
/// carried by the object's transform (tight for primitives and for part tiles, whose local
/// frame is the part frame). Metres.
struct Obb {
  Eigen::Vector3d c;  ///< centre
  Eigen::Matrix3d r;  ///< axes (columns)
  Eigen::Vector3d e;  ///< half extents along the axes
};

/// A box around a mesh along its principal axes (a tile of a curved slab: thin along its
/// normal, where the box of its part-frame bounds would hold all its slope).
Obb FitObb(const geom::TriangleMesh& mesh_m);

/// An FCL primitive of MuJoCo half sizes `s` (metres), its local box computed; null for a
/// plane.
Geometry MakePrimitive(MjcfShape shape, const Eigen::Vector3d& s);

/// An FCL BVH (OBBRSS) of a mesh in metres, its local box computed.
Geometry MakeMesh(const geom::TriangleMesh& mesh_m);

/// `mm` with every vertex multiplied by `scale`.
geom::TriangleMesh ScaledMesh(const geom::TriangleMesh& mm, double scale);

/// Empty when FCL really checks `a` against `b` (two overlapping canonical shapes of their
/// node types collide, two apart have a distance); else why not. FCL answers "no contact"
/// for a pair it does not support; this makes that an error instead.
std::string ProbeFclSupport(const fcl::CollisionGeometryd& a, const fcl::CollisionGeometryd& b);

inline fcl::Transform3d ToFcl(const Eigen::Isometry3d& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.linear();
  out.translation() = t.translation();
  return out;
}

/// The oriented box of `object` (its geometry's local box, or `fitted` in the geometry frame).
inline Obb ObbOf(const fcl::CollisionObjectd& object, const Obb* fitted) {
  const fcl::Transform3d& t = object.getTransform();
  if (fitted != nullptr) return {t * fitted->c, t.linear() * fitted->r, fitted->e};
  const auto& box = object.collisionGeometry()->aabb_local;
  return {t * (0.5 * (box.min_ + box.max_)), t.linear(), 0.5 * (box.max_ - box.min_)};
}

/// The world-axis box around an oriented box.
inline fcl::AABBd BoxOf(const Obb& o) {
  const Eigen::Vector3d half = o.r.cwiseAbs() * o.e;
  return fcl::AABBd(o.c - half, o.c + half);
}

/// fcl::AABB::distance, inline (the same arithmetic, so the same bits): the broad phase asks
/// it of millions of box pairs.
inline double BoxDistance(const fcl::AABBd& a, const fcl::AABBd& b) {
  double result = 0;
  for (int i = 0; i < 3; ++i) {
    if (a.min_[i] > b.max_[i]) {
      const double delta = b.max_[i] - a.min_[i];
      result += delta * delta;
    } else if (b.min_[i] > a.max_[i]) {
      const double delta = a.max_[i] - b.min_[i];
      result += delta * delta;
    }
  }
  return std::sqrt(result);
}

/// fcl::AABB::overlap, inline.
inline bool BoxesOverlap(const fcl::AABBd& a, const fcl::AABBd& b) {
  for (int i = 0; i < 3; ++i) {
    if (a.min_[i] > b.max_[i] || a.max_[i] < b.min_[i]) return false;
  }
  return true;
}

/// A lower bound on the distance between two oriented boxes: the largest gap between their
/// projections on the 15 separating-axis candidates (projection never lengthens a distance).
/// 0 when they may touch. Stops early once an axis shows a gap of at least `enough`.
inline double ObbGapLowerBound(const Obb& a, const Obb& b,
                               double enough = std::numeric_limits<double>::infinity()) {
  // In a's frame: b's axes are the columns of r, its centre is at t.
  const Eigen::Matrix3d r = a.r.transpose() * b.r;
  const Eigen::Vector3d t = a.r.transpose() * (b.c - a.c);
  const Eigen::Matrix3d abs_r = r.cwiseAbs();
  double gap = 0.0;
  for (int i = 0; i < 3; ++i) {
    gap = std::max(gap, std::abs(t[i]) - a.e[i] - b.e.dot(abs_r.row(i)));
  }
  if (gap >= enough) return gap;
  for (int j = 0; j < 3; ++j) {
    gap = std::max(gap, std::abs(t.dot(r.col(j))) - a.e.dot(abs_r.col(j)) - b.e[j]);
  }
  if (gap >= enough) return gap;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double len2 = 1.0 - r(i, j) * r(i, j);  // |a_i x b_j|^2
      if (len2 < 1e-12) continue;
      const double sep = std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j)) -
                         (a.e[i1] * abs_r(i2, j) + a.e[i2] * abs_r(i1, j)) -
                         (b.e[j1] * abs_r(i, j2) + b.e[j2] * abs_r(i, j1));
      gap = std::max(gap, sep / std::sqrt(len2));
    }
  }
  return gap;
}

}  // namespace stitchsim::sim::detail
