// The afp.* rules through the whole text path: the AFP planner's 45 deg helix course on the
// seed-003 concave cylinder, written as text, made into one ply of two courses (M70 / M71 /
// M62 / M63 / M72) whose second course is the first moved along the cylinder axis so that the
// courses lie 16 w + 1.0 mm apart across the fibres (a 1.0 mm gap) or 16 w - 1.2 mm (a 1.2 mm
// overlap), parsed and executed on the cell: the gap (overlap) fires inside course 2 only,
// with the closed-form value, and the helix does not steer.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "stitchsim/common/units.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"
#include "verify_test_support.h"

namespace stitchsim::verify {
namespace {

constexpr double kTowWidth = 6.35;

// The course's motion lines, moved `dx` mm along part x (the cylinder's axis).
std::vector<std::string> MotionLines(const std::string& text, double dx) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("G0", 0) != 0 && l.rfind("G1", 0) != 0) continue;
    const std::size_t x = l.find(" X") + 2, end = l.find(' ', x);
    l.replace(x, end - x, std::to_string(std::stod(l.substr(x, end - x)) + dx));
    if (const std::size_t v = l.find(" V"); v != std::string::npos) {
      l.erase(v,
              l.find(' ', v + 1) == std::string::npos ? std::string::npos : l.find(' ', v + 1) - v);
    }
    out.push_back(l);
  }
  return out;
}

struct TwoCourses {
  std::string text;
  int course2_first = 0, course2_last = 0;  ///< lines of course 2's motion
};

TwoCourses Build(const std::string& planned, double spacing_mm) {
  TwoCourses t;
  std::vector<std::string> lines = {"G21 G90", "T3 M6", "M70 P1 (PLY name=test angle=45)"};
  const double dx = spacing_mm / std::sin(kPi / 4);  // across a 45 deg helix
  for (int c = 1; c <= 2; ++c) {
    lines.push_back("M71 P" + std::to_string(c));
    const auto motion = MotionLines(planned, c == 1 ? 0.0 : dx);
    lines.push_back(motion.front());
    lines.push_back("M62 P0");
    if (c == 2) t.course2_first = static_cast<int>(lines.size()) + 1;
    lines.insert(lines.end(), motion.begin() + 1, motion.end());
    if (c == 2) t.course2_last = static_cast<int>(lines.size());
    lines.push_back("M63 P0");
    lines.push_back("M72");
  }
  lines.push_back("M30");
  for (const auto& l : lines) t.text += l + "\n";
  return t;
}

Report Verify(const testing::Loaded& f, const std::string& text) {
  const sim::CellSetup cell = sim::MakeCellSetup(*f.robot, *f.scene);
  const process::ProcessModel model = process::MakeProcessModel(*f.scene, 5.0);
  const trace::CellDescription description = sim::DescribeCell(*f.robot, nullptr);
  Verifier verifier(RuleContext{f.scene.get(), &description, &model}, false);
  DiagnosticSink sink;
  std::istringstream in(text);
  sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, "two_courses.nc",
                      sim::ExecuteOptionsFor(*f.scene), sink, verifier);
  EXPECT_FALSE(sink.HasErrors());
  Report report;
  verifier.Finish(report);
  return report;
}

const RuleSummary* RuleOf(const Report& r, const std::string& id) {
  for (const auto& s : r.rules) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

TEST(AfpProgramme, TwoHelixCoursesGapOrOverlapInsideTheSecondCourse) {
  const testing::Loaded f = testing::Load("afp_concave_cylinder");
  ASSERT_TRUE(f.scene && f.robot);
  planner::AfpPlanOptions options;
  options.lay_angle_rad = kPi / 4;
  DiagnosticSink sink;
  const auto plan = planner::PlanAfpCourse(*f.scene, nullptr, options, sink);
  ASSERT_TRUE(plan);
  std::ostringstream planned;
  planner::WriteAfpProgram(*plan, *f.scene, program::Dialect::Default(), planned);
  struct Case {
    double offset_mm;
    const char* fires;
    const char* quiet;
    double value;
  };
  for (const Case& c :
       {Case{1.0, "afp.gap", "afp.overlap", 1.0}, Case{-1.2, "afp.overlap", "afp.gap", 1.2}}) {
    SCOPED_TRACE(c.fires);
    const TwoCourses two = Build(planned.str(), 16 * kTowWidth + c.offset_mm);
    const Report report = Verify(f, two.text);
    const RuleSummary* fires = RuleOf(report, c.fires);
    const RuleSummary* quiet = RuleOf(report, c.quiet);
    ASSERT_TRUE(fires && quiet);
    ASSERT_TRUE(fires->worst_value);
    EXPECT_NEAR(*fires->worst_value, c.value, 0.02);
    EXPECT_GT(fires->errors, 0);
    for (const Finding& finding : fires->findings) {
      if (finding.subject == "surface") continue;
      EXPECT_GE(finding.line, two.course2_first);
      EXPECT_LE(finding.line, two.course2_last);
    }
    EXPECT_EQ(quiet->errors, 0);
    const RuleSummary* steering = RuleOf(report, "afp.steering_radius");
    ASSERT_TRUE(steering && steering->worst_value);
    // A helix on a cylinder is a geodesic: what is left is the chords' own error (chords of 5 mm
    // lines joined to a tow width where the planner cut them short), 2 % of the head's limit.
    EXPECT_GT(*steering->worst_value, 50 * 635.0);
  }
}

}  // namespace
}  // namespace stitchsim::verify
