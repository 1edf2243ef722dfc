// afp.fiber_angle against directions known in closed form: on a plane, a course turned 4 deg
// from its ply's direction (0 deg and 45 deg plies) reads 4 deg on the line that lays it; on a
// convex cylinder of R 400 (axis x), a 45 deg ply's design direction is the helix at 45 deg to
// the axis wherever it is (the rosette along the axis projects onto the cylinder as the axis
// direction), so a course laid along the helix at 41 deg reads 4 deg, the tool poses built from
// the helix's closed form, not from the surface model; a course along the axis of a 0 deg ply
// reads 0. A line of a ply the scene does not define is not judged.
#include <gtest/gtest.h>

#include <cmath>

#include "afp_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

using testing::AfpScene;
using testing::LayLine;
using testing::RuleOf;
using testing::RunLines;
using testing::ToolAt;

scene::PlySpec Ply(double angle_deg) {
  scene::PlySpec p;
  p.name = "ply";
  p.angle_rad = DegToRad(angle_deg);
  p.direction = Eigen::Vector3d::UnitX();
  p.projection = -Eigen::Vector3d::UnitZ();
  return p;
}

// Line 30: 300 mm along the (u, v) direction at `course_deg` to x; line 31: 100 mm on along x.
std::vector<trace::LineRecord> PlaneCourse(const geom::Surface& s, double course_deg) {
  const double a = DegToRad(course_deg);
  const Eigen::Vector2d dir(std::cos(a), std::sin(a)), x(1, 0);
  const Eigen::Vector2d end = 300.0 * dir;
  return {LayLine(30, ToolAt(s, {0, 0}, dir), ToolAt(s, end, dir)),
          LayLine(31, ToolAt(s, end, x), ToolAt(s, end + Eigen::Vector2d(100, 0), x))};
}

TEST(AfpFiberAngle, OnAPlaneACourseTurnedFourDegreesReadsFourOnItsLine) {
  for (const double ply_deg : {0.0, 45.0}) {
    auto scene = AfpScene(geom::MakePlane(4000, 4000));
    scene->plies.push_back(Ply(ply_deg));
    scene->limits.Set(scene::LimitKey::kAfpFiberAngleMaxDeg, 3.0);
    // Line 30 at ply + 4 deg (hand: 4 deg off); line 31 along x (hand: ply_deg off, folded
    // into 0..90).
    const Report report = RunLines(*scene, PlaneCourse(*scene->surface, ply_deg + 4.0));
    const RuleSummary* rule = RuleOf(report, "afp.fiber_angle");
    ASSERT_NE(rule, nullptr);
    EXPECT_EQ(rule->checked, 2);
    if (ply_deg == 0.0) {
      ASSERT_EQ(rule->findings.size(), 1u);
      EXPECT_EQ(rule->findings[0].line, 30);
      EXPECT_NEAR(rule->findings[0].value, 4.0, 1e-9);
      EXPECT_NE(rule->findings[0].message.find("ply 1 course 1 tow"), std::string::npos)
          << rule->findings[0].message;
    } else {
      ASSERT_EQ(rule->findings.size(), 2u);
      EXPECT_EQ(rule->findings[0].line, 30);
      EXPECT_NEAR(rule->findings[0].value, 4.0, 1e-9);
      EXPECT_EQ(rule->findings[1].line, 31);
      EXPECT_NEAR(rule->findings[1].value, 45.0, 1e-9);
    }
    // The default limit, 5 deg, passes the 4 deg course.
    auto lenient = AfpScene(geom::MakePlane(4000, 4000));
    lenient->plies.push_back(Ply(ply_deg));
    const Report passed = RunLines(*lenient, PlaneCourse(*lenient->surface, ply_deg + 4.0));
    const RuleSummary* again = RuleOf(passed, "afp.fiber_angle");
    ASSERT_NE(again, nullptr);
    EXPECT_EQ(again->errors, ply_deg == 0.0 ? 0 : 1);  // the 45 deg ply's line 31 still fails
  }
}

