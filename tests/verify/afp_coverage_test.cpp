// afp.coverage against closed forms on a plane: a 400 x 64 w ply filled exactly by four
// 16-tow courses (0 % bare, 0 % doubled), with course 2 left out (bare: its share of the
// area beyond the one-tow band, 16 / 62) and with course 3 laid twice (doubled: the same).
// A scene without plies skips the rule with a note.
#include <gtest/gtest.h>

#include "afp_test_support.h"

namespace stitchsim::verify {
namespace {

using namespace testing;

std::unique_ptr<scene::Scene> PlyScene() {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene::PlySpec ply;
  ply.name = "skin";
  ply.boundary_uv = {{0, 0}, {400, 0}, {400, 64 * kTowWidth}, {0, 64 * kTowWidth}};
  scene->plies.push_back(ply);
  return scene;
}

// Courses (1-based, by centre 8 w, 24 w, ...) laid in the order given, each 420 mm long.
std::vector<trace::LineRecord> Courses(const geom::Surface& plane, const std::vector<int>& order) {
  std::vector<trace::LineRecord> lines;
  const Eigen::Vector2d x(1, 0);
  int line = 10;
  for (std::size_t n = 0; n < order.size(); ++n) {
    const double v = (16 * order[n] - 8) * kTowWidth;
    for (int i = 0; i < 3; ++i) {
      lines.push_back(LayLine(line++, ToolAt(plane, Eigen::Vector2d(-10 + 140 * i, v), x),
                              ToolAt(plane, Eigen::Vector2d(130 + 140 * i, v), x), 0xFFFF,
                              static_cast<int>(n) + 1));
    }
  }
  return lines;
}

TEST(AfpCoverage, FilledPlyIsCoveredOnceAndACourseLeftOutOrDoubledIsItsShare) {
  const auto scene = PlyScene();
  struct Case {
    std::vector<int> order;
    double bare, doubled;
    long errors;
  };
  const double share = 16.0 / 62.0 * 100.0;
  for (const Case& c : {Case{{1, 2, 3, 4}, 0.0, 0.0, 0}, Case{{1, 3, 4}, share, 0.0, 1},
                        Case{{1, 2, 3, 3, 4}, 0.0, share, 1}}) {
    SCOPED_TRACE(c.order.size());
    const Report report = RunLines(*scene, Courses(*scene->surface, c.order));
    const RuleSummary* rule = RuleOf(report, "afp.coverage");
    ASSERT_NE(rule, nullptr);
    EXPECT_NEAR(*SubjectOf(*rule, "bare").worst_value, c.bare, 0.2);
    EXPECT_NEAR(*SubjectOf(*rule, "doubled").worst_value, c.doubled, 0.2);
    EXPECT_EQ(rule->errors, c.errors);
    if (c.errors > 0) {
      EXPECT_EQ(rule->findings.front().line, 9 + 3 * static_cast<int>(c.order.size()));
    }
  }
}

TEST(AfpCoverage, ASceneWithoutPliesSkipsTheRule) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const Report report = RunLines(*scene, Courses(*scene->surface, {1}));
  EXPECT_EQ(RuleOf(report, "afp.coverage"), nullptr);
  ASSERT_FALSE(report.skipped.empty());
  EXPECT_EQ(report.skipped.front().id, "afp.coverage");
  EXPECT_NE(RuleOf(report, "afp.gap"), nullptr);
}

}  // namespace
}  // namespace stitchsim::verify
