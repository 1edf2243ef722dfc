#pragma once
// Offset curves on a surface (seed 002, first method; docs/afp.md "Offset curves"). A fiber
// axis is projected onto any geom::Surface to make the reference curve; each point of a curve
// is then offset by d, n times, either by the paper's method (move along N x T, project back
// to the closest surface point) or by the corrected method (walk the surface geodesic normal
// to the curve until the walked length is d). Every step reports the paper's circular
// estimate (eq. 2) beside the distance measured along the surface (eq. 3). Part frame, mm.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "stitchsim/geom/surface.h"

namespace stitchsim::planner {

/// One defining point of a curve on the surface.
struct CurvePoint {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();        ///< surface parameter (mm)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< on the surface, part frame (mm)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   ///< unit surface normal N
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();  ///< unit curve tangent T, orthogonal to N
};
using SurfaceCurve = std::vector<CurvePoint>;

/// The fiber axis: a straight 3D segment, projected onto the surface along `projection`.
struct FiberAxis {
  Eigen::Vector3d start_mm = Eigen::Vector3d::Zero();      ///< part frame
  Eigen::Vector3d end_mm = Eigen::Vector3d::UnitX();       ///< part frame
  Eigen::Vector3d projection = -Eigen::Vector3d::UnitZ();  ///< projection vector V (any length)
};

/// A curve or family of curves, or why there is none.
struct ReferenceCurve {
  bool ok = false;
  std::string message;  ///< why not, when !ok
  SurfaceCurve points;  ///< ordered from the axis start to its end
};

/// Projects the fiber axis onto the surface along V and samples it so that no chord between
/// neighbouring points leaves the curve by more than `chord_tol_mm` (checked at midpoints).
/// Not ok if some point of the axis does not project onto the surface.
ReferenceCurve ProjectFiberAxis(const geom::Surface& surface, const FiberAxis& axis,
                                double chord_tol_mm);

enum class OffsetMethod {
  kPaper,      ///< seed 002: P + d (N x T), projected to the closest surface point
  kCorrected,  ///< walk the geodesic from P along N x T in substeps until the walked length is d
};

struct OffsetOptions {
  double distance_mm = 1.0;  ///< offset distance d (the tow width)
  int count = 1;             ///< offsets n
  OffsetMethod method = OffsetMethod::kPaper;
  double max_substep_mm = 0.5;  ///< corrected method: longest walking substep
  /// Measure every step's distance on the surface (OffsetStepReport::surface_distance_mm; the
  /// eq. 3 integral is most of an offset's cost); a planner that only needs the curves says no.
  bool measure = true;
};

/// What one offset step did, per defining point (index j of the curve).
struct OffsetStepReport {
  std::vector<double> eq2_error_mm;         ///< d (1 - psi / tan psi), psi between N_i and N_i+1
  std::vector<double> surface_distance_mm;  ///< curve i to i+1 on the surface (empty: !measure)
};

struct OffsetFamily {
  bool ok = false;
  std::string message;                  ///< why the family stopped early, when !ok
  std::vector<SurfaceCurve> curves;     ///< curves[0] = the reference, then one per offset
  std::vector<OffsetStepReport> steps;  ///< steps[i]: curves[i] -> curves[i + 1]
};

/// Offsets the reference `count` times. Stops (not ok, curves so far kept) when an offset
/// point leaves the surface's domain.
OffsetFamily OffsetCurves(const geom::Surface& surface, const SurfaceCurve& reference,
                          const OffsetOptions& options);

/// Accumulated error of the corresponding points j of a family (seed 002, Figs. 7 and 8).
struct OffsetDrift {
  double nominal_mm = 0.0;         ///< d * steps
  double surface_length_mm = 0.0;  ///< eq. 3: length on the surface through P_0 .. P_n
  double drift_mm = 0.0;           ///< nominal - surface length
  double eq2_total_mm = 0.0;       ///< sum of the eq. 2 estimates along the points
};
OffsetDrift MeasureDrift(const geom::Surface& surface, const OffsetFamily& family,
                         double distance_mm, std::size_t point_index);

/// Length of the surface curve that is the straight (u, v) segment from `a` to `b`, lifted
/// onto the surface and subdivided until the length changes by less than `rel_tol` (eq. 3,
/// never the chord). On a plane or a cylinder this is the geodesic distance.
double SurfaceLength(const geom::Surface& surface, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& b, double rel_tol = 1e-12);

/// Seed 002 eq. (2): offset error for a circular cross section, psi between the normals.
double CircularOffsetError(double distance_mm, const Eigen::Vector3d& n0,
                           const Eigen::Vector3d& n1);

/// Seed 002 eq. (4): laminate family angle error, theta - acos(R cos theta / (R + d)), rad.
double LaminateAngleError(double radius_mm, double distance_mm, double theta_rad);

}  // namespace stitchsim::planner
