#pragma once
// Planar curves in a surface's (u, v) domain, millimetres, and their lift onto a surface
// with equal-arc-length sampling (seed 000 section 3.2.2).

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {

/// One smooth piece of a 2D curve, parametrised by t in [0, 1].
class CurveSegment {
 public:
  virtual ~CurveSegment() = default;
  virtual Eigen::Vector2d At(double t) const = 0;
  virtual Eigen::Vector2d Derivative(double t) const = 0;
  /// At(t) and Derivative(t) together (segments override it to share work, e.g. sin/cos).
  virtual void Evaluate(double t, Eigen::Vector2d& point, Eigen::Vector2d& derivative) const {
    point = At(t);
    derivative = Derivative(t);
  }
};

std::unique_ptr<CurveSegment> MakeLineSegment(Eigen::Vector2d from, Eigen::Vector2d to);
/// Elliptic arc: centre + (a cos th, b sin th) rotated by `rotation_rad`, th from start to end
/// (end < start runs clockwise). A circular arc has a == b.
std::unique_ptr<CurveSegment> MakeEllipticArc(Eigen::Vector2d centre, double a, double b,
                                              double rotation_rad, double start_rad,
                                              double end_rad);

/// A chain of segments joined end to start. Parameter: segment index + local t.
class Curve2 {
 public:
  void Add(std::unique_ptr<CurveSegment> segment, std::string label = {});
  std::size_t SegmentCount() const { return segments_.size(); }
  const CurveSegment& Segment(std::size_t i) const { return *segments_[i]; }
  const std::string& Label(std::size_t i) const { return labels_[i]; }
  bool Closed(double tol_mm = 1e-9) const;
  Eigen::Vector2d Start() const;
  Eigen::Vector2d End() const;

 private:
  std::vector<std::unique_ptr<CurveSegment>> segments_;
  std::vector<std::string> labels_;
};

/// A point of a path on a surface.
struct PathPoint {
  double arc_length_mm = 0.0;  ///< along the lifted (3D) path from its start
  std::size_t segment = 0;     ///< which segment of the 2D curve
  double t = 0.0;              ///< parameter within that segment
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< part frame, mm
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   ///< unit surface normal
};

/// A 2D curve lifted onto a surface, with an arc-length table for the 3D length.
class SurfacePath {
 public:
  /// Builds the arc-length table; `tolerance_mm` bounds the length error.
  SurfacePath(const Surface& surface, const Curve2& curve, double tolerance_mm = 1e-9);

  double Length() const { return total_length_mm_; }
  bool Closed() const { return closed_; }
  /// The point at arc length s (clamped to [0, Length()]).
  PathPoint AtArcLength(double s_mm) const;
  /// As AtArcLength(s_mm), with the first guess taken from `near`, a point this path
  /// returned (e.g. the previous stitch): fewer Newton steps on curves of varying speed.
  PathPoint AtArcLengthFrom(const PathPoint& near, double s_mm) const;
  /// The segment holding arc length s (clamped): AtArcLength(s_mm).segment without solving.
  std::size_t SegmentAtArcLength(double s_mm) const;
  /// The point at (segment, t).
  PathPoint At(std::size_t segment, double t) const;
  /// Arc length of the lifted path from (segment 0, t 0) to (segment, t).
  double ArcLengthAt(std::size_t segment, double t) const;
  const Curve2& Curve() const { return *curve_; }
  const Surface& SurfaceRef() const { return *surface_; }

 private:
  double SegmentLength(std::size_t segment, double t0, double t1) const;
  std::size_t KnotIntervalAt(std::size_t segment, double local_s_mm) const;
  PathPoint PointAt(std::size_t segment, double t, double s_mm) const;
  PathPoint SolveInKnotInterval(std::size_t segment, std::size_t knot, double s_mm,
                                const PathPoint* near) const;
  const Surface* surface_;
  const Curve2* curve_;
  bool closed_ = false;
  // Per segment: knots t_k and cumulative lengths at the knots.
  std::vector<std::vector<double>> knot_t_;
  std::vector<std::vector<double>> knot_s_;
  std::vector<double> segment_start_s_;
  double total_length_mm_ = 0.0;
};

/// The stitch count rule (seed 000): the integer n >= 1 whose l = length / n is closest to
/// the nominal length; ties go to the larger n (shorter stitches). Returns nullopt when the
/// path is shorter than half a nominal stitch or inputs are not positive and finite.
std::optional<int> StitchCount(double path_length_mm, double nominal_stitch_length_mm);

}  // namespace stitchsim::geom
