// afp.min_tow_length against pieces whose lengths are known by hand: on a plane, a tow added
// for one 60 mm line of a course (limit 100 mm) fires on the line that adds it with 60; on a
// convex cylinder of R 400, a course round the circumference with a tow added for an angle
// of 60 / 400 rad lays R theta = 60 mm of centre line (the tool poses built from the closed
// form, not the surface model). A piece of 110 mm passes, and so does every piece when no
// minimum is given (the rule is then skipped).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "afp_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

using testing::AfpScene;
using testing::LayLine;
using testing::RoundCylinder;
using testing::RuleOf;
using testing::RunLines;
using testing::ToolAt;

constexpr std::uint64_t kAll = testing::kAllTows;
constexpr std::uint64_t kAllButTow5 = testing::AllTowsBut(5);

// Four lines of course 1 along x: 0..100 without tow 5, two lines of len / 2 with it (added
// on line 11, cut after line 12), then 200 mm more without it. Lines 10 to 13.
std::vector<trace::LineRecord> PlaneCourse(const geom::Surface& s, double len) {
  const Eigen::Vector2d dir(1, 0);
  auto at = [&](double x) { return ToolAt(s, Eigen::Vector2d(x, 0), dir); };
  const double mid = 100 + len / 2, end = 100 + len;
  return {LayLine(10, at(0), at(100), kAllButTow5), LayLine(11, at(100), at(mid), kAll),
          LayLine(12, at(mid), at(end), kAll), LayLine(13, at(end), at(end + 200), kAllButTow5)};
}

TEST(AfpMinTowLength, ATowAddedForSixtyMillimetresFiresOnTheLineThatAddsIt) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->limits.Set(scene::LimitKey::kAfpMinTowLengthMm, 100.0);
  const Report report = RunLines(*scene, PlaneCourse(*scene->surface, 60.0));
  const RuleSummary* rule = RuleOf(report, "afp.min_tow_length");
  ASSERT_NE(rule, nullptr);
  // 15 tows laid 360 mm in one piece, tow 5 once for 60 mm (lines 11 and 12).
  EXPECT_EQ(rule->checked, 16);
  EXPECT_EQ(rule->errors, 1);
  ASSERT_EQ(rule->findings.size(), 1u);
  EXPECT_EQ(rule->findings[0].line, 11);
  EXPECT_NEAR(rule->findings[0].value, 60.0, 1e-9);
  EXPECT_EQ(rule->findings[0].subject, "tow 5");
  EXPECT_NE(rule->findings[0].message.find("cut after line 12"), std::string::npos)
      << rule->findings[0].message;
  ASSERT_TRUE(rule->worst_value);
  EXPECT_NEAR(*rule->worst_value, 60.0, 1e-9);
  EXPECT_EQ(rule->worst_line, 11);
  EXPECT_NEAR(*testing::SubjectOf(*rule, "tow 4").worst_value, 360.0, 1e-9);
  // Its place: tow 5's centre where it is added, x = 100, (8.5 - 5) tows to the left (+y:
  // tool x, across the course, is -y along x).
  ASSERT_TRUE(rule->findings[0].position_mm);
  const std::array<double, 3> add = {100.0, (8.5 - 5) * testing::kTowWidth, 0.0};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR((*rule->findings[0].position_mm)[i], add[i], 1e-6) << i;

  const Report longer = RunLines(*scene, PlaneCourse(*scene->surface, 110.0));
  EXPECT_EQ(RuleOf(longer, "afp.min_tow_length")->errors, 0);
}

TEST(AfpMinTowLength, OnACylinderAPieceIsItsArcRadiusTimesAngle) {
  const double r = 400.0;
  auto scene = AfpScene(geom::MakeCylinder(r, true, 4000, 2 * kPi * r * 0.9));
  scene->limits.Set(scene::LimitKey::kAfpMinTowLengthMm, 100.0);
  const double a1 = 0.25, a2 = a1 + 60.0 / r, a3 = a2 + 0.5;
  const Report report =
      RunLines(*scene, {LayLine(20, RoundCylinder(r, 0.0), RoundCylinder(r, a1), kAllButTow5),
                        LayLine(21, RoundCylinder(r, a1), RoundCylinder(r, a2), kAll),
                        LayLine(22, RoundCylinder(r, a2), RoundCylinder(r, a3), kAllButTow5)});
  const RuleSummary* rule = RuleOf(report, "afp.min_tow_length");
  ASSERT_NE(rule, nullptr);
  ASSERT_EQ(rule->findings.size(), 1u);
  EXPECT_EQ(rule->findings[0].line, 21);
  // Chords at most w / 2 = 3.2 mm long under-read an arc of R 400 by about 2.6e-6 of it.
  EXPECT_NEAR(rule->findings[0].value, 60.0, 1e-3);
  EXPECT_NEAR(*testing::SubjectOf(*rule, "tow 4").worst_value, r * a3, 1e-2);
}

TEST(AfpMinTowLength, WithoutAMinimumTheRuleIsSkippedAndSaysWhy) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const Report report = RunLines(*scene, PlaneCourse(*scene->surface, 60.0));
  EXPECT_EQ(RuleOf(report, "afp.min_tow_length"), nullptr);
  bool named = false;
  for (const SkippedRule& s : report.skipped) named |= s.id == "afp.min_tow_length";
  EXPECT_TRUE(named);
}

}  // namespace
}  // namespace stitchsim::verify
