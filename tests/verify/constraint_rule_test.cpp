// constraint.crossing: the raster planner's clean programme of a wing window, then two
// faults made from it, each caught on its line: one stitch moved onto a stringer, and a
// traverse across an intercostal without retracting (stitching left on).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "../planner/raster_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
constexpr double kInch = 25.4;

struct Fixture {
  std::unique_ptr<scene::Scene> scene;
  std::optional<sim::RobotModel> robot;
  planner::RasterOptions options;
};

Fixture Load() {
  Fixture f;
  DiagnosticSink sink;
  f.scene = scene::LoadScene(kSource / "scenes" / "wing_cover.yaml", sink);
  EXPECT_NE(f.scene, nullptr);
  f.robot = sim::LoadRobotModel(f.scene->cell_urdf, sink);
  EXPECT_TRUE(f.robot.has_value());
  f.options.region =
      Eigen::AlignedBox2d(Eigen::Vector2d(-46, -21) * kInch, Eigen::Vector2d(-34, -9) * kInch);
  return f;
}

using planner::testing::Join;
using planner::testing::Lines;

const RuleSummary* Crossing(const Report& r) {
  for (const auto& rule : r.rules) {
    if (rule.id == "constraint.crossing") return &rule;
  }
  return nullptr;
}

Report Check(const Fixture& f, const std::string& text) {
  const sim::CellSetup cell = sim::MakeCellSetup(*f.robot, *f.scene);
  const process::ProcessModel model = process::MakeProcessModel(*f.scene, f.options.pitch_mm);
  const trace::CellDescription cell_description = sim::DescribeCell(*f.robot, nullptr);
  RuleContext ctx{f.scene.get(), &cell_description, &model};
  Verifier verifier(ctx, false);
  DiagnosticSink sink;
  std::istringstream in(text);
  sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, "fault.nc",
                      sim::ExecuteOptionsFor(*f.scene), sink, verifier);
  Report report;
  verifier.Finish(report);
  return report;
}

std::string Plan(const Fixture& f, planner::RasterStrategy strategy) {
  planner::RasterOptions o = f.options;
  o.strategy = strategy;
  DiagnosticSink sink;
  std::ostringstream out;
  EXPECT_TRUE(planner::WriteRasterProgram(*f.scene, o, program::Dialect::Default(), out, sink));
  return out.str();
}

// The index of the n-th G1 line (0: none).
int NthG1(const std::vector<std::string>& lines, int n) {
  int seen = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("G1", 0) == 0 && ++seen == n) return static_cast<int>(i);
  }
  return 0;
}

TEST(ConstraintCrossing, CleanRasterHasNoFinding) {
  const Fixture f = Load();
  const Report r = Check(f, Plan(f, planner::RasterStrategy::kJump));
  ASSERT_NE(Crossing(r), nullptr);
  EXPECT_GT(Crossing(r)->checked, 0);
  EXPECT_EQ(Crossing(r)->errors, 0);
}

TEST(ConstraintCrossing, StitchMovedOntoStringerCaughtOnItsLine) {
  const Fixture f = Load();
  std::vector<std::string> lines = Lines(Plan(f, planner::RasterStrategy::kJump));
  // The first stitch line of the second row piece of the first row (clear of everything):
  // put its Y on stringer_2 (y = -15 in).
  const int target = NthG1(lines, 20);
  ASSERT_GT(target, 0);
  const std::string& l = lines[static_cast<std::size_t>(target)];
  const std::size_t y = l.find(" Y");
  const std::size_t end = l.find(' ', y + 1);
  lines[static_cast<std::size_t>(target)] =
      l.substr(0, y) + " Y" + std::to_string(-15.0 * kInch) + l.substr(end);
  const Report r = Check(f, Join(lines));
  const RuleSummary* c = Crossing(r);
  ASSERT_NE(c, nullptr);
  ASSERT_GT(c->errors, 0);
  bool on_line = false;
  for (const auto& finding : c->findings) {
    EXPECT_NE(finding.subject.find("stringer_2"), std::string::npos) << finding.subject;
    on_line = on_line || finding.line == target + 1;
  }
  EXPECT_TRUE(on_line) << "expected line " << target + 1 << ", first finding on line "
                       << c->findings.front().line;
}

TEST(ConstraintCrossing, TraverseAcrossIntercostalWithoutRetractCaughtOnItsLine) {
  const Fixture f = Load();
  std::vector<std::string> lines = Lines(Plan(f, planner::RasterStrategy::kJump));
  // The first jump: M11, M20, G0 up, G0 over the intercostal, G0 down, M21, M10. Keep only
  // the last G0 (to the landing point on the surface): the head traverses straight across
  // the intercostal with the needles down.
  std::size_t m20 = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i] == "M20") {
      m20 = i;
      break;
    }
  }
  ASSERT_GT(m20, 1u);
  ASSERT_EQ(lines[m20 - 1], "M11");
  for (std::size_t k = 1; k <= 3; ++k) ASSERT_EQ(lines[m20 + k].rfind("G0", 0), 0u) << k;
  ASSERT_EQ(lines[m20 + 4], "M21");
  lines.erase(lines.begin() + static_cast<long>(m20) + 4);
  lines.erase(lines.begin() + static_cast<long>(m20) - 1,
              lines.begin() + static_cast<long>(m20) + 3);
  const int g0_line = static_cast<int>(m20);  // 1-based: M11 .. G0 over removed
  ASSERT_EQ(lines[static_cast<std::size_t>(g0_line - 1)].rfind("G0", 0), 0u);
  const Report r = Check(f, Join(lines));
  const RuleSummary* c = Crossing(r);
  ASSERT_NE(c, nullptr);
  ASSERT_EQ(c->errors, 1);
  EXPECT_EQ(c->findings.front().line, g0_line);
  EXPECT_NE(c->findings.front().subject.find("intercostal_3"), std::string::npos)
      << c->findings.front().subject;
}

