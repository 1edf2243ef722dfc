// afp.gap and afp.overlap against closed forms: two straight 16-tow courses on a plane whose
// centre lines lie 16 w + 1.0 mm apart leave a 1.0 mm gap (fires at 0.76 mm), 16 w - 0.5 mm
// an overlap of 0.5 mm (passes), 16 w - 1.2 mm an overlap of 1.2 mm (fires), each on the
// second course's first laying line, whichever way the second course runs; a tow cut inside a
// course between laid tows is a gap of its width; bits beyond the head's tows are findings.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "afp_test_support.h"

namespace stitchsim::verify {
namespace {

using namespace testing;

// Course 1 along +u at v = `v0` (lines 10..13), course 2 at v = v0 + `spacing` (lines
// 20..23), running along +u or back along -u, 4 lines of 100 mm each; course 1 lays
// `first_tows`, course 2 `tows`.
std::vector<trace::LineRecord> TwoCourses(const geom::Surface& plane, double spacing,
                                          bool second_backwards, std::uint64_t tows = 0xFFFF,
                                          double v0 = 0.0, std::uint64_t first_tows = 0xFFFF) {
  std::vector<trace::LineRecord> lines;
  const Eigen::Vector2d x(1, 0);
  for (int i = 0; i < 4; ++i) {
    lines.push_back(LayLine(10 + i, ToolAt(plane, Eigen::Vector2d(-200 + 100 * i, v0), x),
                            ToolAt(plane, Eigen::Vector2d(-100 + 100 * i, v0), x), first_tows, 1));
  }
  trace::LineRecord between;  // retract and move over: course 0, lays nothing
  between.source_line = 15;
  between.rapid = true;
  between.head_retracted = true;
  between.ply = 1;  // the ply stays in force between its courses
  lines.push_back(between);
  const double dir = second_backwards ? -1.0 : 1.0;
  for (int i = 0; i < 4; ++i) {
    const double u0 = dir * (-200 + 100 * i), u1 = dir * (-100 + 100 * i);
    lines.push_back(LayLine(20 + i, ToolAt(plane, Eigen::Vector2d(u0, v0 + spacing), dir * x),
                            ToolAt(plane, Eigen::Vector2d(u1, v0 + spacing), dir * x), tows, 2));
  }
  return lines;
}

struct Case {
  double offset_mm;  // centre spacing minus 16 w
  const char* rule;  // the rule that sees it
  double value;      // its worst value
  long errors;       // lines it fires on
};

TEST(AfpGaps, NeighbouringCoursesGapAndOverlapByTheirSpacing) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const Case cases[] = {
      {1.0, "afp.gap", 1.0, 4}, {-0.5, "afp.overlap", 0.5, 0}, {-1.2, "afp.overlap", 1.2, 4}};
  for (const bool backwards : {false, true}) {
    for (const Case& c : cases) {
      SCOPED_TRACE(::testing::Message() << c.offset_mm << (backwards ? " backwards" : ""));
      const Report report =
          RunLines(*scene, TwoCourses(*scene->surface, 16 * kTowWidth + c.offset_mm, backwards));
      const RuleSummary* rule = RuleOf(report, c.rule);
      ASSERT_NE(rule, nullptr);
      ASSERT_TRUE(rule->worst_value);
      EXPECT_NEAR(*rule->worst_value, c.value, 1e-6);
      EXPECT_EQ(*rule->error_limit, 0.76);
      EXPECT_EQ(rule->errors, c.errors);
      if (c.errors > 0) {
        ASSERT_FALSE(rule->findings.empty());
        EXPECT_EQ(rule->findings.front().line, 20);
        EXPECT_NEAR(rule->findings.front().value, c.value, 1e-6);
      }
      // The other rule of the pair sees nothing over zero.
      const RuleSummary* other =
          RuleOf(report, std::string(c.rule) == "afp.gap" ? "afp.overlap" : "afp.gap");
      ASSERT_NE(other, nullptr);
      EXPECT_EQ(other->errors, 0);
      EXPECT_NEAR(other->worst_value.value_or(0.0), 0.0, 1e-9);
    }
  }
}

// Issue 26 item 5: on a cylinder, courses along the axis whose centre lines lie 16 w + g apart
// round the circumference (v is arc length) leave a gap g along the surface (unrolled, two
// strips of a plane). The chord projected on the course centre's tangent read
// 2 R sin(g / 2R) cos((W + g) / 2R): 0.942 for 1.0 at R 150, 0.98 at R 250, 0.50 at R 49 (the
// wing's nose), where a gap over the 0.76 mm limit passed.
TEST(AfpGaps, GapsAndOverlapsOnACylinderReadAlongTheSurface) {
  for (const double radius : {49.0, 150.0, 250.0}) {
    const auto scene = AfpScene(geom::MakeCylinder(radius, true, 4000, 2 * kPi * radius * 0.999));
    for (const double g : {1.0, 0.5, -1.2}) {
      SCOPED_TRACE(::testing::Message() << "R " << radius << " offset " << g);
      const double spacing = 16 * kTowWidth + g;
      const Report report =
          RunLines(*scene, TwoCourses(*scene->surface, spacing, false, 0xFFFF, -0.5 * spacing));
      const RuleSummary* rule = RuleOf(report, g > 0 ? "afp.gap" : "afp.overlap");
      ASSERT_NE(rule, nullptr);
      ASSERT_TRUE(rule->worst_value);
      EXPECT_NEAR(*rule->worst_value, std::abs(g), 0.01 * std::abs(g));
      EXPECT_EQ(rule->errors, std::abs(g) > 0.76 ? 4 : 0);
      if (std::abs(g) > 0.76) {
        ASSERT_FALSE(rule->findings.empty());
        EXPECT_EQ(rule->findings.front().line, 20);
        EXPECT_NEAR(rule->findings.front().value, std::abs(g), 0.01 * std::abs(g));
      }
    }
  }
}

// Courses of a narrower ply (issue 26 item 1: head tows 8..9 of 16, and tow 8 alone): the
// facing edges are looked for within 0.75 of the laid width, so the next course but one is not
// taken for a neighbour. Centre lines n w + g apart (n tows; the band's offset from the tool
// point is the same on both courses) leave a gap g, or an overlap -g, read on course 2's first
// line; laid edge to edge, nothing.
TEST(AfpGaps, NarrowCoursesGapAndOverlapByTheirSpacing) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  for (const auto& [n, mask] :
       {std::pair{2, std::uint64_t{0x180}}, std::pair{1, std::uint64_t{0x80}}}) {
    for (const double g : {0.0, 1.0, -1.2}) {
      SCOPED_TRACE(::testing::Message() << n << " tows, offset " << g);
      const Report report =
          RunLines(*scene, TwoCourses(*scene->surface, n * kTowWidth + g, false, mask, 0.0, mask));
      const RuleSummary* gap = RuleOf(report, "afp.gap");
      const RuleSummary* overlap = RuleOf(report, "afp.overlap");
      ASSERT_NE(gap, nullptr);
      ASSERT_NE(overlap, nullptr);
      EXPECT_GT(gap->checked, 0);
      const RuleSummary* fired = g > 0 ? gap : overlap;
      const RuleSummary* quiet = g > 0 ? overlap : gap;
      EXPECT_NEAR(fired->worst_value.value_or(0.0), std::abs(g), 1e-6);
      EXPECT_NEAR(quiet->worst_value.value_or(0.0), 0.0, 1e-9);
      EXPECT_EQ(quiet->errors, 0);
      EXPECT_EQ(fired->errors, g == 0.0 ? 0 : 4);
      if (g != 0.0) {
        ASSERT_FALSE(fired->findings.empty());
        EXPECT_EQ(fired->findings.front().line, 20);
      }
    }
  }
}

