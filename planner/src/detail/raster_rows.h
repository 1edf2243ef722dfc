#pragma once
// Private pieces of the raster planner shared by the plan and the writer: stepping along a
// row at an exact 3D chord, and the tool frame of a stitch.

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <string>

#include "stitchsim/geom/rotation.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::planner::detail {

// Shares of a raster run's time per row piece (RasterOptions::progress): counting its
// stitches, building its passes, writing them. Measured on the whole wing cover (2590 rows,
// 1.66 million stitches; jump and serpentine): about 0.2 s, 0.2-0.4 s and 2.2 s.
inline constexpr double kProgressCountShare = 0.1;
inline constexpr double kProgressPassShare = 0.1;
inline constexpr double kProgressWriteShare = 0.8;

/// A number in the plan's notes and the programme's comments: six decimals.
inline std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6f", v);
  return buf;
}

/// Steps along a row (v fixed) at an exact 3D chord of `pitch`.
class RowStepper {
 public:
  RowStepper(const geom::Surface& s, double pitch) : s_(s), pitch_(pitch) {}
  /// u of the point one pitch (chord) from u in direction dir (+1/-1).
  double Next(double u, double v, double dir) const {
    const Eigen::Vector3d p = s_.Point({u, v});
    const double speed = s_.Jacobian({u, v}).col(0).norm();
    double du = pitch_ / std::max(speed, 1e-9);
    for (int it = 0; it < 3; ++it) {
      const double d = (s_.Point({u + dir * du, v}) - p).norm();
      if (d <= 0) break;
      du *= pitch_ / d;
    }
    return u + dir * du;
  }
  /// Stitches that fit in [a, b] starting at a (dir > 0) or at b (dir < 0); `u_last`, if
  /// given, gets the u of the last one (the start end when none fits).
  long Count(double a, double b, double v, double dir = 1.0, double* u_last = nullptr) const {
    long n = 0;
    double u = dir > 0 ? a : b;
    while (true) {
      const double next = Next(u, v, dir);
      if (next > b + 1e-9 || next < a - 1e-9) break;
      u = next;
      ++n;
    }
    if (u_last != nullptr) *u_last = u;
    return n;
  }

 private:
  const geom::Surface& s_;
  double pitch_;
};

/// The tool frame of a stitch at (u, v) on a row run in direction dir: z the surface normal,
/// y along the row.
inline Eigen::Matrix3d StitchFrame(const geom::Surface& s, double u, double v, double dir) {
  const Eigen::Vector2d uv(u, v);
  const Eigen::Vector3d t = dir * s.Jacobian(uv).col(0);
  return geom::FrameFromNormalAndDirection(s.Normal(uv), t).value_or(Eigen::Matrix3d::Identity());
}

}  // namespace stitchsim::planner::detail
