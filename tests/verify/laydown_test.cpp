// Laydown figures (verify/laydown.h, issue 29 Done-when 4) against hand computations: one
// straight course on a plane, 16 tows, 600 mm at F12000 (200 mm/s; the dialect's F is mm/min),
// tow 5 cut at x = 300 and added back at x = 450, the head slowing to 150 mm/s within 25 mm of
// every cut and add (the course's start adds every tow, its end cuts them). The time with the
// controller's ramps is worked out below as trapezoids in plain arithmetic (a = feed / 0.25 s,
// docs/timing.md), not by the code under test.
#include "stitchsim/verify/laydown.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "afp_test_support.h"

namespace stitchsim::verify {
namespace {

using testing::AfpScene;
using testing::LayLine;
using testing::RunLines;
using testing::ToolAt;

constexpr std::uint64_t kAll = 0xFFFF;
constexpr std::uint64_t kAllButTow5 = 0xFFFF & ~(1ULL << 4);

trace::LineRecord OffPart(int line, double duration_s, double timed_s) {
  trace::LineRecord l;
  l.source_line = line;
  l.rapid = true;
  l.head_retracted = true;
  l.ply = 1;
  l.duration_s = duration_s;
  l.timed_duration_s = timed_s;
  return l;
}

// Approach (off-part 2 s, 2.4 s timed), the course in three lines, leave (1 s, 1.3 s).
std::vector<trace::LineRecord> Course(const geom::Surface& s) {
  const Eigen::Vector2d dir(1, 0);
  auto at = [&](double x) { return ToolAt(s, Eigen::Vector2d(x, 0), dir); };
  std::vector<trace::LineRecord> lines = {OffPart(9, 2.0, 2.4), LayLine(10, at(0), at(300), kAll),
                                          LayLine(11, at(300), at(450), kAllButTow5),
                                          LayLine(12, at(450), at(600), kAll),
                                          OffPart(13, 1.0, 1.3)};
  for (auto& l : lines)
    if (!l.rapid) l.feed_mm_per_min = 12000;  // 200 mm/s
  return lines;
}

std::unique_ptr<scene::Scene> SlowingScene() {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene->head.afp.cut_add_feed_mm_s = 150;
  scene->head.afp.cut_add_zone_mm = 25;
  return scene;
}

// The hand computation. Slow zones (150 mm/s): [0, 25], [275, 325], [425, 475], [575, 600];
// 200 mm/s between. Ramps at a = v / 0.25 s: 600 mm/s^2 at 150, 800 mm/s^2 at 200.
double HandRampedTime() {
  // [0, 25]: from rest to 150 at 600 mm/s^2: 0.25 s over 150^2 / 1200 = 18.75 mm, then
  // 6.25 mm at 150. [575, 600] the same backwards.
  const double ends = 2 * (0.25 + 6.25 / 150);
  // A 200 mm/s stretch between zones: 150 -> 200 and back at 800 mm/s^2, 0.0625 s each over
  // (200^2 - 150^2) / 1600 = 10.9375 mm each, the rest at 200. Stretches of 250, 100, 100 mm.
  auto stretch = [](double len) { return 2 * 0.0625 + (len - 2 * 10.9375) / 200; };
  const double fast = stretch(250) + stretch(100) + stretch(100);
  const double zones = 2 * 50.0 / 150;  // [275, 325] and [425, 475] at 150 throughout
  return ends + fast + zones;           // 3.546875 s
}

TEST(Laydown, OneCourseWithACutAndAnAddMatchesTheHandComputation) {
  auto scene = SlowingScene();
  const Report report = RunLines(*scene, Course(*scene->surface));
  ASSERT_EQ(report.laydown.size(), 2u);  // ply 1, then the whole programme
  const LaydownFigures& ply = report.laydown[0];
  EXPECT_EQ(ply.ply, 1);
  EXPECT_EQ(report.laydown[1].ply, 0);
  EXPECT_NEAR(ply.laid_path_mm, 600.0, 1e-9);
  // Programmed feeds with the zones: 150 mm at 150 mm/s, 450 mm at 200 mm/s.
  EXPECT_NEAR(ply.laydown_s, 150.0 / 150 + 450.0 / 200, 1e-9);
  const double hand = HandRampedTime();
  EXPECT_NEAR(hand, 3.546875, 1e-12);
  EXPECT_NEAR(ply.laydown_timed_s, hand, 0.01 * hand);
  EXPECT_NEAR(ply.off_part_s, 3.0, 1e-12);
  EXPECT_NEAR(ply.off_part_timed_s, 3.7, 1e-12);
  // 16 tows added at the start, tow 5 again at 450; 16 cut at the end, tow 5 at 300.
  EXPECT_EQ(ply.tows_added, 17);
  EXPECT_EQ(ply.tows_cut, 17);
  ASSERT_TRUE(ply.shortest_tow_mm);
  EXPECT_NEAR(*ply.shortest_tow_mm, 150.0, 1e-9);
  // 15 tows of 600 mm and tow 5's 300 + 150 mm, 6.35 mm wide, 300 g/m^2 (no material given).
  const double kg = (15 * 600.0 + 450.0) * 6.35 * 300.0 * 1e-9;
  EXPECT_NEAR(ply.tow_length_mm, 9450.0, 1e-9);
  EXPECT_NEAR(ply.material_kg, kg, 1e-15);
  EXPECT_NEAR(ply.rate_kg_h, kg / ((hand + 3.7) / 3600), 0.01 * kg / ((hand + 3.7) / 3600));
  // The whole programme is the one ply here.
  EXPECT_EQ(report.laydown[1].tows_added, 17);
  EXPECT_NEAR(report.laydown[1].laydown_s, ply.laydown_s, 1e-12);
}

TEST(Laydown, TheMaterialsArealWeightIsUsed) {
  auto scene = SlowingScene();
  scene::PlySpec p;
  p.name = "light";
  p.areal_weight_g_m2 = 150.0;
  scene->plies.push_back(p);
  const Report report = RunLines(*scene, Course(*scene->surface));
  ASSERT_FALSE(report.laydown.empty());
  EXPECT_NEAR(report.laydown[0].material_kg, 9450.0 * 6.35 * 150.0 * 1e-9, 1e-15);
}

TEST(Laydown, WithoutSlowZonesTheFeedTimeIsLengthOverFeed) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));  // no cut_add_* given
  const Report report = RunLines(*scene, Course(*scene->surface));
  ASSERT_FALSE(report.laydown.empty());
  EXPECT_NEAR(report.laydown[0].laydown_s, 3.0, 1e-12);
  // One 600 mm trapezoid at 200 mm/s, a = 800 mm/s^2: 2 x 0.25 s of ramps over 25 mm each.
  EXPECT_NEAR(report.laydown[0].laydown_timed_s, 0.5 + 550.0 / 200, 1e-9);
}