TEST(AfpFiberAngle, TheRosetteIsProjectedAlongThePlysProjectionDirection) {
  // Reference (1, 0, 1) projected onto z = 0 along (0, 1, -1): (1, 0, 1) + (0, 1, -1) =
  // (1, 1, 0), the design direction at 45 deg to x (projected straight down it would be x).
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene::PlySpec ply = Ply(0.0);
  ply.direction = Eigen::Vector3d(1, 0, 1).normalized();
  ply.projection = Eigen::Vector3d(0, 1, -1).normalized();
  scene->plies.push_back(ply);
  const Report report = RunLines(*scene, PlaneCourse(*scene->surface, 41.0));
  const RuleSummary* rule = RuleOf(report, "afp.fiber_angle");
  ASSERT_NE(rule, nullptr);
  ASSERT_EQ(rule->findings.size(), 1u);  // line 31, along x: 45 deg off
  EXPECT_EQ(rule->findings[0].line, 31);
  EXPECT_NEAR(rule->findings[0].value, 45.0, 1e-9);
  EXPECT_NEAR(testing::SubjectOf(*rule, "tow 1").worst_value.value_or(-1), 45.0, 1e-9);
}

// The tool on a convex cylinder of radius r (axis along x at z = -r) at axial x and arc angle
// theta, travelling at `alpha` to the axis (a helix): built from the closed form.
Eigen::Isometry3d OnHelix(double r, double x, double theta, double alpha) {
  const Eigen::Vector3d normal(0, std::sin(theta), std::cos(theta));
  const Eigen::Vector3d round(0, std::cos(theta), -std::sin(theta));
  const Eigen::Vector3d travel =
      std::cos(alpha) * Eigen::Vector3d::UnitX() + std::sin(alpha) * round;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = travel.cross(normal);
  t.linear().col(1) = travel;
  t.linear().col(2) = normal;
  t.translation() = Eigen::Vector3d(x, r * std::sin(theta), r * std::cos(theta) - r);
  return t;
}

// `steps` lines of `step` mm along the helix at `alpha_deg`, from arc length 0 at theta0.
std::vector<trace::LineRecord> Helix(double r, double alpha_deg, double theta0, int steps,
                                     double step) {
  const double alpha = DegToRad(alpha_deg);
  auto at = [&](int k) {
    const double s = k * step;
    return OnHelix(r, s * std::cos(alpha), theta0 + s * std::sin(alpha) / r, alpha);
  };
  std::vector<trace::LineRecord> lines;
  for (int k = 0; k < steps; ++k) lines.push_back(LayLine(40 + k, at(k), at(k + 1)));
  return lines;
}

TEST(AfpFiberAngle, OnACylinderAHelixReadsItsAngleToTheProjectedRosette) {
  const double r = 400.0;
  auto scene = AfpScene(geom::MakeCylinder(r, true, 4000, 2 * kPi * r * 0.9));
  scene->plies.push_back(Ply(45.0));
  scene->limits.Set(scene::LimitKey::kAfpFiberAngleMaxDeg, 3.0);
  // 20 lines of 10 mm: the executor's straight line between two helix poses projects onto the
  // cylinder within about 0.002 deg of the helix's direction.
  const Report report = RunLines(*scene, Helix(r, 41.0, 0.1, 20, 10.0));
  const RuleSummary* rule = RuleOf(report, "afp.fiber_angle");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->checked, 20);
  EXPECT_EQ(rule->errors, 20);
  ASSERT_TRUE(rule->worst_value);
  EXPECT_NEAR(*rule->worst_value, 4.0, 0.01);
  for (const auto& f : rule->findings) EXPECT_NEAR(f.value, 4.0, 0.01) << f.line;

  // Along the axis, a 0 deg ply: no deviation anywhere round the cylinder.
  auto axial = AfpScene(geom::MakeCylinder(r, true, 4000, 2 * kPi * r * 0.9));
  axial->plies.push_back(Ply(0.0));
  const Report straight = RunLines(*axial, Helix(r, 0.0, 0.6, 5, 60.0));
  const RuleSummary* zero = RuleOf(straight, "afp.fiber_angle");
  ASSERT_NE(zero, nullptr);
  ASSERT_TRUE(zero->worst_value);
  EXPECT_NEAR(*zero->worst_value, 0.0, 1e-6);
  EXPECT_EQ(zero->errors, 0);
}

TEST(AfpFiberAngle, ALineOfAPlyTheSceneDoesNotDefineIsNotJudged) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->plies.push_back(Ply(0.0));
  const Eigen::Vector2d dir(std::cos(0.3), std::sin(0.3));
  const Report report =
      RunLines(*scene, {LayLine(50, ToolAt(*scene->surface, {0, 0}, dir),
                                ToolAt(*scene->surface, 300.0 * dir, dir), 0xFFFF, 1, /*ply=*/2)});
  const RuleSummary* rule = RuleOf(report, "afp.fiber_angle");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->checked, 0);
}

}  // namespace
}  // namespace stitchsim::verify
