// afp.restart_distance against restarts whose distances are known by hand: on a plane, tow 3
// of a straight course along x cut at x = 100 and added again at x = 140 is 140 - 100 = 40 mm
// from its cut (limit 50: fires on the re-adding line; limit 30: passes), whether the lines in
// between lay the other tows or none; on a convex cylinder of R 400, a course round the
// circumference with tow 3 cut over an angle of 40 / 400 rad is R delta_theta = 40 mm from its
// cut along the arc, not the 2 R sin(delta_theta / 2) of the chord (the tool poses built from
// the closed form, not the surface model). A rapid inside the course is bridged by its chord; a
// tow added again in another course is no restart, and without a minimum the rule is skipped.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "afp_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

using namespace testing;  // the afp.* rule tests' scenes, poses, lines and runs

constexpr std::uint64_t kAll = kAllTows;
constexpr std::uint64_t kAllButTow3 = AllTowsBut(3);
constexpr const char* kId = "afp.restart_distance";

constexpr std::uint64_t kTow3 = 1ULL << 2;

// Course 1 along x: 0..100 with `first` (line 10), 100..120 and 120..140 with `between`
// (lines 11, 12), 140..300 with every tow (line 13, in course `last_course`).
std::vector<trace::LineRecord> PlaneCourse(const geom::Surface& s, std::uint64_t first,
                                           std::uint64_t between, int last_course = 1) {
  const Eigen::Vector2d dir(1, 0);
  auto at = [&](double x) { return ToolAt(s, Eigen::Vector2d(x, 0), dir); };
  return {LayLine(10, at(0), at(100), first), LayLine(11, at(100), at(120), between),
          LayLine(12, at(120), at(140), between), LayLine(13, at(140), at(300), kAll, last_course)};
}

TEST(AfpRestartDistance, ATowAddedFortyMillimetresAfterItsCutFiresOnTheReAddingLine) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->limits.Set(scene::LimitKey::kAfpRestartDistanceMm, 50.0);
  const double by_hand = 140.0 - 100.0;  // the x of the re-add less the x of the cut
  // The lines in between lay the other tows (the shared sampling), or none (the rule's own:
  // tow 3 is then the only tow laid before).
  for (const std::uint64_t between : {kAllButTow3, std::uint64_t{0}}) {
    const std::uint64_t first = between == 0 ? kTow3 : kAll;
    const Report report = RunLines(*scene, PlaneCourse(*scene->surface, first, between));
    const RuleSummary* rule = RuleOf(report, kId);
    ASSERT_NE(rule, nullptr);
    EXPECT_EQ(rule->checked, 1) << between;
    EXPECT_EQ(rule->errors, 1);
    ASSERT_EQ(rule->findings.size(), 1u);
    EXPECT_EQ(rule->findings[0].line, 13);
    EXPECT_NEAR(rule->findings[0].value, by_hand, 1e-6);
    EXPECT_NEAR(rule->findings[0].value, 40.0, 1e-6);
    EXPECT_EQ(rule->findings[0].subject, "tow 3");
    EXPECT_NE(rule->findings[0].message.find("cut after line 10"), std::string::npos)
        << rule->findings[0].message;
    ASSERT_TRUE(rule->worst_value);
    EXPECT_NEAR(*rule->worst_value, by_hand, 1e-6);
    EXPECT_EQ(rule->worst_line, 13);
    // Its place: tow 3's centre where it is added again, x = 140, (8.5 - 3) tows to the left
    // (+y: tool x, across the course, is -y along x).
    ASSERT_TRUE(rule->findings[0].position_mm);
    const std::array<double, 3> re_add = {140.0, (8.5 - 3) * kTowWidth, 0.0};
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR((*rule->findings[0].position_mm)[i], re_add[i], 1e-6) << i;
    }
  }

  scene->limits.Set(scene::LimitKey::kAfpRestartDistanceMm, 30.0);
  const Report passing = RunLines(*scene, PlaneCourse(*scene->surface, kAll, kAllButTow3));
  const RuleSummary* rule = RuleOf(passing, kId);
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->checked, 1);
  EXPECT_EQ(rule->errors, 0);
  EXPECT_NEAR(*rule->worst_value, by_hand, 1e-6);
}

