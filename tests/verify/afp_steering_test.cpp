// afp.steering_radius against closed forms: a circular course of radius R on a plane steers
// its inner tow on R - 7.5 w and its outer on R + 7.5 w; a helix on a cylinder (a geodesic)
// does not steer though it is curved in space; a course of R = 500 mm (below the head's
// 635 mm) fires on every tow, on the line ending at each measured vertex.
#include <gtest/gtest.h>

#include <cmath>

#include "afp_test_support.h"

namespace stitchsim::verify {
namespace {

using namespace testing;

// A counter-clockwise circular course of radius `r` about the plane's origin, lines from
// line 10 on, `chord_mm` long, heading along the circle's tangent at each line end.
std::vector<trace::LineRecord> CircleCourse(const geom::Surface& plane, double r, double chord_mm,
                                            int count) {
  const double step = 2.0 * std::asin(0.5 * chord_mm / r);
  auto pose = [&](int i) {
    const double a = i * step;
    return ToolAt(plane, r * Eigen::Vector2d(std::cos(a), std::sin(a)),
                  Eigen::Vector2d(-std::sin(a), std::cos(a)));
  };
  std::vector<trace::LineRecord> lines;
  trace::LineRecord approach;  // outside any course: lays nothing
  approach.source_line = 9;
  approach.rapid = true;
  approach.head_retracted = true;
  approach.to = pose(0);
  lines.push_back(approach);
  for (int i = 0; i < count; ++i) lines.push_back(LayLine(10 + i, pose(i), pose(i + 1)));
  return lines;
}

TEST(AfpSteering, CircularCourseSteersItsInnerAndOuterTowsOnClosedFormRadii) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const double r = 1000.0;
  const Report report = RunLines(*scene, CircleCourse(*scene->surface, r, 20.0, 40));
  const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
  ASSERT_NE(rule, nullptr);
  ASSERT_TRUE(rule->worst_value);
  EXPECT_EQ(rule->errors, 0);
  EXPECT_EQ(*rule->error_limit, 635.0);  // the head's min_steering_radius_mm
  ASSERT_EQ(rule->subjects.size(), 16U);
  const double inner = r - 7.5 * kTowWidth, outer = r + 7.5 * kTowWidth;
  EXPECT_NEAR(*rule->worst_value, inner, 1e-3 * inner);
  EXPECT_EQ(rule->subjects.front().subject, "tow 1");
  EXPECT_NEAR(*rule->subjects.front().worst_value, inner, 1e-3 * inner);
  EXPECT_NEAR(*rule->subjects.back().worst_value, outer, 1e-3 * outer);
  for (int t = 1; t <= 16; ++t) {
    const double expected = r + (t - 8.5) * kTowWidth;
    EXPECT_NEAR(*rule->subjects[static_cast<std::size_t>(t) - 1].worst_value, expected,
                1e-3 * expected)
        << "tow " << t;
  }
}

// A planner inserts very short moves where it cuts a tow; written with 6 decimals their ends
// wander by up to 1e-6 mm. Over a 0.01 mm move that is a turn of 1e-4 rad, a "radius" of
// 100 mm if measured over the move itself: chords are joined to a tow width first.
TEST(AfpSteering, ShortMovesWithRoundedEndsDoNotReadAsSteering) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const Eigen::Vector2d x(1, 0);
  std::vector<trace::LineRecord> lines;
  double u = 0.0;
  int n = 10;
  for (int i = 0; i < 60; ++i) {
    const double len = i % 3 == 0 ? 5.0 : 0.01;
    const double wobble_from = (i % 2 == 0 ? 1e-6 : -1e-6), wobble_to = -wobble_from;
    lines.push_back(LayLine(n++, ToolAt(*scene->surface, Eigen::Vector2d(u, wobble_from), x),
                            ToolAt(*scene->surface, Eigen::Vector2d(u + len, wobble_to), x)));
    u += len;
  }
  const Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 0);
  ASSERT_TRUE(rule->worst_value);
  EXPECT_GT(*rule->worst_value, 1e4);
}

TEST(AfpSteering, HelixOnACylinderIsAGeodesicAndDoesNotSteer) {
  const auto scene = AfpScene(geom::MakeCylinder(300, true, 2000, 1800));
  const geom::Surface& s = *scene->surface;
  const Eigen::Vector2d dir = Eigen::Vector2d(1, 1).normalized();
  std::vector<trace::LineRecord> lines;
  for (int i = 0; i < 40; ++i) {
    lines.push_back(LayLine(10 + i, ToolAt(s, (i * 20.0 - 400) * dir, dir),
                            ToolAt(s, ((i + 1) * 20.0 - 400) * dir, dir)));
  }
  // Curved in space: the centre line's chords turn (about 0.9 deg a line), along the normal.
  const Eigen::Vector3d a = lines[0].to.translation() - lines[0].from.translation();
  const Eigen::Vector3d b = lines[1].to.translation() - lines[1].from.translation();
  EXPECT_GT(std::acos(a.normalized().dot(b.normalized())), 0.01);
  const Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
  ASSERT_NE(rule, nullptr);
  ASSERT_TRUE(rule->worst_value);
  EXPECT_GT(rule->checked, 0);
  EXPECT_GT(*rule->worst_value, 1e5);
  EXPECT_EQ(rule->errors, 0);
}