TEST(AfpGaps, CoursesFarApartAreNotNeighbours) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const Report report = RunLines(*scene, TwoCourses(*scene->surface, 16 * kTowWidth + 40, false));
  const RuleSummary* gap = RuleOf(report, "afp.gap");
  ASSERT_NE(gap, nullptr);
  EXPECT_EQ(gap->checked, 0);
}

TEST(AfpGaps, ATowCutBetweenLaidTowsIsAGapOfItsWidth) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  // Course 2 touches course 1 exactly but lays without tows 5 and 6.
  const std::uint64_t mask = 0xFFFF & ~std::uint64_t{0x30};
  const Report report = RunLines(*scene, TwoCourses(*scene->surface, 16 * kTowWidth, false, mask));
  const RuleSummary* gap = RuleOf(report, "afp.gap");
  ASSERT_NE(gap, nullptr);
  EXPECT_NEAR(*gap->worst_value, 2 * kTowWidth, 1e-9);
  EXPECT_EQ(gap->errors, 4);
  ASSERT_FALSE(gap->findings.empty());
  EXPECT_EQ(gap->findings.front().line, 20);
  EXPECT_EQ(gap->findings.front().subject, "tow 5");
}

// Where the course's centre passes within half a course and a tow width of its ply's boundary
// the coverage policy cuts tows one by one (afp.coverage judges what is left bare): a hole
// there is not a gap finding; the same hole in the ply's interior is.
TEST(AfpGaps, ATowCutAtThePlyBoundaryIsLeftToTheCoveragePolicy) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene::PlySpec ply;
  ply.name = "p";
  ply.boundary_uv = {{-200, -60}, {200, -60}, {200, 170}, {-200, 170}};
  scene->plies.push_back(ply);
  const std::uint64_t mask = 0xFFFF & ~std::uint64_t{0x30};
  const Report report = RunLines(*scene, TwoCourses(*scene->surface, 16 * kTowWidth, false, mask));
  const RuleSummary* gap = RuleOf(report, "afp.gap");
  ASSERT_NE(gap, nullptr);
  // Lines 20 (u -200..-100) and 23 (100..200) reach the ply's ends; 21 and 22 do not.
  EXPECT_EQ(gap->errors, 2);
  ASSERT_EQ(gap->findings.size(), 2u);
  EXPECT_EQ(gap->findings[0].line, 21);
  EXPECT_EQ(gap->findings[1].line, 22);
}

