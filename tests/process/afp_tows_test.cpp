// Tow placement across the compaction roller (process/afp_tows.h) against closed forms: on a
// plane the boundaries are straight offsets; around a cylinder they are arcs of the offset's
// length (the walk measures along the surface, not the chord).

#include "stitchsim/process/afp_tows.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "../geom/seed_wing.h"
#include "stitchsim/geom/naca.h"
#include "stitchsim/geom/wing_surface.h"

namespace stitchsim::process {
namespace {

TEST(afp_tows, CentresAreSymmetricAboutTheToolPoint) {
  const TowLayout l{16, 6.35};
  EXPECT_DOUBLE_EQ(TowCentreOffset(l, 1), -7.5 * 6.35);
  EXPECT_DOUBLE_EQ(TowCentreOffset(l, 16), 7.5 * 6.35);
  EXPECT_DOUBLE_EQ(TowCentreOffset(TowLayout{3, 2.0}, 2), 0.0);
  EXPECT_EQ(AllTows(l), 0xFFFFu);
  EXPECT_EQ(AllTows(TowLayout{64, 1.0}), ~std::uint64_t{0});
}

TEST(afp_tows, OnAPlaneTheBoundariesAreStraightOffsetsAlongToolX) {
  const auto plane = geom::MakePlane(1000, 1000);
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  // Travel along part +y, head axis +z: tool x = y cross z = +x.
  tool.linear().col(0) = Eigen::Vector3d::UnitX();
  tool.linear().col(1) = Eigen::Vector3d::UnitY();
  tool.linear().col(2) = Eigen::Vector3d::UnitZ();
  tool.translation() = Eigen::Vector3d(10, 20, 0);
  for (int k : {15, 16}) {
    const TowLayout l{k, 6.35};
    const TowCross c = TowsAt(*plane, tool, l, nullptr);
    ASSERT_TRUE(c.ok);
    ASSERT_EQ(c.boundary.size(), static_cast<std::size_t>(k) + 1);
    for (int b = 0; b <= k; ++b) {
      const Eigen::Vector3d want(10 + (b - 0.5 * k) * 6.35, 20, 0);
      EXPECT_LT((c.boundary[static_cast<std::size_t>(b)] - want).norm(), 1e-9) << k << " " << b;
    }
  }
}

TEST(afp_tows, AroundACylinderTheBoundariesAreArcsOfTheirOffset) {
  const double r = 150.0;  // a tight radius: the chord would be 1.4 mm short at the edge tow
  const auto cyl = geom::MakeCylinder(r, true, 1000, 600);
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  // Axial travel (+x) at the crown, head axis +z: tool x = x cross z = -y.
  tool.linear().col(0) = -Eigen::Vector3d::UnitY();
  tool.linear().col(1) = Eigen::Vector3d::UnitX();
  tool.linear().col(2) = Eigen::Vector3d::UnitZ();
  tool.translation() = Eigen::Vector3d(5, 0, 0);
  const TowLayout l{16, 6.35};
  const Eigen::Vector2d hint(4, 1);
  const TowCross c = TowsAt(*cyl, tool, l, &hint);
  ASSERT_TRUE(c.ok);
  for (int b = 0; b <= 16; ++b) {
    const double s = (b - 8) * 6.35;  // arc length, towards -y
    const Eigen::Vector3d want(5, -r * std::sin(s / r), -r + r * std::cos(s / r));
    EXPECT_LT((c.boundary[static_cast<std::size_t>(b)] - want).norm(), 1e-6) << b;
  }
}

// Issue 26 item 1: a ply of n tows lays the head's middle n (docs/program-format.md, "Tows"),
// numbered as the head numbers them; on a plane its boundaries are the head's, at
// (b - k / 2) w, and its centre is the tool point (k - n even) or w / 2 to its left (odd).
TEST(afp_tows, ANarrowPlyLaysTheHeadsMiddleTows) {
  const TowLayout head{16, 6.35};
  struct Case {
    int n, first;
    double centre_mm;
  };
  for (const Case c : {Case{16, 1, 0.0}, Case{8, 5, 0.0}, Case{12, 3, 0.0}, Case{7, 5, -3.175},
                       Case{1, 8, -3.175}, Case{15, 1, -3.175}}) {
    SCOPED_TRACE(c.n);
    const TowBand band = PlyTowBand(head, c.n);
    EXPECT_EQ(band.first, c.first);
    EXPECT_EQ(band.count, c.n);
    EXPECT_NEAR(BandCentreOffset(head, band), c.centre_mm, 1e-12);
    EXPECT_EQ(BandTows(band), ((std::uint64_t{1} << c.n) - 1) << (c.first - 1));
  }
  const auto plane = geom::MakePlane(1000, 1000);
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.translation() = Eigen::Vector3d(10, 20, 0);  // tool x = +x
  for (const int n : {7, 8}) {
    const TowBand band = PlyTowBand(head, n);
    const TowCross c = TowsAt(*plane, tool, head, band, nullptr);
    ASSERT_TRUE(c.ok);
    ASSERT_EQ(c.boundary.size(), static_cast<std::size_t>(n) + 1);
    for (int j = 0; j <= n; ++j) {
      const int b = band.first - 1 + j;  // the head's boundary
      const Eigen::Vector3d want(10 + (b - 8) * 6.35, 20, 0);
      EXPECT_LT((c.boundary[static_cast<std::size_t>(j)] - want).norm(), 1e-9) << n << " " << j;
    }
  }
  // The band's tows may stay on a plate the head's outer tows overhang.
  tool.translation() = Eigen::Vector3d(470, 0, 0);
  EXPECT_FALSE(TowsAt(*plane, tool, head, nullptr).ok);
  EXPECT_TRUE(TowsAt(*plane, tool, head, PlyTowBand(head, 8), nullptr).ok);
}

TEST(afp_tows, AToolPointOffTheSurfaceIsNotOk) {
  const auto plane = geom::MakePlane(100, 100);
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.translation() = Eigen::Vector3d(500, 0, 0);
  EXPECT_FALSE(TowsAt(*plane, tool, TowLayout{16, 6.35}, nullptr).ok);
  tool.translation() = Eigen::Vector3d(45, 0, 0);  // centre on, right edge tow off the plate
  EXPECT_FALSE(TowsAt(*plane, tool, TowLayout{16, 6.35}, nullptr).ok);
}

// Issue 26 item 7: the tool point's foot is its closest point on the wing, whatever skin the
// hint (the previous pose's foot) lies on. The roller on the lower skin near the trailing edge
// (97.5 % chord at mid-span, the skins 13 mm apart), the hint on the upper skin at the same
// station: before, the descent from the hint stopped on the upper skin and every tow was placed
// there, 13 mm from the roller. Second route: the closed-form loft (naca.h).
TEST(afp_tows, AHintOnTheOtherSkinOfTheWingDoesNotDecideTheFoot) {
  std::string error;
  const geom::WingSurface w =
      geom::MakeWingSurface(geom::testing::SeedWingSpec(), geom::WingSkin::kFull, error);
  ASSERT_TRUE(w.surface) << error;
  const std::optional<geom::Wing> wing = geom::Wing::Make(geom::testing::SeedWingSpec(), error);
  ASSERT_TRUE(wing) << error;
  const Eigen::Vector2d len = w.surface->Domain().max;
  for (const double s : {0.95, 0.05}) {  // lower skin, then upper
    const double eta = 0.5;
    const geom::WingDerivatives d = wing->Derivatives(s, eta);
    const Eigen::Vector3d n = wing->Normal(s, eta);
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
    tool.linear().col(2) = n;                                          // head axis
    tool.linear().col(1) = (d.d_ds - d.d_ds.dot(n) * n).normalized();  // chordwise travel
    tool.linear().col(0) = tool.linear().col(1).cross(n);              // tows along the span
    tool.translation() = d.point;
    const Eigen::Vector2d hint(len.x() * (1.0 - s), len.y() * eta);  // the other skin
    const TowCross c = TowsAt(*w.surface, tool, TowLayout{16, 6.35}, &hint);
    ASSERT_TRUE(c.ok) << s;
    EXPECT_LT((c.centre - d.point).norm(), 0.02) << s;
    for (const Eigen::Vector3d& b : {c.boundary.front(), c.boundary.back()}) {
      // 50.8 mm along the span either side, on the same skin.
      EXPECT_NEAR((b - d.point).norm(), 50.8, 0.05) << s;
      EXPECT_LT(std::abs((b - d.point).dot(n)), 0.5) << s;
    }
  }
}

}  // namespace
}  // namespace stitchsim::process
