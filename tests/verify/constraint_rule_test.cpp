// constraint.crossing: the raster planner's clean programme of a wing window, then two
// faults made from it, each caught on its line: one stitch moved onto a stringer, and a
// traverse across an intercostal without retracting (stitching left on).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <vector>

#include "../planner/raster_test_support.h"

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
  int target = 0;
  int g1_seen = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("G1", 0) == 0 && ++g1_seen == 20) {
      target = static_cast<int>(i);
      break;
    }
  }
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

}  // namespace
}  // namespace stitchsim::verify