// The footprint's size from the scene by hand, not from scene/footprint.h (which planner and
// rule share): stringer_2 is a box 1 in wide and 1.5 in tall across y, centred at
// y = -15.0449 in and turned 3.4336 deg about x; its shadow on the (x, y) plane is
// 0.5 cos + 0.75 sin inches either side of its centre, grown by the rule's default margin of
// 1 mm. A stitch 0.3 mm outside that edge is clear; 0.3 mm inside fires on its line. A
// footprint too large (or too small) fails one of the two.
TEST(ConstraintCrossing, StitchBesideTheStringerEdgeIsJudgedByTheHandComputedFootprint) {
  const Fixture f = Load();
  const std::vector<std::string> planned = Lines(Plan(f, planner::RasterStrategy::kJump));
  constexpr double kTilt = 3.4336 * kPi / 180.0;
  const double centre = -15.0449 * kInch;
  const double half = (0.5 * std::cos(kTilt) + 0.75 * std::sin(kTilt)) * kInch + 1.0;
  const int target = NthG1(planned, 20);
  ASSERT_GT(target, 0);
  const std::string& l = planned[static_cast<std::size_t>(target)];
  const std::size_t y = l.find(" Y");
  const std::size_t end = l.find(' ', y + 1);
  ASSERT_LT(std::stod(l.substr(y + 2, end - y - 2)), centre - half);  // the row is below it
  for (const double outside : {0.3, -0.3}) {
    std::vector<std::string> lines = planned;
    char value[32];
    std::snprintf(value, sizeof(value), "%.4f", centre - half - outside);
    lines[static_cast<std::size_t>(target)] = l.substr(0, y) + " Y" + value + l.substr(end);
    const Report r = Check(f, Join(lines));
    const RuleSummary* c = Crossing(r);
    ASSERT_NE(c, nullptr);
    if (outside > 0) {
      EXPECT_EQ(c->errors, 0) << "0.3 mm outside: " << c->findings.front().message;
      continue;
    }
    // The moves into and out of the stitch cross the edge at right angles: each is reported
    // on its line with the depth of the middle of its part inside, 0.15 mm.
    ASSERT_EQ(c->errors, 2);
    for (int k = 0; k < 2; ++k) {
      const auto& finding = c->findings[static_cast<std::size_t>(k)];
      EXPECT_EQ(finding.line, target + 1 + k);
      EXPECT_NE(finding.subject.find("stringer_2"), std::string::npos);
      EXPECT_NEAR(finding.value, 0.15, 1e-3);
    }
  }
}

// The planner's side of the same footprint, bounded from both sides by hand: rows run along
// the stringers, so the stitches nearest stringer_2 lie in the first row beyond its shadow
// (0.5 cos + 0.75 sin inches from its centre) grown by the plan's margin (0.5 in) and the
// RS535's keep-out radius (its envelope, 44 mm, above its needles' spread): at least that far
// and less than one row spacing (0.2 in) further.
TEST(ConstraintCrossing, RasterRowsStopOneRowBeyondTheHandComputedKeepOut) {
  const Fixture f = Load();
  const std::vector<std::string> lines = Lines(Plan(f, planner::RasterStrategy::kJump));
  constexpr double kTilt = 3.4336 * kPi / 180.0;
  const double centre = -15.0449 * kInch;
  const double keep_out =
      (0.5 * std::cos(kTilt) + 0.75 * std::sin(kTilt)) * kInch + 0.5 * kInch + 44.0;
  double below = 1e9, above = 1e9;  // nearest stitch on either side, beyond the keep-out
  int stitches = 0;
  for (const std::string& l : lines) {
    const std::size_t y = l.find(" Y");
    if (l.rfind("G1", 0) != 0 || y == std::string::npos) continue;
    ++stitches;
    const double d = std::stod(l.substr(y + 2)) - centre;
    (d < 0 ? below : above) = std::min(d < 0 ? below : above, std::abs(d) - keep_out);
  }
  ASSERT_GT(stitches, 1000);
  ASSERT_EQ(f.options.row_spacing_mm, 0.2 * kInch);  // the planner's default
  ASSERT_EQ(f.options.margin_mm, 0.5 * kInch);
  for (const double gap : {below, above}) {
    EXPECT_GE(gap, -1e-6);
    EXPECT_LT(gap, 0.2 * kInch + 1e-6);
  }
}

}  // namespace
}  // namespace stitchsim::verify
