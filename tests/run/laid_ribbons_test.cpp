// The overview's ribbons from a hand-made laid material on the plane z = 0: a course along x
// with the 16-tow head's boundaries at y = (b - 8) w. Closed form: tow t's ribbon runs at
// y = (t - 8.5) w, 0.5 mm above the plane, w / 2 wide each side; merged k tows at a time a
// group's ribbon is as wide as its first to last laid tow; past the budget every n-th station.
#include "stitchsim/run/laid_ribbons.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "run_test_support.h"

namespace stitchsim::run {
namespace {

constexpr int kTows = 16;
constexpr double kW = 6.35;

verify::LaidMaterial Empty() { return testing::EmptyLaid(kTows, kW, 25.0); }

// A line of ply `ply` (its course 1) laying `tows`, `stations` stations 25 mm apart along x;
// `joined`: it starts on the previous line's last station (shared, as the verifier keeps it).
void AddStrip(verify::LaidMaterial& m, int ply, std::uint64_t tows, int stations,
              bool joined = false) {
  verify::LaidStrip s;
  s.line = 10 * static_cast<int>(m.strips.size() + 1);
  s.ply = ply;
  s.course = 1;
  s.tows = tows;
  s.first_station = static_cast<std::uint32_t>(m.stations.size() - (joined ? 1 : 0));
  s.station_count = static_cast<std::uint32_t>(stations);
  for (int i = joined ? 1 : 0; i < stations; ++i) {
    const float x = 25.0F * static_cast<float>(m.stations.size());
    verify::LaidStation st;
    st.tool = Eigen::Vector3f(x, 0, 0);
    m.stations.push_back(st);
    for (int b = 0; b <= kTows; ++b) {
      m.boundary.emplace_back(x, static_cast<float>((b - kTows / 2) * kW), 0.0F);
      m.boundary_uv.emplace_back(0.0F, 0.0F);
    }
  }
  m.strips.push_back(s);
}

verify::LaidMaterial OneStrip(std::uint64_t tows) {
  verify::LaidMaterial m = Empty();
  AddStrip(m, 1, tows, 5);
  return m;
}

TEST(LaidRibbons, OneRibbonPerTowOnItsCentreLineLiftedOffThePart) {
  const LaidRibbons r = MakeLaidRibbons(OneStrip(0xFFFF), 1000);
  EXPECT_EQ(r.tows_per_ribbon, 1);
  EXPECT_EQ(r.station_step, 1);
  ASSERT_EQ(r.sets.size(), 16U);
  EXPECT_EQ(r.segments, 16U * 4U);
  for (int t = 1; t <= kTows; ++t) {
    const RenderRequest::PointSet& s = r.sets[static_cast<std::size_t>(t - 1)];
    EXPECT_EQ(s.label, "afp_ply_1");
    EXPECT_TRUE(s.polyline);
    EXPECT_NEAR(s.radius_mm, 0.5 * kW, 1e-9);
    ASSERT_EQ(s.points_part_mm.size(), 5U);
    ASSERT_EQ(s.normals_part.size(), 5U);
    for (std::size_t i = 0; i < 5; ++i) {
      EXPECT_NEAR(s.points_part_mm[i].x(), 25.0 * static_cast<double>(i), 1e-4);
      EXPECT_NEAR(s.points_part_mm[i].y(), (t - 8.5) * kW, 1e-4);
      EXPECT_NEAR(s.points_part_mm[i].z(), kRibbonLiftMm, 1e-6);
      EXPECT_NEAR(s.normals_part[i].z(), 1.0, 1e-9);
    }
  }
  ASSERT_EQ(r.legend.size(), 1U);
  EXPECT_EQ(r.legend.front().label, "ply 1");
}

TEST(LaidRibbons, ThinnedByMergingTowsThenStations) {
  // 64 segments one per tow: a budget of 20 merges 4 tows a ribbon (16 segments).
  const LaidRibbons four = MakeLaidRibbons(OneStrip(0xFFFF), 20);
  EXPECT_EQ(four.tows_per_ribbon, 4);
  ASSERT_EQ(four.sets.size(), 4U);
  for (int g = 0; g < 4; ++g) {
    const auto& s = four.sets[static_cast<std::size_t>(g)];
    EXPECT_NEAR(s.radius_mm, 2.0 * kW, 1e-9);
    EXPECT_NEAR(s.points_part_mm.front().y(), (4 * g - 6) * kW, 1e-4);
  }
  // Tows 1..3 laid only: the first group is 3 tows wide, centred between boundaries 0 and 3.
  const LaidRibbons part = MakeLaidRibbons(OneStrip(0x7), 2);
  ASSERT_EQ(part.sets.size(), 1U);
  EXPECT_EQ(part.tows_per_ribbon, 16);
  EXPECT_NEAR(part.sets.front().radius_mm, 1.5 * kW, 1e-9);
  EXPECT_NEAR(part.sets.front().points_part_mm.front().y(), (1.5 - 8) * kW, 1e-4);
  // One ribbon of 4 segments over a budget of 2: every 2nd station, the ends kept.
  EXPECT_EQ(part.station_step, 2);
  ASSERT_EQ(part.sets.front().points_part_mm.size(), 3U);
  EXPECT_NEAR(part.sets.front().points_part_mm.back().x(), 100.0, 1e-4);
}

TEST(LaidRibbons, JoinedLinesOfACourseMakeOneRibbonUntilTheSpanChanges) {
  verify::LaidMaterial m = Empty();
  AddStrip(m, 1, 0xFFFF, 3);
  AddStrip(m, 1, 0xFFFF, 3, true);               // stations 2..4: one ribbon over 5 stations
  AddStrip(m, 1, 0x7FFF, 3, true);               // tow 16 cut: the span changes, a new ribbon
  const LaidRibbons r = MakeLaidRibbons(m, 10);  // 8 tows a ribbon: 12 segments; 16: 6
  EXPECT_EQ(r.tows_per_ribbon, 16);
  ASSERT_EQ(r.sets.size(), 2U);
  EXPECT_EQ(r.sets[0].points_part_mm.size(), 5U);
  EXPECT_NEAR(r.sets[0].points_part_mm.back().x(), 100.0, 1e-4);
  EXPECT_NEAR(r.sets[1].radius_mm, 7.5 * kW, 1e-9);
  EXPECT_EQ(r.segments, 4U + 2U);
}

TEST(LaidRibbons, APlyAboveIsLiftedHigherAndTheLegendListsEightPliesFromTheTop) {
  verify::LaidMaterial m = Empty();
  for (int ply = 1; ply <= 13; ++ply) AddStrip(m, ply, 0x1, 2);
  // A station off the surface (NaN) leaves no ribbon point.
  m.boundary[0].x() = std::numeric_limits<float>::quiet_NaN();
  AddStrip(m, 2, 0x1, 2);
  const LaidRibbons r = MakeLaidRibbons(m, 1000);
  ASSERT_EQ(r.sets.size(), 13U);  // ply 1's strip has one point left: no ribbon
  EXPECT_EQ(r.sets.front().label, "afp_ply_2");
  EXPECT_NEAR(r.sets.front().points_part_mm.front().z(), kRibbonLiftMm + kRibbonPlyStepMm, 1e-6);
  ASSERT_EQ(r.legend.size(), 9U);
  EXPECT_EQ(r.legend[0].label, "ply 13");
  EXPECT_EQ(r.legend[7].label, "ply 6");
  EXPECT_EQ(r.legend.back().label, "...");
  EXPECT_TRUE(r.hidden_plies.empty());
  EXPECT_NE(PlyColour(1), PlyColour(2));
}

// Past the budget with one ribbon a line, the lowest plies go before any station does: three
// plies of one 5-station line (4 segments each, 12 in all); a budget of 8 leaves ply 1 out
// and draws every station; a budget of 3 leaves plies 1 and 2 out and draws ply 3's every
// 2nd station; the top ply is always drawn.
TEST(LaidRibbons, TheLowestPliesAreLeftOutBeforeStations) {
  verify::LaidMaterial m = Empty();
  for (int ply = 1; ply <= 3; ++ply) AddStrip(m, ply, 0xFFFF, 5);
  const LaidRibbons eight = MakeLaidRibbons(m, 8);
  EXPECT_EQ(eight.tows_per_ribbon, 16);
  EXPECT_EQ(eight.hidden_plies, std::vector<int>{1});
  EXPECT_EQ(eight.station_step, 1);
  EXPECT_EQ(eight.segments, 8U);
  ASSERT_EQ(eight.legend.size(), 3U);
  EXPECT_EQ(eight.legend[0].label, "ply 3");
  EXPECT_EQ(eight.legend[1].label, "ply 2");
  EXPECT_EQ(eight.legend[2].label, "ply 1 under these: not drawn");
  for (const auto& set : eight.sets) EXPECT_NE(set.label, "afp_ply_1");
  const LaidRibbons three = MakeLaidRibbons(m, 3);
  EXPECT_EQ(three.hidden_plies, (std::vector<int>{1, 2}));
  EXPECT_EQ(three.station_step, 2);
  ASSERT_EQ(three.sets.size(), 1U);
  EXPECT_EQ(three.sets.front().label, "afp_ply_3");
  EXPECT_EQ(three.legend.back().label, "2 plies (1 to 2) under these: not drawn");
}

}  // namespace
}  // namespace stitchsim::run