// The band a tow width inside the ply's boundary is left to the coverage policy only where the
// boundary meets the courses at a slant (tows cut one by one there leave bare triangles): a
// 1 mm seam gap at v = 8 w .. 8 w + 1 with the ply's edge parallel to the courses half a tow
// beyond it (v = 8.5 w + 1) is a gap on all four lines of course 2 (a seam 3 mm inside the ply,
// which afp.coverage's 2 % of bare area would not see); with that edge slanted 30 deg across
// the courses (a tow cut every 11 mm) the stretch of seam within a tow width of it is left to
// the coverage policy.
TEST(AfpGaps, ASeamGapBesideAParallelPlyEdgeIsAGapAndBesideASlantedEdgeIsNot) {
  const double edge_v = 8.5 * kTowWidth + 1.0;
  // afp.gap over the two courses 1 mm apart in a ply whose edge runs from (-300, left_v) to
  // (300, right_v).
  auto gap_beside = [&](double left_v, double right_v) {
    auto scene = AfpScene(geom::MakePlane(4000, 4000));
    scene::PlySpec ply;
    ply.name = "p";
    ply.boundary_uv = {{-300, -60}, {300, -60}, {300, right_v}, {-300, left_v}};
    scene->plies.push_back(ply);
    const Report report =
        RunLines(*scene, TwoCourses(*scene->surface, 16 * kTowWidth + 1.0, false));
    const RuleSummary* gap = RuleOf(report, "afp.gap");
    return gap == nullptr ? RuleSummary{} : *gap;
  };
  const RuleSummary parallel = gap_beside(edge_v, edge_v);
  EXPECT_EQ(parallel.errors, 4);
  ASSERT_TRUE(parallel.worst_value.has_value());
  EXPECT_NEAR(*parallel.worst_value, 1.0, 1e-6);
  // The edge v = edge_v + u tan 30: course 2's facing edge (v = 8 w + 1) enters the ply at
  // u = -5.5 and is within a tow width of the edge (measured square to it) for u in
  // -18.2 .. 7.2. Outside it is trimmed off (line 20, and line 21 from u -100 to -18.2), in
  // the band left to the coverage policy (lines 21 and 22 up to u 7.2), beyond it a gap
  // (line 22 from u 7.2, line 23).
  const double k = std::tan(30.0 * kPi / 180.0);
  const RuleSummary slanted = gap_beside(edge_v - 300 * k, edge_v + 300 * k);
  EXPECT_EQ(slanted.errors, 2);
  ASSERT_EQ(slanted.findings.size(), 2u);
  EXPECT_EQ(slanted.findings[0].line, 22);
  EXPECT_EQ(slanted.findings[1].line, 23);
}

