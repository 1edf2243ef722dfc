// Laminate family curves (seed 002, second method) on concentric circles in a plane, where
// eq. 4 is exact: the paper's construction arrives at each next curve off theta by eq. 4
// (about 1 deg in the seed's worst case: d 0.635 cm, R 63.5 cm, theta 30 deg); the corrected
// construction keeps the curve's crossing angle at theta within 0.05 deg.
#include "stitchsim/planner/laminate_family.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "offset_fixtures.h"
#include "stitchsim/common/units.h"

namespace stitchsim::planner {
namespace {

// Clockwise arc of radius r about the origin from +30 to -30 deg, a point every ~1 mm: its
// N x T points outwards, so its offsets are the circles r + k d.
SurfaceCurve ClockwiseArc(double r) {
  SurfaceCurve c;
  const int n = static_cast<int>(r * 60 * kDeg);
  for (int k = 0; k <= n; ++k) {
    const double phi = (30.0 - 60.0 * k / n) * kDeg;
    CurvePoint p;
    p.position = Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), 0);
    p.uv = p.position.head<2>();
    p.normal = Eigen::Vector3d::UnitZ();
    p.tangent = Eigen::Vector3d(std::sin(phi), -std::cos(phi), 0);
    c.push_back(p);
  }
  return c;
}

struct Fixture {
  std::unique_ptr<geom::Surface> plane = geom::MakePlane(3000, 3000);
  OffsetFamily family;
  Fixture(double r, double d, int n) {
    OffsetOptions o;
    o.distance_mm = d;
    o.count = n;
    family = OffsetCurves(*plane, ClockwiseArc(r), o);
  }
};

double WorstCrossingError(const LaminateCurve& l, double theta) {
  double worst = 0;
  for (const LaminateCrossing& c : l.crossings) {
    worst = std::max(worst, std::abs(c.crossing_rad - theta));
  }
  return worst;
}

TEST(LaminateFamily, PaperConstructionMissesThetaByEq4) {
  constexpr double r = 635, d = 6.35, theta = 30 * kDeg;  // seed 002's worst case, in mm
  Fixture fx(r, d, 12);
  ASSERT_TRUE(fx.family.ok) << fx.family.message;
  LaminateOptions o;
  o.theta_rad = theta;
  const LaminateCurve l = LaminateFamilyCurve(*fx.plane, fx.family.curves, 60, o);
  ASSERT_TRUE(l.ok) << l.message;
  ASSERT_EQ(l.crossings.size(), 13u);
  for (std::size_t i = 1; i < l.crossings.size(); ++i) {
    const LaminateCrossing& c = l.crossings[i];
    const double closed = LaminateAngleError(r + (i - 1) * d, d, theta);
    EXPECT_NEAR(theta - c.arrive_rad, closed, 0.002 * kDeg) << "crossing " << i;
    EXPECT_NEAR(c.eq4_error_rad, closed, 0.002 * kDeg) << "crossing " << i;
    EXPECT_NEAR(std::hypot(c.position.x(), c.position.y()), r + i * d, 1e-3);
    if (i + 1 < l.crossings.size()) {
      EXPECT_NEAR(c.leave_rad, theta, 1e-9);
    }
  }
  std::cout << "paper's laminate construction, first crossing: "
            << (theta - l.crossings[1].arrive_rad) / kDeg << " deg (eq. 4 "
            << l.crossings[1].eq4_error_rad / kDeg << ", seed: about 1.0); the curve's worst "
            << WorstCrossingError(l, theta) / kDeg << " deg\n";
}

TEST(LaminateFamily, CorrectedConstructionKeepsTheCrossingAngle) {
  constexpr double r = 635, d = 6.35, theta = 30 * kDeg;
  Fixture fx(r, d, 12);
  ASSERT_TRUE(fx.family.ok) << fx.family.message;
  LaminateOptions o;
  o.theta_rad = theta;
  o.corrected = true;
  const LaminateCurve l = LaminateFamilyCurve(*fx.plane, fx.family.curves, 60, o);
  ASSERT_TRUE(l.ok) << l.message;
  ASSERT_EQ(l.crossings.size(), 13u);
  const double worst = WorstCrossingError(l, theta);
  EXPECT_LT(worst, 0.05 * kDeg);
  std::cout << "corrected laminate construction: worst crossing error " << worst / kDeg << " deg\n";
}

TEST(LaminateFamily, OnACurvedSurfaceTheCorrectedCurveKeepsTheAngle) {
  // The inflected surface of the offset tests (z = y^3 / 20), offset curves 0.635 mm apart
  // from a reference along x; theta 30 deg.
  const auto surf = testing::InflectedSurface(20);
  FiberAxis axis;
  axis.start_mm = Eigen::Vector3d(-18, -3.5, 50);
  axis.end_mm = Eigen::Vector3d(18, -3.5, 50);
  const ReferenceCurve ref = ProjectFiberAxis(*surf, axis, 0.001);
  ASSERT_TRUE(ref.ok) << ref.message;
  OffsetOptions o;
  o.distance_mm = 0.635;
  o.count = 12;
  o.method = OffsetMethod::kCorrected;
  const OffsetFamily f = OffsetCurves(*surf, ref.points, o);
  ASSERT_TRUE(f.ok) << f.message;
  LaminateOptions lo;
  lo.theta_rad = 30 * kDeg;
  const LaminateCurve paper = LaminateFamilyCurve(*surf, f.curves, 2, lo);
  lo.corrected = true;
  const LaminateCurve corrected = LaminateFamilyCurve(*surf, f.curves, 2, lo);
  ASSERT_TRUE(paper.ok) << paper.message;
  ASSERT_TRUE(corrected.ok) << corrected.message;
  EXPECT_EQ(corrected.crossings.size(), 13u);
  EXPECT_LT(WorstCrossingError(corrected, lo.theta_rad), 0.05 * kDeg);
  for (const LaminateCrossing& x : corrected.crossings) {
    EXPECT_LT(std::abs(surf->Project(x.position).signed_distance_mm), 1e-9);
  }
  std::cout << "z = y^3/20, d 0.635, theta 30: worst crossing error, paper "
            << WorstCrossingError(paper, lo.theta_rad) / kDeg << " deg, corrected "
            << WorstCrossingError(corrected, lo.theta_rad) / kDeg << " deg\n";
}

TEST(LaminateFamily, APlaneMissingTheNextCurveIsAStatus) {
  Fixture fx(635, 6.35, 3);
  ASSERT_TRUE(fx.family.ok);
  LaminateOptions o;
  o.theta_rad = 30 * kDeg;
  // From the last point the segment runs past the ends of the next arcs.
  const LaminateCurve l =
      LaminateFamilyCurve(*fx.plane, fx.family.curves, fx.family.curves[0].size() - 1, o);
  EXPECT_FALSE(l.ok);
  EXPECT_EQ(l.message, "laminate family: the plane misses curve 1");
  EXPECT_FALSE(LaminateFamilyCurve(*fx.plane, {}, 0, o).ok);
}

}  // namespace
}  // namespace stitchsim::planner
