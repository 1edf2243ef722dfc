// geom::WalkOnSurface against closed-form geodesics (issue 26 item 4): on a cylinder (u along
// the axis, v the arc round it) a geodesic at angle a to the axis is the helix whose (u, v)
// runs on the straight line (cos a, sin a) s; on a sphere it is a great circle.
#include "stitchsim/geom/surface_walk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {
namespace {

double Angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

struct WalkError {
  double point_mm = 0.0;     ///< largest distance from the closed form
  double tangent_rad = 0.0;  ///< largest angle from the closed form's tangent
};

// Walks the cylinder from its crown in `steps` chained walks of `step_mm` (each restarting from
// the last one's end tangent, as the planner's course extensions and the tow walks do) and
// compares every end with the helix.
WalkError CylinderWalk(double radius_mm, bool outside, double angle_deg, double step_mm, int steps,
                       double max_substep_mm) {
  const auto s = MakeCylinder(radius_mm, outside, 2000.0, 1.9 * kPi * radius_mm);
  const double a = angle_deg * kPi / 180.0;
  const Eigen::Vector2d d_uv(std::cos(a), std::sin(a));
  WalkError e;
  for (const double sign : {1.0, -1.0}) {
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    Eigen::Vector3d dir = sign * (s->Jacobian(uv) * d_uv);
    for (int k = 1; k <= steps; ++k) {
      const SurfaceFoot f = WalkOnSurface(*s, uv, dir, step_mm, max_substep_mm);
      EXPECT_TRUE(f.converged);
      const Eigen::Vector2d exact_uv = sign * k * step_mm * d_uv;
      e.point_mm = std::max(e.point_mm, (f.point - s->Point(exact_uv)).norm());
      const Eigen::Vector3d exact_t = sign * (s->Jacobian(exact_uv) * d_uv);
      e.tangent_rad = std::max(e.tangent_rad, Angle(f.tangent, exact_t));
      uv = f.uv;
      dir = f.tangent;
    }
  }
  return e;
}

class CylinderGeodesic : public ::testing::TestWithParam<std::tuple<double, double>> {};

// +-175 mm in 5 mm walks of 0.5 mm substeps, as the planner's geodesic reference walks. The
// chord-carried walk this replaced bent in an S about the helix: 0.04 mm on R 350 at 60 deg,
// 0.17 mm on R 110.
TEST_P(CylinderGeodesic, ChainedWalksFollowTheHelix) {
  const auto [radius, angle] = GetParam();
  for (const bool outside : {true, false}) {
    const WalkError e = CylinderWalk(radius, outside, angle, 5.0, 35, 0.5);
    EXPECT_LT(e.point_mm, 1e-6) << "R " << radius << " at " << angle << " deg, outside " << outside;
    EXPECT_LT(e.tangent_rad, 1e-8) << "R " << radius << " at " << angle << " deg";
  }
}

// One long walk and coarse substeps (the offsets walk a course width in 20 substeps).
TEST_P(CylinderGeodesic, OneLongWalkFollowsTheHelix) {
  const auto [radius, angle] = GetParam();
  const WalkError e = CylinderWalk(radius, true, angle, 175.0, 1, 2.5);
  EXPECT_LT(e.point_mm, 1e-6) << "R " << radius << " at " << angle << " deg";
}

INSTANTIATE_TEST_SUITE_P(Radii, CylinderGeodesic,
                         ::testing::Combine(::testing::Values(75.0, 110.0, 350.0, 2000.0),
                                            ::testing::Values(0.0, 30.0, 60.0, 90.0)),
                         [](const auto& info) {
                           return "R" + std::to_string(static_cast<int>(std::get<0>(info.param))) +
                                  "_" + std::to_string(static_cast<int>(std::get<1>(info.param))) +
                                  "deg";
                         });

// A sphere of radius r in longitude / latitude: u = r lon, v = r lat.
class Sphere final : public Surface {
 public:
  explicit Sphere(double r) : r_(r) {}
  std::string Kind() const override { return "sphere"; }
  Domain2 Domain() const override {
    return {Eigen::Vector2d(-kPi * r_, -0.45 * kPi * r_),
            Eigen::Vector2d(kPi * r_, 0.45 * kPi * r_)};
  }
  Eigen::Vector3d Point(const Eigen::Vector2d& uv) const override { return r_ * Normal(uv); }
  Eigen::Vector3d Normal(const Eigen::Vector2d& uv) const override {
    const double lon = uv.x() / r_, lat = uv.y() / r_;
    return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
  }
  Eigen::Matrix<double, 3, 2> Jacobian(const Eigen::Vector2d& uv) const override {
    const double lon = uv.x() / r_, lat = uv.y() / r_;
    Eigen::Matrix<double, 3, 2> j;
    j.col(0) << -std::cos(lat) * std::sin(lon), std::cos(lat) * std::cos(lon), 0.0;
    j.col(1) << -std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat);
    return j;
  }

