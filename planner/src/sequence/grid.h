#pragma once
// A uniform grid over tow quads in a surface's (u, v), for the overlap queries of the
// precedence network (precedence.cpp). Private to the planner.
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/planner/sequence/precedence.h"

namespace stitchsim::planner::detail {

/// Area (uv units^2) of convex quad `subject` inside convex counter-clockwise quad `clip`.
double ClippedArea(const CourseFootprint::Quad& subject, const CourseFootprint::Quad& clip);
/// |Su x Sv| at the quad's centre: mm^2 of surface per uv unit^2.
double QuadAreaElement(const geom::Surface& s, const CourseFootprint::Quad& q);

/// Quads of whole courses, bucketed by cell; queries return, per course met, the surface
/// area it shares with the query course (more than zero only).
class QuadGrid {
 public:
  QuadGrid(const geom::Surface& surface, const std::vector<CourseFootprint>& footprints,
           double cell)
      : surface_(surface), fp_(footprints), cell_(cell) {}

  void Insert(int course) {
    const auto& quads = fp_[static_cast<std::size_t>(course)].quads;
    for (int q = 0; q < static_cast<int>(quads.size()); ++q) {
      ForCells(quads[static_cast<std::size_t>(q)], [&](std::int64_t key) {
        cells_[key].push_back({course, q});
      });
    }
  }
  void Clear() { cells_.clear(); }

  /// Calls `visit(other, area_mm2)` for every course in the grid sharing area with `course`
  /// (each once, after all its area is summed), skipping courses for which skip(other).
  template <typename Skip, typename Visit>
  void Query(int course, Skip skip, Visit visit) {
    const auto& quads = fp_[static_cast<std::size_t>(course)].quads;
    area_.clear();
    for (const auto& qa : quads) {
      const double da = QuadAreaElement(surface_, qa);
      seen_.clear();
      ForCells(qa, [&](std::int64_t key) {
        const auto it = cells_.find(key);
        if (it == cells_.end()) return;
        for (const Ref& r : it->second) {
          if (skip(r.course)) continue;
          const std::uint64_t id =
              (static_cast<std::uint64_t>(r.course) << 24) ^ static_cast<std::uint64_t>(r.quad);
          if (!seen_.insert(id).second) continue;
          const auto& qb =
              fp_[static_cast<std::size_t>(r.course)].quads[static_cast<std::size_t>(r.quad)];
          const double a = ClippedArea(qa, qb) * da;
          if (a > 0.0) area_[r.course] += a;
        }
      });
    }
    for (const auto& [other, a] : area_) visit(other, a);
  }

 private:
  struct Ref {
    int course, quad;
  };
  template <typename F>
  void ForCells(const CourseFootprint::Quad& q, F f) {
    Eigen::Vector2d lo = q.uv[0], hi = q.uv[0];
    for (int i = 1; i < 4; ++i) {
      lo = lo.cwiseMin(q.uv[i]);
      hi = hi.cwiseMax(q.uv[i]);
    }
    const auto i0 = static_cast<std::int64_t>(std::floor(lo.x() / cell_));
    const auto i1 = static_cast<std::int64_t>(std::floor(hi.x() / cell_));
    const auto j0 = static_cast<std::int64_t>(std::floor(lo.y() / cell_));
    const auto j1 = static_cast<std::int64_t>(std::floor(hi.y() / cell_));
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j) f((i << 32) ^ (j & 0xffffffff));
  }

  const geom::Surface& surface_;
  const std::vector<CourseFootprint>& fp_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<Ref>> cells_;
  std::unordered_set<std::uint64_t> seen_;
  std::map<int, double> area_;
};

}  // namespace stitchsim::planner::detail
