// afp.coverage on hand-made laying lines over a plane: a rectangular ply filled exactly by
// four straight courses passes with its figures reported (0 % bare, 0 % doubled); one course
// left out fires "bare" on the line of the neighbouring course nearest the gap; one course
// laid twice fires "doubled" on the second laying's line; a ply the scene does not define is
// judged by what it lays.
#include <gtest/gtest.h>

#include "afp_test_support.h"
#include "stitchsim/verify/afp_coverage_image.h"

namespace stitchsim::verify {
namespace {

using namespace testing;

constexpr double kCourse = 16 * kTowWidth;  // 101.6 mm
constexpr double kLength = 80 * kTowWidth;  // 508 mm

std::unique_ptr<scene::Scene> PlyScene() {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene::PlySpec ply;
  ply.name = "p0";
  ply.boundary_uv = {{0, 0}, {4 * kCourse, 0}, {4 * kCourse, kLength}, {0, kLength}};
  scene->plies.push_back(ply);
  return scene;
}

// Course `index` (0-based across u) laid along +v in ten lines from line `first_line`, as
// course number `course` of ply 1, after a rapid outside any course.
void AddCourse(const geom::Surface& plane, int index, int course, int first_line,
               std::vector<trace::LineRecord>& lines) {
  const double u = (index + 0.5) * kCourse;
  auto pose = [&](int s) { return ToolAt(plane, {u, s * kLength / 10}, {0, 1}); };
  trace::LineRecord rapid;
  rapid.source_line = first_line - 1;
  rapid.rapid = true;
  rapid.head_retracted = true;
  rapid.to = pose(0);
  lines.push_back(rapid);
  for (int s = 0; s < 10; ++s) {
    lines.push_back(LayLine(first_line + s, pose(s), pose(s + 1), 0xFFFF, course));
  }
}

TEST(AfpCoverageRule, ExactFillPassesAndReportsItsFigures) {
  const auto scene = PlyScene();
  std::vector<trace::LineRecord> lines;
  for (int c = 0; c < 4; ++c) AddCourse(*scene->surface, c, c + 1, 100 * (c + 1), lines);
  const Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.coverage");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 0);
  EXPECT_EQ(rule->checked, 1);
  ASSERT_TRUE(rule->worst_value);
  EXPECT_EQ(*rule->worst_value, 0.0);
  EXPECT_EQ(*rule->error_limit, 2.0);
  ASSERT_EQ(rule->subjects.size(), 3U);
  EXPECT_EQ(rule->subjects[0].subject, "p0 bare");
  EXPECT_EQ(rule->subjects[1].subject, "p0 doubled");
  EXPECT_EQ(*rule->subjects[1].error_limit, 5.0);
  EXPECT_EQ(*rule->subjects[1].worst_value, 0.0);
  EXPECT_EQ(rule->subjects[2].subject, "p0 laid outside");
  EXPECT_NEAR(*rule->subjects[2].worst_value, 0.0, 1e-9);
}

TEST(AfpCoverageRule, CourseLeftOutFiresBareOnTheNeighbouringCoursesLine) {
  const auto scene = PlyScene();
  std::vector<trace::LineRecord> lines;
  for (int c : {0, 1, 3}) AddCourse(*scene->surface, c, c + 1, 100 * (c + 1), lines);
  const Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.coverage");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 1);
  // One course of four, beyond the band: 101.6 x 495.3 of 393.7 x 495.3.
  const double expected = 100.0 * kCourse / (4 * kCourse - 2 * kTowWidth);
  ASSERT_TRUE(rule->worst_value);
  EXPECT_NEAR(*rule->worst_value, expected, 1e-6);
  ASSERT_EQ(rule->findings.size(), 1U);
  EXPECT_EQ(rule->findings[0].subject, "p0 bare");
  // The worst patch's first block (low v, left side of the gap) lies beside course 2's first
  // line.
  EXPECT_EQ(rule->findings[0].line, 200);
}

TEST(AfpCoverageRule, CourseLaidTwiceFiresDoubledOnTheSecondLaying) {
  const auto scene = PlyScene();
  std::vector<trace::LineRecord> lines;
  for (int c = 0; c < 4; ++c) AddCourse(*scene->surface, c, c + 1, 100 * (c + 1), lines);
  AddCourse(*scene->surface, 1, 5, 900, lines);
  const Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.coverage");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 1);
  EXPECT_EQ(*rule->worst_value, 0.0);  // nothing bare
  EXPECT_NEAR(*rule->subjects[1].worst_value, 100.0 * kCourse / (4 * kCourse - 2 * kTowWidth),
              1e-6);
  ASSERT_EQ(rule->findings.size(), 1U);
  EXPECT_EQ(rule->findings[0].subject, "p0 doubled");
  EXPECT_EQ(rule->findings[0].line, 900);
}

// The snapshot's picture: the missing course's middle is a gap, the course laid twice an
// overlap, the others laid tows, and the corner of the box (outside the ply) empty.
TEST(AfpCoverageRule, CoverageImageShowsTowsGapsAndOverlapsWhereTheyLie) {
  const auto scene = PlyScene();
  std::vector<trace::LineRecord> lines;
  for (int c : {0, 1, 3}) AddCourse(*scene->surface, c, c + 1, 100 * (c + 1), lines);
  AddCourse(*scene->surface, 1, 5, 900, lines);
  const process::ProcessModel model = process::MakeProcessModel(*scene, 5.0);
  trace::CellDescription cell;
  Verifier v(RuleContext{scene.get(), &cell, &model}, false);
  for (const auto& l : lines) v.OnLine(l);
  Report r;
  v.Finish(r);
  const std::vector<CoverageImage> images = CoverageImages(v, 400);
  ASSERT_EQ(images.size(), 1U);
  const CoverageImage& img = images[0];
  EXPECT_EQ(img.ply, 1);
  EXPECT_EQ(img.name, "p0");
  EXPECT_LE(std::max(img.width, img.height), 400);
  auto at = [&](double u, double v) {
    const int x =
        static_cast<int>((u - img.lo_uv.x()) / (img.hi_uv.x() - img.lo_uv.x()) * img.width);
    const int y =
        img.height - 1 -
        static_cast<int>((v - img.lo_uv.y()) / (img.hi_uv.y() - img.lo_uv.y()) * img.height);
    return img.pixels[static_cast<std::size_t>(y * img.width + x)];
  };
  const double mid_v = kLength / 2;
  EXPECT_EQ(at(0.5 * kCourse, mid_v), CoverageState::kLaid);
  EXPECT_EQ(at(1.5 * kCourse, mid_v), CoverageState::kDoubled);
  EXPECT_EQ(at(2.5 * kCourse, mid_v), CoverageState::kBare);
  EXPECT_EQ(at(3.5 * kCourse, mid_v), CoverageState::kLaid);
  EXPECT_EQ(at(2.5 * kCourse, 2.0), CoverageState::kBoundaryBare);  // in the band
  EXPECT_EQ(at(img.lo_uv.x() + 1, img.lo_uv.y() + 1), CoverageState::kNone);
}

// A ply the scene does not define (M70 P1 on a scene without plies, as `plan afp` writes its
// course; issue 26 item 6) has no boundary: what it lays is measured (on the plane the course's
// 64 x 320 cells of w / 4 are exactly its 101.6 x 508 mm, 100 % of its moves' length x 16 w)
// and material laid twice fires "doubled" on the second laying's line. Before, a scene without
// plies skipped the rule.
TEST(AfpCoverageRule, APlyTheSceneDoesNotDefineIsJudgedByWhatItLays) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  std::vector<trace::LineRecord> lines;
  AddCourse(*scene->surface, 0, 1, 100, lines);
  Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.coverage");
  ASSERT_NE(rule, nullptr);
  EXPECT_TRUE(rule->Applies());
  EXPECT_EQ(rule->errors, 0);
  ASSERT_EQ(rule->subjects.size(), 2U);
  EXPECT_EQ(rule->subjects[0].subject, "ply 1 laid (of nominal)");
  EXPECT_NEAR(*rule->subjects[0].worst_value, 100.0, 1e-6);
  EXPECT_EQ(rule->subjects[1].subject, "ply 1 doubled");
  EXPECT_EQ(*rule->subjects[1].worst_value, 0.0);
  for (const auto& s : report.skipped) EXPECT_NE(s.id, "afp.coverage");

  AddCourse(*scene->surface, 0, 2, 200, lines);  // the same course again
  report = RunLines(*scene, lines);
  rule = RuleOf(report, "afp.coverage");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 1);
  EXPECT_NEAR(*rule->subjects[0].worst_value, 50.0, 1e-6);   // the same area for twice the tows
  EXPECT_NEAR(*rule->subjects[1].worst_value, 100.0, 1e-6);  // all of it twice
  ASSERT_EQ(rule->findings.size(), 1U);
  EXPECT_GE(rule->findings[0].line, 200);
}

}  // namespace
}  // namespace stitchsim::verify