TEST(AfpRestartDistance, ATowAddedInAnotherCourseIsNoRestart) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->limits.Set(scene::LimitKey::kAfpRestartDistanceMm, 50.0);
  const Report report = RunLines(*scene, PlaneCourse(*scene->surface, kAll, kAllButTow3, 2));
  const RuleSummary* rule = RuleOf(report, kId);
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->checked, 0);
  EXPECT_EQ(rule->errors, 0);
}

// A rapid inside the course (the head lifted from x = 100 to 140) cuts every tow and is
// bridged by the chord, the distance on a plane: it does not start the course afresh.
TEST(AfpRestartDistance, ARapidInsideTheCourseCutsEveryTowAndIsBridged) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->limits.Set(scene::LimitKey::kAfpRestartDistanceMm, 50.0);
  const Eigen::Vector2d dir(1, 0);
  auto at = [&](double x) { return ToolAt(*scene->surface, Eigen::Vector2d(x, 0), dir, 5.0); };
  auto on = [&](double x) { return ToolAt(*scene->surface, Eigen::Vector2d(x, 0), dir); };
  trace::LineRecord rapid = LayLine(11, at(100), at(140), kAll);
  rapid.rapid = true;
  const Report report = RunLines(
      *scene, {LayLine(10, on(0), on(100), kAll), rapid, LayLine(12, on(140), on(300), kAll)});
  const RuleSummary* rule = RuleOf(report, kId);
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->checked, 16);
  ASSERT_EQ(rule->findings.size(), 1u);
  EXPECT_EQ(rule->findings[0].line, 12);
  EXPECT_NEAR(rule->findings[0].value, 140.0 - 100.0, 1e-6);
}

TEST(AfpRestartDistance, OnACylinderTheDistanceIsItsArcRadiusTimesAngle) {
  const double r = 400.0;
  auto scene = AfpScene(geom::MakeCylinder(r, true, 4000, 2 * kPi * r * 0.9));
  scene->limits.Set(scene::LimitKey::kAfpRestartDistanceMm, 50.0);
  const double a1 = 0.25, a2 = a1 + 40.0 / r, a3 = a2 + 0.5;
  const double arc = r * (a2 - a1), chord = 2 * r * std::sin(0.5 * (a2 - a1));
  ASSERT_GT(arc - chord, 0.01);  // the tolerance below tells them apart
  for (const std::uint64_t between : {kAllButTow3, std::uint64_t{0}}) {
    const Report report = RunLines(
        *scene,
        {LayLine(20, RoundCylinder(r, 0.0), RoundCylinder(r, a1), between == 0 ? kTow3 : kAll),
         LayLine(21, RoundCylinder(r, a1), RoundCylinder(r, a2), between),
         LayLine(22, RoundCylinder(r, a2), RoundCylinder(r, a3), kAll)});
    const RuleSummary* rule = RuleOf(report, kId);
    ASSERT_NE(rule, nullptr);
    ASSERT_EQ(rule->findings.size(), 1u) << between;
    EXPECT_EQ(rule->findings[0].line, 22);
    EXPECT_EQ(rule->findings[0].subject, "tow 3");
    // Chords at most w / 2 = 3.2 mm long under-read an arc of R 400 by about 2.6e-6 of it.
    EXPECT_NEAR(rule->findings[0].value, arc, 1e-3) << between;
  }
}

TEST(AfpRestartDistance, WithoutAMinimumTheRuleIsSkippedAndSaysWhy) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->head.afp.min_restart_mm.reset();  // the bundled head states 100 mm
  const Report report = RunLines(*scene, PlaneCourse(*scene->surface, kAll, kAllButTow3));
  EXPECT_EQ(RuleOf(report, kId), nullptr);
  bool named = false;
  for (const SkippedRule& s : report.skipped) {
    if (s.id != kId) continue;
    named = true;
    EXPECT_EQ(s.reason,
              "no minimum restart distance given (limits: afp.restart_distance: {min_mm: ...}, or "
              "the head's min_restart_mm)");
  }
  EXPECT_TRUE(named);
}

}  // namespace
}  // namespace stitchsim::verify