TEST(Laydown, RampedTimeIsTheTimingDocsHandCase) {
  // docs/timing.md's worked example: 1000 mm at 100 mm/s, ramp 0.25 s: 10.25 s.
  EXPECT_NEAR(RampedTime({{1000.0, 100.0}}, 0.25), 10.25, 1e-12);
  // Cut into lines it is the same path: the speed carries across.
  EXPECT_NEAR(RampedTime({{300.0, 100.0}, {700.0, 100.0}}, 0.25), 10.25, 1e-12);
  // Too short for the cruise: a triangle, peak sqrt(a d) = sqrt(400 x 10) mm/s.
  EXPECT_NEAR(RampedTime({{10.0, 100.0}}, 0.25), 2 * std::sqrt(400.0 * 10.0) / 400.0, 1e-12);
}

TEST(Laydown, OverlappingZonesMerge) {
  // Events at 100 and 130 with 25 mm zones: one slow stretch [75, 155] of 80 mm.
  const std::vector<FeedPiece> pieces =
      SlowZonePieces({{400.0, 200.0}}, {100.0, 130.0}, 25.0, 150.0);
  EXPECT_NEAR(FeedTime(pieces), 80.0 / 150 + 320.0 / 200, 1e-12);
}

}  // namespace
}  // namespace stitchsim::verify
