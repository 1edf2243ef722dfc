// process::CoverageMap against closed forms: a rectangle filled exactly by straight courses on
// a plane has nothing bare or doubled; one course left out leaves its width x length bare; one
// course laid twice doubles its area; areas are surface areas (a cylinder's patch is its axial
// length x arc, an inclined plane's is its (u, v) area / cos of its slope); the band along the
// boundary is one tow width; a grid over budget is coarsened and says so.
#include "stitchsim/process/afp_coverage.h"

#include <gtest/gtest.h>

#include <cmath>

namespace stitchsim::process {
namespace {

constexpr double kW = 6.35;          // tow width, mm
constexpr double kCourse = 16 * kW;  // 101.6 mm
constexpr double kLength = 80 * kW;  // 508 mm: the ply's length along v

std::vector<Eigen::Vector2d> Rectangle(double u0, double v0, double u1, double v1) {
  return {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
}

// Course `c` (0-based) along v: 16 tows from u = c * 101.6, in segments of 50.8 mm.
void LayCourse(CoverageMap& map, int c, int first_line) {
  for (int s = 0; s < 10; ++s) {
    const double v0 = s * kLength / 10, v1 = (s + 1) * kLength / 10;
    for (int t = 0; t < 16; ++t) {
      const double u0 = c * kCourse + t * kW, u1 = u0 + kW;
      map.PaintQuad({Eigen::Vector2d(u0, v0), Eigen::Vector2d(u1, v0), Eigen::Vector2d(u1, v1),
                     Eigen::Vector2d(u0, v1)},
                    first_line + s);
    }
  }
  map.EndCourse();
}

CoverageMap PlaneMap(const geom::Surface& plane) {
  // The ply's box and a tow width around it, cells of w / 4 (ply edges fall on cell edges).
  return CoverageMap(plane, Eigen::Vector2d(-kW, -kW),
                     Eigen::Vector2d(4 * kCourse + kW, kLength + kW), kW / 4);
}

TEST(AfpCoverage, RectangleFilledExactlyHasNothingBareOrDoubled) {
  const auto plane = geom::MakePlane(2000, 2000);
  CoverageMap map = PlaneMap(*plane);
  EXPECT_FALSE(map.Grid().coarsened);
  EXPECT_NEAR(map.Grid().cell_uv.x(), kW / 4, 1e-12);
  for (int c = 0; c < 4; ++c) LayCourse(map, c, 100 * (c + 1));
  const PlyCoverage cov = MeasurePly(map, Rectangle(0, 0, 4 * kCourse, kLength), kW);
  EXPECT_NEAR(cov.ply_area_mm2, 4 * kCourse * kLength, 1e-6);
  EXPECT_NEAR(cov.ply_area_beyond_band_mm2, (4 * kCourse - 2 * kW) * (kLength - 2 * kW), 1e-6);
  EXPECT_EQ(cov.bare_mm2, 0.0);
  EXPECT_EQ(cov.doubled_mm2, 0.0);
  EXPECT_EQ(cov.laid_outside_mm2, 0.0);
  EXPECT_EQ(map.Count(map.Grid().nu / 2, map.Grid().nv / 2), 1);
}

TEST(AfpCoverage, TowsOfOneCourseNeverOverlapEachOther) {
  const auto plane = geom::MakePlane(2000, 2000);
  CoverageMap map = PlaneMap(*plane);
  // The same quad painted twice in one course (neighbouring tows sharing an edge, a line
  // retraced) counts once.
  const std::array<Eigen::Vector2d, 4> q = {Eigen::Vector2d(0, 0), Eigen::Vector2d(kW, 0),
                                            Eigen::Vector2d(kW, kW), Eigen::Vector2d(0, kW)};
  map.PaintQuad(q, 1);
  map.PaintQuad(q, 2);
  map.EndCourse();
  const PlyCoverage cov = MeasurePly(map, Rectangle(0, 0, 4 * kCourse, kLength), kW);
  EXPECT_EQ(cov.doubled_mm2, 0.0);
  EXPECT_NEAR(cov.ply_area_mm2 - cov.bare_mm2, kW * kW, 1e-6);
}

TEST(AfpCoverage, CourseLeftOutIsBareOverItsWidthTimesLength) {
  const auto plane = geom::MakePlane(2000, 2000);
  CoverageMap map = PlaneMap(*plane);
  for (int c : {0, 1, 3}) LayCourse(map, c, 100 * (c + 1));
  const PlyCoverage cov = MeasurePly(map, Rectangle(0, 0, 4 * kCourse, kLength), kW);
  EXPECT_NEAR(cov.bare_mm2, kCourse * kLength, 1e-6);
  EXPECT_NEAR(cov.bare_beyond_band_mm2, kCourse * (kLength - 2 * kW), 1e-6);
  EXPECT_EQ(cov.doubled_mm2, 0.0);
  // The worst bare patch lies in the missing course; the nearest laid cell is a neighbour's.
  EXPECT_GT(cov.worst_bare_uv.x(), 2 * kCourse);
  EXPECT_LT(cov.worst_bare_uv.x(), 3 * kCourse);
  const int line = map.NearestLine(cov.worst_bare_uv);
  EXPECT_TRUE((line >= 200 && line < 210) || (line >= 400 && line < 410)) << line;
}

TEST(AfpCoverage, CourseLaidTwiceIsDoubledOverItsArea) {
  const auto plane = geom::MakePlane(2000, 2000);
  CoverageMap map = PlaneMap(*plane);
  for (int c = 0; c < 4; ++c) LayCourse(map, c, 100 * (c + 1));
  LayCourse(map, 1, 900);
  const PlyCoverage cov = MeasurePly(map, Rectangle(0, 0, 4 * kCourse, kLength), kW);
  EXPECT_NEAR(cov.doubled_mm2, kCourse * kLength, 1e-6);
  EXPECT_NEAR(cov.doubled_beyond_band_mm2, kCourse * (kLength - 2 * kW), 1e-6);
  EXPECT_EQ(cov.bare_mm2, 0.0);
  EXPECT_GT(cov.worst_doubled_uv.x(), kCourse);
  EXPECT_LT(cov.worst_doubled_uv.x(), 2 * kCourse);
  // The second laying is the last to paint the doubled cells.
  const int line = map.NearestLine(cov.worst_doubled_uv);
  EXPECT_GE(line, 900);
  EXPECT_LT(line, 910);
}

TEST(AfpCoverage, MaterialPastTheBoundaryIsLaidOutside) {
  const auto plane = geom::MakePlane(2000, 2000);
  CoverageMap map = PlaneMap(*plane);
  for (int c = 0; c < 4; ++c) LayCourse(map, c, 100 * (c + 1));
  // The ply is one course narrower than what was laid: the last course lies outside, its
  // part more than a tow width from the edge beyond the band.
  const PlyCoverage cov = MeasurePly(map, Rectangle(0, 0, 3 * kCourse, kLength), kW);
  EXPECT_NEAR(cov.laid_outside_mm2, kCourse * kLength, 1e-6);
  EXPECT_NEAR(cov.laid_outside_beyond_band_mm2, (kCourse - kW) * kLength, 1e-6);
}

TEST(AfpCoverage, CylinderPatchAreaIsAxialLengthTimesArc) {
  // u axial, v arc length: a patch's area is its (u, v) area although the cells are curved.
  const auto cylinder = geom::MakeCylinder(300, true, 2000, 1800);
  CoverageMap map(*cylinder, Eigen::Vector2d(-200, -400), Eigen::Vector2d(200, 400), kW / 4);
  const PlyCoverage cov = MeasurePly(map, Rectangle(-100, -300, 100, 300), kW);
  EXPECT_NEAR(cov.ply_area_mm2, 200.0 * 600.0, 1e-3 * 200 * 600);
  EXPECT_NEAR(cov.bare_mm2, cov.ply_area_mm2, 1e-9);
}

TEST(AfpCoverage, CellsAreWeightedBySurfaceAreaOnAnInclinedPlane) {
  // z = 0.75 x: |Su x Sv| = sqrt(1 + 0.75^2) = 1.25.
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(1, 0) = 0.75;
  const auto incline = geom::MakePolynomialHeightField(
      c, geom::Domain2{Eigen::Vector2d(-500, -500), Eigen::Vector2d(500, 500)});
  CoverageMap map(*incline, Eigen::Vector2d(-200, -200), Eigen::Vector2d(200, 200), kW / 4);
  const PlyCoverage cov = MeasurePly(map, Rectangle(-100, -100, 100, 100), kW);
  // Edge cells count by their centre: within a row of cells along the perimeter.
  EXPECT_NEAR(cov.ply_area_mm2, 1.25 * 200 * 200, 1e-3 * 1.25 * 200 * 200);
}

TEST(AfpCoverage, GridOverBudgetIsCoarsened) {
  const auto plane = geom::MakePlane(4000, 4000);
  CoverageMap map(*plane, Eigen::Vector2d(-1000, -1000), Eigen::Vector2d(1000, 1000), kW / 4,
                  100'000);
  EXPECT_TRUE(map.Grid().coarsened);
  EXPECT_LE(static_cast<std::size_t>(map.Grid().nu) * static_cast<std::size_t>(map.Grid().nv),
            100'000U);
  const PlyCoverage cov = MeasurePly(map, Rectangle(-500, -500, 500, 500), kW);
  EXPECT_NEAR(cov.ply_area_mm2, 1e6, 0.02 * 1e6);
}

}  // namespace
}  // namespace stitchsim::process