// A course of R = 500 mm (below the head's 635 mm) written as the ply planner writes poses
// (5 mm apart) and as a coarse hand programme (20 mm): every tow fires, each on its circle
// R + (t - 8.5) w to 0.1 %; a finding on every line whose end is a measured vertex (a half
// window, 25 mm of the tow, from both ends of the course for some tow).
TEST(AfpSteering, CourseOfRadius500FiresOnEveryTowOnItsClosedFormRadius) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const double r = 500.0, half_window = 25.0;
  for (const double chord : {5.0, 20.0}) {
    const int count = static_cast<int>(std::lround(300.0 / chord));
    const Report report = RunLines(*scene, CircleCourse(*scene->surface, r, chord, count));
    const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
    ASSERT_NE(rule, nullptr);
    ASSERT_EQ(rule->subjects.size(), 16U);
    for (int t = 1; t <= 16; ++t) {
      const double expected = r + (t - 8.5) * kTowWidth;
      const SubjectFigure& f = rule->subjects[static_cast<std::size_t>(t) - 1];
      ASSERT_TRUE(f.worst_value) << "tow " << t;
      EXPECT_NEAR(*f.worst_value, expected, 1e-3 * expected) << "chord " << chord << " tow " << t;
      EXPECT_LT(*f.worst_value, *rule->error_limit);
    }
    // Vertex j (the end of line 10 + j - 1) is measured for tow t when the tow's chords reach
    // a half window both ways: j c_t >= 25 and (count - j) c_t >= 25.
    std::vector<int> expected_lines;
    const double step = 2.0 * std::asin(0.5 * chord / r);
    for (int j = 1; j < count; ++j) {
      for (int t = 1; t <= 16; ++t) {
        const double c = 2.0 * (r + (t - 8.5) * kTowWidth) * std::sin(0.5 * step);
        if (j * c >= half_window - 1e-9 && (count - j) * c >= half_window - 1e-9) {
          expected_lines.push_back(10 + j - 1);
          break;
        }
      }
    }
    std::string seen;
    for (const auto& f : rule->findings) seen += " " + std::to_string(f.line);
    ASSERT_EQ(rule->findings.size(), expected_lines.size()) << "chord " << chord << ":" << seen;
    EXPECT_EQ(rule->errors, static_cast<long>(expected_lines.size()));
    for (std::size_t i = 0; i < expected_lines.size(); ++i) {
      EXPECT_EQ(rule->findings[i].line, expected_lines[i]);
      EXPECT_EQ(rule->findings[i].limit, 635.0);
      // Its place: tow t's centre at the vertex, on the circle of radius r + (t - 8.5) w
      // about the course's centre (tool x points out of the circle; tow 1 is innermost).
      const verify::Finding& f = rule->findings[i];
      ASSERT_TRUE(f.position_mm);
      const int t = std::stoi(f.subject.substr(4));
      EXPECT_NEAR(std::hypot((*f.position_mm)[0], (*f.position_mm)[1]), r + (t - 8.5) * kTowWidth,
                  1e-6);
      EXPECT_NEAR((*f.position_mm)[2], 0.0, 1e-9);
    }
    const double inner = r - 7.5 * kTowWidth;
    EXPECT_NEAR(*rule->worst_value, inner, 1e-3 * inner);
  }
}

// One 200 mm move along which the head turns 20 deg (the executor slerps the heading): the
// tool point runs straight but each tow sweeps a curve, c(f) = (L f, 0) + d (sin p, -cos p)
// with p = 20 deg f and d its offset; the rule divides the move and reads that curve's radius,
// |c'|^3 / |c' x c''|, here computed in closed form over the measured stretch (a half window
// of the tow from each end).
TEST(AfpSteering, AHeadTurningAlongOneLongMoveSteersItsTows) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  const double length = 200.0, turn = 20.0 * kPi / 180.0;
  const Eigen::Vector2d start(0, 0), end(length, 0);
  const Report report = RunLines(
      *scene,
      {LayLine(10, ToolAt(*scene->surface, start, Eigen::Vector2d(1, 0)),
               ToolAt(*scene->surface, end, Eigen::Vector2d(std::cos(turn), std::sin(turn))))});
  const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
  ASSERT_NE(rule, nullptr);
  for (int t = 1; t <= 16; ++t) {
    const double d = (t - 8.5) * kTowWidth;
    auto velocity = [&](double f) {
      const double p = turn * f;
      return Eigen::Vector2d(length + d * turn * std::cos(p), d * turn * std::sin(p));
    };
    auto radius = [&](double f) {
      const double p = turn * f;
      const Eigen::Vector2d v = velocity(f);
      const Eigen::Vector2d a(-d * turn * turn * std::sin(p), d * turn * turn * std::cos(p));
      return std::pow(v.norm(), 3) / std::abs(v.x() * a.y() - v.y() * a.x());
    };
    const int n = 20000;
    double total = 0.0;
    for (int i = 0; i < n; ++i) total += velocity((i + 0.5) / n).norm() / n;
    double expected = INFINITY, arc = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double f = static_cast<double>(i) / n;
      if (arc >= 25.0 && total - arc >= 25.0) expected = std::min(expected, radius(f));
      arc += velocity((i + 0.5) / n).norm() / n;
    }
    const SubjectFigure& figure = rule->subjects[static_cast<std::size_t>(t) - 1];
    ASSERT_TRUE(figure.worst_value) << "tow " << t;
    EXPECT_NEAR(*figure.worst_value, expected, 0.01 * expected) << "tow " << t;
  }
}

TEST(AfpSteering, LinesOutsideACourseLayNothing) {
  const auto scene = AfpScene(geom::MakePlane(4000, 4000));
  auto lines = CircleCourse(*scene->surface, 500, 20.0, 10);
  for (auto& l : lines) l.course = 0;
  const Report report = RunLines(*scene, lines);
  const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->checked, 0);
  EXPECT_EQ(rule->errors, 0);
}

}  // namespace
}  // namespace stitchsim::verify
