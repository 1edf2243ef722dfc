// The verifier's laid material (Verifier::Laid(), afp_laid_material.h) against closed forms:
// on a plane z = 0 ((u, v) = (x, y)) a course travelling along +y with the tool at x = x0
// has boundary b of the 16-tow head at x = x0 + (b - k/2) w (b = t - 1: tow t's left edge),
// its uv equal to (x, y); stations at most the spacing apart with both ends present. A tow
// cut and re-added mid-course: its events on the lines and at the points a hand computation
// gives. Round a convex cylinder (tool poses from the closed form): every boundary lies on
// the cylinder and its v unrolls to the arc length R theta of its own point. The per-tow
// figures equal what afp.fiber_angle and afp.steering_radius report (a course turned 4 deg
// reads 4 deg; a circle of R 500 steers tow t on R + (t - 8.5) w). Nothing is kept for a
// stitching head or without keep_stitch_marks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "afp_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/process/afp_steering.h"

namespace stitchsim::verify {
namespace {

using testing::AfpScene;
using testing::kTowWidth;
using testing::LayLine;
using testing::RoundCylinder;
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

// The centre of head tow `tow` (16-tow head) across a course along +y with the tool at x = 0.
double TowCentreX(int tow) { return (tow - 1 - 8 + 0.5) * kTowWidth; }

TEST(AfpLaidMaterial, ATowCutAndReAddedMidCourseHasItsEventsWhereTheProgrammeSays) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const geom::Surface& s = *scene->surface;
  const Eigen::Vector2d along(0, 1);
  auto at = [&](double y) { return ToolAt(s, {0, y}, along); };
  // Course 1: line 20 (y 0 .. 50) all tows; 21 (50 .. 100) all but tow 5; 22, 23 all tows.
  // Line 24: head up (lays nothing). Course 2, line 25 (y 300 .. 340): tows 1 and 2 only.
  trace::LineRecord up = LayLine(24, at(200), at(300));
  up.head_retracted = true;
  const std::vector<trace::LineRecord> lines = {
      LayLine(20, at(0), at(50)),
      LayLine(21, at(50), at(100), testing::AllTowsBut(5)),
      LayLine(22, at(100), at(150)),
      LayLine(23, at(150), at(200)),
      up,
      LayLine(25, at(300), at(340), 0x3, 2)};
  RunKeeping(*scene, lines, [&](const Verifier& v) {
    const LaidMaterial& m = v.Laid();
    ASSERT_EQ(m.strips.size(), 5U);  // line 24 lays nothing
    // Hand: 16 adds on line 20 at y 0; tow 5 cut on line 20 at y 50 and added on line 22
    // at y 100; 16 cuts on line 23 at y 200 (the head lifts); course 2: tows 1, 2 added on
    // line 25 at y 300 and cut there at y 340.
    struct Expected {
      TowEvent::Kind kind;
      int line, course, tow;
      double y;
    };
    std::vector<Expected> expected;
    for (int t = 1; t <= 16; ++t) expected.push_back({TowEvent::Kind::kAdd, 20, 1, t, 0.0});
    expected.push_back({TowEvent::Kind::kCut, 20, 1, 5, 50.0});
    expected.push_back({TowEvent::Kind::kAdd, 22, 1, 5, 100.0});
    for (int t = 1; t <= 16; ++t) expected.push_back({TowEvent::Kind::kCut, 23, 1, t, 200.0});
    for (int t = 1; t <= 2; ++t) expected.push_back({TowEvent::Kind::kAdd, 25, 2, t, 300.0});
    for (int t = 1; t <= 2; ++t) expected.push_back({TowEvent::Kind::kCut, 25, 2, t, 340.0});
    ASSERT_EQ(m.events.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const TowEvent& e = m.events[i];
      const Expected& x = expected[i];
      EXPECT_EQ(e.kind, x.kind) << "event " << i;
      EXPECT_EQ(e.line, x.line) << "event " << i;
      EXPECT_EQ(e.course, x.course) << "event " << i;
      EXPECT_EQ(e.ply, 1);
      EXPECT_EQ(e.tow, x.tow) << "event " << i;
      EXPECT_EQ(m.strips[e.strip].line, x.line);
      EXPECT_NEAR(e.point.x(), TowCentreX(x.tow), 1e-4) << "event " << i;
      EXPECT_NEAR(e.point.y(), x.y, 1e-4) << "event " << i;
      EXPECT_NEAR(e.point.z(), 0.0, 1e-4);
      EXPECT_NEAR(e.uv.x(), TowCentreX(x.tow), 1e-4);
      EXPECT_NEAR(e.uv.y(), x.y, 1e-4);
    }
    // Line 21's mask leaves tow 5 out; course 2 starts a strip of its own stations.
    EXPECT_EQ(m.strips[1].tows, testing::AllTowsBut(5));
    EXPECT_EQ(m.strips[4].first_station, m.strips[3].first_station + m.strips[3].station_count);
    EXPECT_FLOAT_EQ(m.strips[0].feed_mm_s, 100.0F);  // F6000 mm/min
  });
}

TEST(AfpLaidMaterial, RoundACylinderBoundariesLieOnItAndUnrollToTheArcLength) {
  const double r = 400.0;
  auto scene = AfpScene(geom::MakeCylinder(r, true, 2000, 2400));
  std::vector<trace::LineRecord> lines;
  const double step = 60.0 / r;  // 60 mm of arc a line: stations thinned between the ends
  for (int i = 0; i < 8; ++i) {
    lines.push_back(
        LayLine(40 + i, RoundCylinder(r, (i - 4) * step), RoundCylinder(r, (i - 3) * step)));
  }
  RunKeeping(*scene, lines, [&](const Verifier& v) {
    const LaidMaterial& m = v.Laid();
    ASSERT_EQ(m.strips.size(), 8U);
    ASSERT_GT(m.stations.size(), 16U);
    for (std::size_t st = 0; st < m.stations.size(); ++st) {
      ASSERT_TRUE(m.stations[st].on_surface);
      for (int b = 0; b <= 16; ++b) {
        const Eigen::Vector3d p = m.Boundary(st, b).cast<double>();
        const Eigen::Vector2d uv = m.BoundaryUv(st, b).cast<double>();
        // On the cylinder (axis x at z = -r), to float's resolution (1e-6 relative).
        EXPECT_NEAR(std::hypot(p.y(), p.z() + r), r, 1e-6 * r) << st << " " << b;
        // v is the arc length from the crown: R theta of the point itself; u its x.
        EXPECT_NEAR(uv.y(), r * std::atan2(p.y(), p.z() + r), 1e-4) << st << " " << b;
        EXPECT_NEAR(uv.x(), p.x(), 1e-4);
        EXPECT_NEAR(uv.x(), (b - 8) * kTowWidth, 1e-3);
      }
    }
    // Stations along each line at most the spacing apart (chords of the tool's line).
    for (const LaidStrip& strip : m.strips) {
      EXPECT_GE(strip.station_count, 4U);  // 60 mm: at least 2 between the ends
      for (std::uint32_t i = 1; i < strip.station_count; ++i) {
        const std::size_t st = strip.first_station + i;
        EXPECT_LE((m.stations[st].tool - m.stations[st - 1].tool).norm(), m.spacing_mm + 1e-4);
      }
    }
  });
}

TEST(AfpLaidMaterial, FibreAnglePerLineIsWhatAfpFiberAngleReports) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  scene::PlySpec ply;
  ply.name = "ply";
  ply.direction = Eigen::Vector3d::UnitX();
  ply.projection = -Eigen::Vector3d::UnitZ();
  scene->plies.push_back(ply);
  scene->limits.Set(scene::LimitKey::kAfpFiberAngleMaxDeg, 3.0);
  const geom::Surface& s = *scene->surface;
  const double a = DegToRad(4.0);
  const Eigen::Vector2d dir(std::cos(a), std::sin(a)), x(1, 0);
  const Eigen::Vector2d end = 300.0 * dir;
  // Line 30 turned 4 deg off the 0 deg ply; line 31 along it.
  const std::vector<trace::LineRecord> lines = {
      LayLine(30, ToolAt(s, {0, 0}, dir), ToolAt(s, end, dir)),
      LayLine(31, ToolAt(s, end, x), ToolAt(s, end + Eigen::Vector2d(100, 0), x))};
  RunKeeping(*scene, lines, [&](const Verifier& v) {
    const LaidMaterial& m = v.Laid();
    ASSERT_EQ(m.strips.size(), 2U);
    for (int t = 1; t <= 16; ++t) {
      EXPECT_NEAR(m.FiberAngleDeg(0, t), 4.0, 1e-4) << "tow " << t;
      EXPECT_NEAR(m.FiberAngleDeg(1, t), 0.0, 1e-4) << "tow " << t;
    }
    // The rule's own figure for line 30 (its finding: the worst tow).
    for (const auto& rule : v.Rules()) {
      if (rule->Summary().id != "afp.fiber_angle") continue;
      ASSERT_EQ(rule->Summary().findings.size(), 1U);
      const Finding& f = rule->Summary().findings[0];
      EXPECT_EQ(f.line, 30);
      float worst = 0.0F;
      for (int t = 1; t <= 16; ++t) worst = std::max(worst, m.FiberAngleDeg(0, t));
      EXPECT_FLOAT_EQ(worst, static_cast<float>(f.value));
    }
  });
}

