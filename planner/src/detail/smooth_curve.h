#pragma once
// Private to the ply planner: a course's centre curve as a C2 function of its length (issue 26
// item 3). The curve's defining points (a projected fibre axis sampled to a chord tolerance,
// an offset, a geodesic walk) are joined by a clamped cubic spline of (u, v) over the chord
// length, its end slopes the end points' tangents, instead of straight (u, v) segments whose
// kinks at every point read as steering.

#include <Eigen/Core>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/planner/offset_curves.h"

namespace stitchsim::planner::detail {

class SmoothCurve {
 public:
  /// Through the points of `c` (points closer than 1e-6 mm to the previous one are dropped).
  SmoothCurve(const geom::Surface& surface, const SurfaceCurve& c);
  /// Chord length through the points (mm); the parameter s runs over [0, Length()].
  double Length() const { return s_.empty() ? 0.0 : s_.back(); }
  /// (u, v) at s (clamped to the curve).
  Eigen::Vector2d Uv(double s) const;
  /// d(u, v)/ds at s.
  Eigen::Vector2d Slope(double s) const;

 private:
  std::size_t Piece(double s) const;

  std::vector<double> s_;
  std::vector<Eigen::Vector2d> uv_;
  std::vector<Eigen::Vector2d> m_;  ///< second derivatives at the points
};

}  // namespace stitchsim::planner::detail
