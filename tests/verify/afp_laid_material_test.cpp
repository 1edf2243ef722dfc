// The verifier's laid material (Verifier::Laid(), afp_laid_material.h) against closed forms:
// on a plane z = 0 ((u, v) = (x, y)) a course travelling along +y with the tool at x = x0
// has boundary b of the 16-tow head at x = x0 + (b - k/2) w (b = t - 1: tow t's left edge),
// its uv equal to (x, y); stations at most the spacing apart with both ends present.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "afp_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

using testing::AfpScene;
using testing::kTowWidth;
using testing::LayLine;
using testing::ToolAt;

// Runs a verifier that keeps stitch marks (as verify --snapshots / --html) over `lines`.
void RunKeeping(const scene::Scene& scene, const std::vector<trace::LineRecord>& lines,
                const std::function<void(const Verifier&)>& then, bool keep = true) {
  testing::RunLines(scene, lines, then, keep);
}

TEST(AfpLaidMaterial, AStraightCourseOnAPlaneHasItsTowBoundariesInClosedForm) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const geom::Surface& s = *scene->surface;
  const Eigen::Vector2d along(0, 1);
  const double x0 = 30.0;
  // Line 10: 0 .. 130 mm along y; line 11: 130 .. 140 (continues it, shares a station).
  const std::vector<trace::LineRecord> lines = {
      LayLine(10, ToolAt(s, {x0, 0}, along), ToolAt(s, {x0, 130}, along)),
      LayLine(11, ToolAt(s, {x0, 130}, along), ToolAt(s, {x0, 140}, along))};
  RunKeeping(*scene, lines, [&](const Verifier& v) {
    const LaidMaterial& m = v.Laid();
    ASSERT_EQ(m.tows, 16);
    EXPECT_DOUBLE_EQ(m.tow_width_mm, kTowWidth);
    ASSERT_EQ(m.strips.size(), 2U);
    EXPECT_EQ(m.strips[0].line, 10);
    EXPECT_EQ(m.strips[1].line, 11);
    EXPECT_EQ(m.strips[1].first_station, m.strips[0].first_station + m.strips[0].station_count - 1);
    ASSERT_EQ(m.boundary.size(), m.stations.size() * 17);
    for (const LaidStrip& strip : m.strips) {
      ASSERT_GE(strip.station_count, 2U);
      const LaidStation& first = m.stations[strip.first_station];
      const LaidStation& last = m.stations[strip.first_station + strip.station_count - 1];
      const double y0 = strip.line == 10 ? 0.0 : 130.0, y1 = strip.line == 10 ? 130.0 : 140.0;
      EXPECT_NEAR(first.tool.y(), y0, 1e-4);  // both ends present
      EXPECT_NEAR(last.tool.y(), y1, 1e-4);
      for (std::uint32_t i = 0; i < strip.station_count; ++i) {
        const std::size_t st = strip.first_station + i;
        if (i > 0) {
          EXPECT_LE((m.stations[st].tool - m.stations[st - 1].tool).norm(), m.spacing_mm + 1e-4);
        }
        EXPECT_NEAR(m.stations[st].normal.z(), 1.0, 1e-6);
        for (int b = 0; b <= 16; ++b) {
          const double x = x0 + (b - 8) * kTowWidth;
          EXPECT_NEAR(m.Boundary(st, b).x(), x, 1e-4) << "station " << st << " boundary " << b;
          EXPECT_NEAR(m.Boundary(st, b).y(), m.stations[st].tool.y(), 1e-4);
          EXPECT_NEAR(m.Boundary(st, b).z(), 0.0, 1e-4);
          EXPECT_NEAR(m.BoundaryUv(st, b).x(), m.Boundary(st, b).x(), 1e-4);
          EXPECT_NEAR(m.BoundaryUv(st, b).y(), m.Boundary(st, b).y(), 1e-4);
        }
      }
    }
    // 130 mm at most 25 mm apart: at least 7 stations on line 10.
    EXPECT_GE(m.strips[0].station_count, 7U);
    // Adds on line 10 and cuts on line 11, one per tow.
    ASSERT_EQ(m.events.size(), 32U);
  });
}

}  // namespace
}  // namespace stitchsim::verify
