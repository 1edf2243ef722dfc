// Off-part moves between lay-ups (planner/sequence/offpart.h): retract and approach along the
// tool z, travel kept clear of the part. Heights are checked by closed forms (plane: z; convex
// cylinder: distance from the axis less the radius), not by the surface's own projection.
#include <gtest/gtest.h>

#include <cmath>

#include "stitchsim/common/units.h"
#include "stitchsim/planner/sequence/offpart.h"

namespace stitchsim::planner {
namespace {

// Tool pose on a convex cylinder of radius r (axis along x at z = -r) at angle `a` from the
// crown, travel along +x: z = outward normal, y = +x, x = y cross z.
Eigen::Isometry3d OnCylinder(double r, double x, double a) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d n(0.0, std::sin(a), std::cos(a));
  const Eigen::Vector3d y = Eigen::Vector3d::UnitX();
  t.linear().col(0) = y.cross(n);
  t.linear().col(1) = y;
  t.linear().col(2) = n;
  t.translation() = Eigen::Vector3d(x, 0.0, -r) + r * n;
  return t;
}

double CylinderHeight(double r, const Eigen::Vector3d& p) {
  return std::hypot(p.y(), p.z() + r) - r;
}

// Every point of the tool-point polyline, sampled each mm, in order.
template <typename Height>
double LowestAlong(const Eigen::Vector3d& from, const std::vector<program::OffPartBlock>& blocks,
                   std::size_t first, std::size_t last, Height height) {
  double lowest = 1e300;
  Eigen::Vector3d p = from;
  for (std::size_t i = first; i < last; ++i) {
    const Eigen::Vector3d q = blocks[i].pose.translation();
    const int n = std::max(1, static_cast<int>((q - p).norm()));
    for (int k = 0; k <= n; ++k) lowest = std::min(lowest, height(p + (q - p) * (double(k) / n)));
    p = q;
  }
  return lowest;
}

TEST(OffPart, OnAPlaneRetractTravelApproachAreExact) {
  const auto plane = geom::MakePlane(2000, 2000);
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = Eigen::Isometry3d::Identity();
  a.translation() = Eigen::Vector3d(400, 0, 0);
  b.translation() = Eigen::Vector3d(-400, 100, 0);
  b.linear() = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  OffPartOptions o;
  o.turn_about_z_rad = -kPi;  // the head turns round clockwise (seen from above)
  const auto blocks = OffPartPath(*plane, OffPartEnd{a, true}, OffPartEnd{b, true}, 12000.0, o);
  // Retract, travel in two halves (a half turn is made in quarter turns, so each move's own
  // shortest rotation goes the chosen way; nothing is in the way), approach.
  ASSERT_EQ(blocks.size(), 4u);
  EXPECT_TRUE(blocks[0].head_retracted);
  EXPECT_NEAR((blocks[0].pose.translation() - Eigen::Vector3d(400, 0, 100)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((blocks[1].pose.translation() - Eigen::Vector3d(0, 50, 100)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(TwistAboutZ(a.linear(), blocks[1].pose.linear()), -0.5 * kPi, 1e-12);
  EXPECT_NEAR((blocks[2].pose.translation() - Eigen::Vector3d(-400, 100, 100)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(blocks[2].pose.linear().isApprox(b.linear(), 1e-12));
  EXPECT_EQ(blocks[3].motion, program::Motion::kFeed);
  EXPECT_FALSE(blocks[3].head_retracted);
  ASSERT_TRUE(blocks[3].feed_mm_per_min.has_value());
  EXPECT_EQ(*blocks[3].feed_mm_per_min, 12000.0);
  EXPECT_TRUE(blocks[3].pose.isApprox(b, 1e-12));
  o.turn_about_z_rad = kPi;  // the other way round
  const auto other = OffPartPath(*plane, OffPartEnd{a, true}, OffPartEnd{b, true}, 12000.0, o);
  ASSERT_EQ(other.size(), 4u);
  EXPECT_NEAR(TwistAboutZ(a.linear(), other[1].pose.linear()), 0.5 * kPi, 1e-12);
  // 100 up, 806.2 across, 100 down.
  EXPECT_NEAR(OffPartLength(a.translation(), blocks), 200.0 + std::hypot(800.0, 100.0), 1e-9);
}

TEST(OffPart, AroundAConvexCylinderTheTravelKeepsItsClearance) {
  const double r = 400.0;
  const auto cyl = geom::MakeCylinder(r, true, 1200, r * 2.6);
  const Eigen::Isometry3d a = OnCylinder(r, 300, -1.2), b = OnCylinder(r, -300, 1.2);
  OffPartOptions o;
  const auto blocks = OffPartPath(*cyl, OffPartEnd{a, true}, OffPartEnd{b, true}, 6000.0, o);
  ASSERT_GE(blocks.size(), 4u);  // the straight chord cuts through the part: via points
  EXPECT_LT(CylinderHeight(r, 0.5 * (a.translation() + b.translation())), 0.0);
  EXPECT_NEAR(CylinderHeight(r, blocks.front().pose.translation()), o.retract_mm, 1e-9);
  const double lowest = LowestAlong(blocks.front().pose.translation(), blocks, 1, blocks.size() - 1,
                                    [&](const Eigen::Vector3d& p) { return CylinderHeight(r, p); });
  EXPECT_GE(lowest, 0.95 * o.clearance_mm);
  EXPECT_TRUE(blocks.back().pose.isApprox(b, 1e-12));
  for (std::size_t i = 0; i + 1 < blocks.size(); ++i) EXPECT_TRUE(blocks[i].head_retracted) << i;
}

TEST(OffPart, FromHomeAndBackHome) {
  const auto plane = geom::MakePlane(2000, 2000);
  Eigen::Isometry3d home = Eigen::Isometry3d::Identity(), a = Eigen::Isometry3d::Identity();
  home.translation() = Eigen::Vector3d(0, 0, 500);
  a.translation() = Eigen::Vector3d(300, 0, 0);
  OffPartOptions o;
  const auto in = OffPartPath(*plane, OffPartEnd{home, false}, OffPartEnd{a, true}, 6000.0, o);
  ASSERT_EQ(in.size(), 2u);  // travel to above the start, then down
  EXPECT_NEAR(OffPartLength(home.translation(), in), std::hypot(300.0, 400.0) + 100.0, 1e-9);
  const auto out =
      OffPartPath(*plane, OffPartEnd{a, true}, OffPartEnd{home, false}, std::nullopt, o);
  ASSERT_EQ(out.size(), 2u);  // retract, travel home
  EXPECT_TRUE(out.back().pose.isApprox(home, 1e-12));
  const auto none = OffPartPath(*plane, OffPartEnd{a, true}, std::nullopt, std::nullopt, o);
  ASSERT_EQ(none.size(), 1u);  // retract only
}

TEST(OffPart, HeightAboveSurfaceMatchesTheClosedForm) {
  const double r = 250.0;
  const auto cyl = geom::MakeCylinder(r, true, 800, 700);
  for (const double a : {-0.8, 0.0, 0.5}) {
    for (const double h : {-50.0, 0.0, 30.0, 120.0}) {
      const Eigen::Vector3d p =
          OnCylinder(r, 10.0, a).translation() + h * Eigen::Vector3d(0, std::sin(a), std::cos(a));
      EXPECT_NEAR(HeightAboveSurface(*cyl, p), CylinderHeight(r, p), 1e-6) << a << " " << h;
    }
  }
}

// A bidirectional programme turns the head round at every backward course. Made the shorter
// way each time, near-half turns that all lean one way (179 deg) wind the wrist up: two of them
// are 358 deg, past a6's 350. The policy turns back instead, and leaves small turns alone.
TEST(OffPart, HalfTurnsUnwindTheHeadInsteadOfWindingIt) {
  const double deg = kDeg;
  double twist = 0.0, worst = 0.0;
  for (int i = 0; i < 20; ++i) {
    twist += UnwindingTurn(twist, 179.0 * deg);
    worst = std::max(worst, std::abs(twist));
  }
  EXPECT_LT(worst, 181.0 * deg);
  double shorter_way = 0.0;
  for (int i = 0; i < 20; ++i) shorter_way += 179.0 * deg;
  EXPECT_GT(shorter_way, 350.0 * deg);  // what always taking the shorter way would do
  EXPECT_NEAR(UnwindingTurn(0.0, 10.0 * deg), 10.0 * deg, 1e-15);            // small: as it is
  EXPECT_NEAR(UnwindingTurn(250.0 * deg, 10.0 * deg), 10.0 * deg, 1e-15);    // 260: still inside
  EXPECT_NEAR(UnwindingTurn(265.0 * deg, 10.0 * deg), -350.0 * deg, 1e-12);  // 275: back round
  EXPECT_NEAR(UnwindingTurn(180.0 * deg, 170.0 * deg), -190.0 * deg, 1e-12);
  EXPECT_NEAR(UnwindingTurn(-180.0 * deg, -170.0 * deg), 190.0 * deg, 1e-12);
}

}  // namespace
}  // namespace stitchsim::planner
