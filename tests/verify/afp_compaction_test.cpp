// afp.compaction against closed forms on a plane: a roller lifted 0.4 mm (limit 0.25 mm), a
// roller axis rolled 3 deg (limit 2), a head leaning 10 deg along the travel (passes, limit 15)
// and 20 deg (fires), each on its own line; on a convex cylinder a circumferential chord of
// length c sinks its middle by the sagitta r - sqrt(r^2 - c^2 / 4) (press).
#include <gtest/gtest.h>

#include <cmath>

#include "afp_test_support.h"

namespace stitchsim::verify {
namespace {

using namespace testing;

TEST(AfpCompaction, LiftRollAndLeanFireOnTheirLinesAgainstTheirLimits) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const geom::Surface& s = *scene->surface;
  const Eigen::Vector2d x(1, 0);
  auto pose = [&](double u, double lift = 0.0) {
    return ToolAt(s, Eigen::Vector2d(u, 0), x, lift);
  };
  auto turned = [&](double u, const Eigen::Vector3d& tool_axis, double deg) {
    Eigen::Isometry3d t = pose(u);
    t.linear() = t.linear() * Eigen::AngleAxisd(deg * kPi / 180, tool_axis).toRotationMatrix();
    return t;
  };
  std::vector<trace::LineRecord> lines = {
      LayLine(10, pose(0), pose(50)),
      LayLine(11, pose(50, 0.4), pose(100, 0.4)),  // lifted: 160 % of 0.25 mm
      LayLine(12, turned(100, Eigen::Vector3d::UnitY(), 3),
              turned(150, Eigen::Vector3d::UnitY(), 3)),
      LayLine(13, turned(150, Eigen::Vector3d::UnitX(), 10),
              turned(200, Eigen::Vector3d::UnitX(), 10)),
      LayLine(14, turned(200, Eigen::Vector3d::UnitX(), 20),
              turned(250, Eigen::Vector3d::UnitX(), 20)),
  };
  const Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.compaction");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 3);
  ASSERT_EQ(rule->findings.size(), 3U);
  EXPECT_EQ(rule->findings[0].line, 11);
  EXPECT_EQ(rule->findings[0].subject, "lift");
  EXPECT_NEAR(rule->findings[0].value, 160.0, 1e-6);
  EXPECT_EQ(rule->findings[1].line, 12);
  EXPECT_EQ(rule->findings[1].subject, "roll");
  EXPECT_NEAR(rule->findings[1].value, 150.0, 1e-6);
  EXPECT_EQ(rule->findings[2].line, 14);
  EXPECT_EQ(rule->findings[2].subject, "lean");
  EXPECT_NEAR(rule->findings[2].value, 20.0 / 15.0 * 100.0, 1e-6);
  EXPECT_NEAR(*SubjectOf(*rule, "lean").worst_value, 20.0 / 15.0 * 100.0, 1e-6);
  EXPECT_NEAR(*SubjectOf(*rule, "press").worst_value, 0.0, 1e-9);
}

TEST(AfpCompaction, AChordAroundACylinderPressesByItsSagitta) {
  const double r = 300.0, c = 40.0;
  const auto scene = AfpScene(geom::MakeCylinder(r, true, 1000, 1000));
  const geom::Surface& s = *scene->surface;
  const Eigen::Vector2d v(0, 1);
  const Report report =
      RunLines(*scene, {LayLine(10, ToolAt(s, Eigen::Vector2d(0, -0.5 * c * 1.0), v),
                                ToolAt(s, Eigen::Vector2d(0, 0.5 * c), v))});
  const RuleSummary* rule = RuleOf(report, "afp.compaction");
  ASSERT_NE(rule, nullptr);
  // The arc of length c spans the angle c / r; its chord's middle lies below the surface by
  // r (1 - cos(c / 2r)).
  const double sagitta = r * (1 - std::cos(0.5 * c / r));
  EXPECT_NEAR(*SubjectOf(*rule, "press").worst_value, sagitta / 1.0 * 100.0, 0.5);
  EXPECT_EQ(rule->errors, 0);
}

}  // namespace
}  // namespace stitchsim::verify