 private:
  double r_;
};

TEST(SphereGeodesic, WalkFollowsTheGreatCircle) {
  for (const double r : {60.0, 250.0}) {
    const Sphere s(r);
    const Eigen::Vector2d uv0(0.3 * r, 0.2 * r);
    const Eigen::Vector3d p0 = s.Point(uv0), e1 = p0 / r;
    const Eigen::Matrix<double, 3, 2> j = s.Jacobian(uv0);
    const Eigen::Vector3d w =
        (j.col(0).normalized() * std::cos(0.6) + j.col(1).normalized() * std::sin(0.6))
            .normalized();
    double worst = 0.0, worst_t = 0.0;
    Eigen::Vector2d uv = uv0;
    Eigen::Vector3d dir = w;
    const double step = 5.0;
    for (int k = 1; k * step <= 1.2 * r; ++k) {
      const SurfaceFoot f = WalkOnSurface(s, uv, dir, step, 0.5);
      ASSERT_TRUE(f.converged);
      const double phi = k * step / r;
      const Eigen::Vector3d exact = r * (std::cos(phi) * e1 + std::sin(phi) * w);
      const Eigen::Vector3d exact_t = -std::sin(phi) * e1 + std::cos(phi) * w;
      worst = std::max(worst, (f.point - exact).norm());
      worst_t = std::max(worst_t, Angle(f.tangent, exact_t));
      uv = f.uv;
      dir = f.tangent;
    }
    EXPECT_LT(worst, 1e-6) << "sphere R " << r;
    EXPECT_LT(worst_t, 1e-8) << "sphere R " << r;
  }
}

// Second order (at least) elsewhere: halving the substep cuts the error at least threefold on
// a saddle (a height field z = (x^2 - y^2) / 400, compared with a much finer walk).
TEST(SaddleGeodesic, WalkConvergesWithTheSubstep) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(2, 0) = 1.0 / 400.0;
  c(0, 2) = -1.0 / 400.0;
  const auto s = MakePolynomialHeightField(c, {{-200, -200}, {200, 200}});
  const Eigen::Vector2d uv0(-40.0, 10.0);
  const Eigen::Vector3d dir = s->Jacobian(uv0) * Eigen::Vector2d(1.0, 0.4);
  const Eigen::Vector3d fine = WalkOnSurface(*s, uv0, dir, 80.0, 0.01).point;
  const double e1 = (WalkOnSurface(*s, uv0, dir, 80.0, 1.0).point - fine).norm();
  const double e2 = (WalkOnSurface(*s, uv0, dir, 80.0, 0.5).point - fine).norm();
  EXPECT_LT(e1, 1e-3);
  EXPECT_GT(e1 / e2, 3.0) << e1 << " " << e2;
  RecordProperty("error_1mm", ::testing::PrintToString(e1));
  RecordProperty("error_half_mm", ::testing::PrintToString(e2));
}

}  // namespace
}  // namespace stitchsim::geom