// Past the ply's end (extended tow ends are trimmed off the part) and within a tow width of its
// boundary (left to the coverage policy) a gap or overlap between two courses is not judged: a
// 1 mm gap along u -200..200 with the ply ending at u = 50 fires on lines 20 to 22 (each has
// edge points inside the ply, more than a tow width from its end) and not on 23 (u 100..200,
// wholly outside); the same courses overlapping by 1.2 mm, likewise.
TEST(AfpGaps, GapsAndOverlapsWhollyOutsideThePlyAreTrimmedOff) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene::PlySpec ply;
  ply.name = "p";
  ply.boundary_uv = {{-300, -60}, {50, -60}, {50, 170}, {-300, 170}};
  scene->plies.push_back(ply);
  for (const auto& [offset, id] : {std::pair{1.0, "afp.gap"}, std::pair{-1.2, "afp.overlap"}}) {
    SCOPED_TRACE(id);
    const Report report =
        RunLines(*scene, TwoCourses(*scene->surface, 16 * kTowWidth + offset, false));
    const RuleSummary* rule = RuleOf(report, id);
    ASSERT_NE(rule, nullptr);
    EXPECT_EQ(rule->errors, 3);
    ASSERT_EQ(rule->findings.size(), 3u);
    EXPECT_EQ(rule->findings.back().line, 22);
    EXPECT_NEAR(rule->findings.back().value, std::abs(offset), 1e-6);
  }
}

TEST(AfpGaps, TowBitsBeyondTheHeadAreFindings) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const Report report = RunLines(*scene, TwoCourses(*scene->surface, 16 * kTowWidth, false,
                                                    0xFFFF | (std::uint64_t{1} << 20)));
  const RuleSummary* gap = RuleOf(report, "afp.gap");
  ASSERT_NE(gap, nullptr);
  EXPECT_EQ(gap->errors, 4);
  ASSERT_FALSE(gap->findings.empty());
  EXPECT_EQ(gap->findings.front().subject, "tow mask");
}

}  // namespace
}  // namespace stitchsim::verify

namespace stitchsim::verify {
namespace {

// M62 P0 sets all 64 bits of the modal mask: every tow, not bits beyond the head.
TEST(AfpGaps, AllBitsSetIsEveryTowNotAFinding) {
  const auto scene = testing::AfpScene(geom::MakePlane(4000, 4000));
  const Report report = testing::RunLines(
      *scene, TwoCourses(*scene->surface, 16 * testing::kTowWidth, false, ~std::uint64_t{0}));
  const RuleSummary* gap = testing::RuleOf(report, "afp.gap");
  ASSERT_NE(gap, nullptr);
  EXPECT_EQ(gap->errors, 0);
  EXPECT_GT(gap->checked, 0);
}

}  // namespace
}  // namespace stitchsim::verify
