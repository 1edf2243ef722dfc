// afp.stagger against seams placed by hand on a plane: two 0 deg plies of a laminate, each of
// two adjacent courses along x (16 tows of 6.35 mm: a course is 101.6 mm wide, so a ply's
// seam lies midway between its two courses' centre lines). The second ply's courses moved
// 2 mm across put its seam 2 mm from the first's: with a 10 mm stagger offset it fires on
// both of its lines with 2 mm (the hand difference of the centre lines); moved 12 mm it passes
// and reads 12. The window counts plies of the same angle only. Without a laminate the rule
// is skipped.
#include <gtest/gtest.h>

#include "afp_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

using testing::AfpScene;
using testing::LayLine;
using testing::RuleOf;
using testing::RunLines;
using testing::ToolAt;

constexpr double kCourse = 16 * testing::kTowWidth;

scene::PlySpec PlyAt(double angle_deg) {
  scene::PlySpec p;
  p.name = "p" + std::to_string(static_cast<int>(angle_deg));
  p.angle_rad = DegToRad(angle_deg);
  return p;
}

// Ply `ply`'s two courses along x, 300 mm long, centre lines at y = shift and shift + one
// course width; lines first_line and first_line + 1.
std::vector<trace::LineRecord> TwoCourses(const geom::Surface& s, int ply, double shift,
                                          int first_line) {
  const Eigen::Vector2d x(1, 0);
  std::vector<trace::LineRecord> lines;
  for (int c = 0; c < 2; ++c) {
    const double y = shift + c * kCourse;
    lines.push_back(
        LayLine(first_line + c, ToolAt(s, {0, y}, x), ToolAt(s, {300, y}, x), 0xFFFF, c + 1, ply));
  }
  return lines;
}

// Plies 1 and 2 at 0 deg and ply 3 at 90 deg; the laminate stacks `stack` (0-based plies).
std::unique_ptr<scene::Scene> Laminate(const std::vector<std::size_t>& stack, int window) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->plies = {PlyAt(0), PlyAt(0), PlyAt(90)};
  scene::LaminateSpec lam;
  lam.name = "skin";
  lam.stagger_offset_mm = 10.0;
  lam.stagger_plies_before_repeat = window;
  for (std::size_t p : stack) {
    scene::LaminateStackEntry e;
    e.ply = p;
    lam.stack.push_back(e);
  }
  scene->laminates.push_back(lam);
  return scene;
}

std::vector<trace::LineRecord> Programme(const geom::Surface& s, double shift) {
  auto lines = TwoCourses(s, 1, 0.0, 10);
  for (const auto& l : TwoCourses(s, 2, shift, 20)) lines.push_back(l);
  return lines;
}

TEST(AfpStagger, SeamsTwoMillimetresApartFireOnTheUpperPlysLines) {
  const auto scene = Laminate({0, 1}, 1);
  const Report report = RunLines(*scene, Programme(*scene->surface, 2.0));
  const RuleSummary* rule = RuleOf(report, "afp.stagger");
  ASSERT_NE(rule, nullptr);
  ASSERT_EQ(rule->findings.size(), 2u);
  EXPECT_EQ(rule->findings[0].line, 20);
  EXPECT_EQ(rule->findings[1].line, 21);
  for (const auto& f : rule->findings) {
    EXPECT_NEAR(f.value, 2.0, 1e-6);
    EXPECT_EQ(f.subject, "ply 2");
    EXPECT_NE(f.message.find("from a seam of ply 1 (line 1"), std::string::npos) << f.message;
    // Where: on ply 2's seam, half a course across from its first course's centre line (y = 2)
    // and 2 mm from ply 1's (y = 50.8), along the courses (x 0 .. 300) on the plane (z = 0).
    ASSERT_TRUE(f.position_mm);
    EXPECT_NEAR((*f.position_mm)[1], 2.0 + 0.5 * kCourse, 1e-6);
    EXPECT_GE((*f.position_mm)[0], 0.0);
    EXPECT_LE((*f.position_mm)[0], 300.0);
    EXPECT_NEAR((*f.position_mm)[2], 0.0, 1e-6);
  }
  ASSERT_TRUE(rule->worst_value);
  EXPECT_NEAR(*rule->worst_value, 2.0, 1e-6);

  const Report apart = RunLines(*scene, Programme(*scene->surface, 12.0));
  const RuleSummary* passed = RuleOf(apart, "afp.stagger");
  ASSERT_NE(passed, nullptr);
  EXPECT_EQ(passed->errors, 0);
  ASSERT_TRUE(passed->worst_value);
  EXPECT_NEAR(*passed->worst_value, 12.0, 1e-6);
  EXPECT_GT(passed->checked, 0);
}

TEST(AfpStagger, APlysOuterEdgesAreNotSeams) {
  // The upper ply's courses at y = -100.6 and 1.0: its seam (-49.8) lies 1 mm from the lower
  // ply's outer edge (-50.8) and its outer edge (51.8) 1 mm from the lower ply's seam (50.8);
  // seam to seam they are 100.6 mm apart.
  const auto scene = Laminate({0, 1}, 1);
  const Report report = RunLines(*scene, Programme(*scene->surface, -100.6));
  const RuleSummary* rule = RuleOf(report, "afp.stagger");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 0);
  EXPECT_GT(rule->checked, 0);
}

TEST(AfpStagger, TheWindowCountsSameAnglePliesOnly) {
  // Stack (0-based plies) 0, 1, 2, 3 at 0, 0, 90, 0 deg. Ply 4's seam lies 2 mm from ply 1's
  // and 28 mm from ply 2's (ply 2 moved 30 mm); ply 2's lies 30 mm from ply 1's. The 90 deg
  // ply between does not count: in a window of one same-angle ply, ply 4 meets ply 2 only
  // (passes); of two, ply 1 too (fires on ply 4's two lines).
  auto programme = [](const geom::Surface& s) {
    auto lines = TwoCourses(s, 1, 0.0, 10);
    for (const auto& l : TwoCourses(s, 2, 30.0, 20)) lines.push_back(l);
    for (const auto& l : TwoCourses(s, 4, 2.0, 40)) lines.push_back(l);
    return lines;
  };
  for (const int window : {1, 2}) {
    auto scene = Laminate({0, 1, 2, 3}, window);
    scene->plies.push_back(PlyAt(0));  // ply 4 (index 3)
    const Report report = RunLines(*scene, programme(*scene->surface));
    const RuleSummary* rule = RuleOf(report, "afp.stagger");
    ASSERT_NE(rule, nullptr);
    if (window == 1) {
      EXPECT_EQ(rule->errors, 0);
    } else {
      ASSERT_EQ(rule->findings.size(), 2u);
      EXPECT_EQ(rule->findings[0].line, 40);
      EXPECT_NEAR(rule->findings[0].value, 2.0, 1e-6);
      EXPECT_EQ(rule->findings[0].subject, "ply 4");
    }
  }
}

TEST(AfpStagger, WithoutALaminateTheRuleIsSkipped) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->plies = {PlyAt(0), PlyAt(0)};
  const Report report = RunLines(*scene, Programme(*scene->surface, 2.0));
  EXPECT_EQ(RuleOf(report, "afp.stagger"), nullptr);
  bool named = false;
  for (const SkippedRule& s : report.skipped) named |= s.id == "afp.stagger";
  EXPECT_TRUE(named);
}

}  // namespace
}  // namespace stitchsim::verify