TEST(AfpLaidMaterial, SteeringRadiusPerLineIsWhatAfpSteeringRadiusReports) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const geom::Surface& s = *scene->surface;
  const double r = 500.0, chord = 20.0;
  const double step = 2.0 * std::asin(0.5 * chord / r);
  std::vector<trace::LineRecord> lines;
  for (int i = 0; i < 15; ++i) {
    const double a0 = i * step, a1 = (i + 1) * step;
    lines.push_back(LayLine(10 + i,
                            ToolAt(s, r * Eigen::Vector2d(std::cos(a0), std::sin(a0)),
                                   Eigen::Vector2d(-std::sin(a0), std::cos(a0))),
                            ToolAt(s, r * Eigen::Vector2d(std::cos(a1), std::sin(a1)),
                                   Eigen::Vector2d(-std::sin(a1), std::cos(a1)))));
  }
  RunKeeping(*scene, lines, [&](const Verifier& v) {
    const LaidMaterial& m = v.Laid();
    ASSERT_EQ(m.strips.size(), 15U);
    const RuleSummary* rule = nullptr;
    for (const auto& rl : v.Rules()) {
      if (rl->Summary().id == "afp.steering_radius") rule = &rl->Summary();
    }
    ASSERT_NE(rule, nullptr);
    for (int t = 1; t <= 16; ++t) {
      const double expected = r + (t - 8.5) * kTowWidth;
      float smallest = std::numeric_limits<float>::infinity();
      int measured = 0;
      for (std::size_t k = 0; k < m.strips.size(); ++k) {
        const float f = m.SteeringRadiusMm(k, t);
        if (std::isnan(f)) continue;
        ++measured;
        EXPECT_NEAR(f, expected, 1e-3 * expected) << "tow " << t << " line " << m.strips[k].line;
        smallest = std::min(smallest, f);
      }
      EXPECT_GT(measured, 0) << "tow " << t;
      // The rule's worst for the tow is the smallest the laid material holds for it.
      const SubjectFigure& sub = rule->subjects[static_cast<std::size_t>(t) - 1];
      ASSERT_TRUE(sub.worst_value);
      EXPECT_FLOAT_EQ(smallest, static_cast<float>(*sub.worst_value)) << "tow " << t;
    }
    // Every radius is under the head's 635 mm: the rule reports every line it measured a
    // vertex on, with its smallest tow. The lines the laid material holds radii for, and
    // their smallest, are those (the first line ends less than a half window into the
    // course: NaN for every tow).
    for (int t = 1; t <= 16; ++t) EXPECT_TRUE(std::isnan(m.SteeringRadiusMm(0, t)));
    std::vector<std::pair<int, float>> per_line;
    for (std::size_t k = 0; k < m.strips.size(); ++k) {
      float smallest = std::numeric_limits<float>::quiet_NaN();
      for (int t = 1; t <= 16; ++t) {
        const float f = m.SteeringRadiusMm(k, t);
        if (!std::isnan(f) && !(f >= smallest)) smallest = f;
      }
      if (!std::isnan(smallest)) per_line.emplace_back(m.strips[k].line, smallest);
    }
    ASSERT_EQ(per_line.size(), rule->findings.size());
    for (std::size_t i = 0; i < per_line.size(); ++i) {
      EXPECT_EQ(per_line[i].first, rule->findings[i].line);
      EXPECT_FLOAT_EQ(per_line[i].second, static_cast<float>(rule->findings[i].value));
    }
  });
}

TEST(AfpLaidMaterial, NothingIsKeptForAStitchingHeadOrWithoutStitchMarks) {
  auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const geom::Surface& s = *scene->surface;
  const std::vector<trace::LineRecord> lines = {
      LayLine(10, ToolAt(s, {0, 0}, {0, 1}), ToolAt(s, {0, 100}, {0, 1}))};
  RunKeeping(*scene, lines, [](const Verifier& v) { EXPECT_FALSE(v.Laid().Empty()); });
  RunKeeping(
      *scene, lines,
      [](const Verifier& v) {
        EXPECT_TRUE(v.Laid().Empty());
        EXPECT_TRUE(v.Laid().stations.empty());
        EXPECT_EQ(v.Laid().tows, 0);
      },
      false);
  scene->head = scene::HeadSpec{};  // a stitching head
  ASSERT_TRUE(scene->head.IsStitching());
  RunKeeping(*scene, lines, [](const Verifier& v) {
    EXPECT_TRUE(v.Laid().Empty());
    EXPECT_TRUE(v.Laid().events.empty());
  });
}

}  // namespace
}  // namespace stitchsim::verify
