#pragma once
// Laminate family curves (seed 002, second method; docs/afp.md): from a point on offset curve
// i, a straight segment at the laminate angle theta to the curve's tangent (T turned about N
// by theta), cut with curve i + 1 in the plane (O, N); repeated across a family of offset
// curves. The paper's construction meets each next curve at an angle that differs from theta
// (eq. 4); the corrected construction turns each segment so that the curve through its
// crossings meets every offset curve at theta. Part frame, mm; angles in radians.

#include <string>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/planner/offset_curves.h"

namespace stitchsim::planner {

struct LaminateOptions {
  double theta_rad = 0.0;       ///< laminate family angle, from T towards N x T
  bool corrected = false;       ///< false: the paper's construction
  double tolerance_rad = 1e-5;  ///< corrected: crossing angle solved to this
};

/// Where the laminate curve meets offset curve `curve`.
struct LaminateCrossing {
  std::size_t curve = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< on the surface, part frame (mm)
  double leave_rad = 0.0;   ///< angle of the segment leaving, from the curve's tangent
  double arrive_rad = 0.0;  ///< angle of the segment arriving, from the curve's tangent
  /// Angle of the laminate curve itself: the mean of leave and arrive inside; at the ends the
  /// segment's angle mirrored about the neighbouring crossing's turn.
  double crossing_rad = 0.0;
  /// Eq. 4 predicted from the previous crossing (its curve as a circle of its geodesic radius).
  double eq4_error_rad = 0.0;
};

struct LaminateCurve {
  bool ok = false;
  std::string message;                      ///< why it stopped early, when !ok
  std::vector<LaminateCrossing> crossings;  ///< one per offset curve reached
};

/// The laminate family curve from point `start_index` of `curves[0]` across all the curves
/// (an OffsetFamily's curves, in order). Stops (not ok) where a plane misses the next curve.
LaminateCurve LaminateFamilyCurve(const geom::Surface& surface,
                                  const std::vector<SurfaceCurve>& curves, std::size_t start_index,
                                  const LaminateOptions& options);

}  // namespace stitchsim::planner
