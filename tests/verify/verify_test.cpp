// Execute + verify: planner programmes of every bundled scene, the seed's coupled failures,
// the cylinder chord width of seed 000 figure 9, hand-written faulty programmes, and a rule
// on a hand-made trace.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/writer.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"
#include "verify_test_support.h"

namespace stitchsim::verify {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;

using testing::Load;
using testing::Loaded;

struct Outcome {
  bool input_ok = false;
  std::vector<Diagnostic> diagnostics;
  Report report;
  const RuleSummary* Rule(const std::string& id) const {
    for (const auto& r : report.rules) {
      if (r.id == id) return &r;
    }
    return nullptr;
  }
  long Errors(const std::string& id) const { return Rule(id) ? Rule(id)->errors : -1; }
};

Outcome Verify(const Loaded& l, const std::string& text, double stitch_length_mm) {
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  const process::ProcessModel model = process::MakeProcessModel(*l.scene, stitch_length_mm);
  const trace::CellDescription cell_description = sim::DescribeCell(*l.robot, nullptr);
  RuleContext ctx{l.scene.get(), &cell_description, &model};
  Verifier verifier(ctx, true);
  DiagnosticSink sink;
  std::istringstream in(text);
  const sim::ExecutionSummary run =
      sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, "test.nc",
                          sim::ExecuteOptionsFor(*l.scene), sink, verifier);
  Outcome o;
  o.input_ok = run.ok;
  o.diagnostics = sink.Diagnostics();
  o.report.moves = run.moves;
  verifier.Finish(o.report);
  return o;
}

std::pair<std::string, double> PlanText(const Loaded& l, const scene::PathSpec& p,
                                        planner::Mode mode) {
  DiagnosticSink sink;
  planner::StitchPlanOptions opt;
  opt.mode = mode;
  auto pl = planner::StitchPathPlanner::Create(*l.scene, p, opt, sink);
  EXPECT_TRUE(pl.has_value());
  std::ostringstream out;
  planner::WriteStitchProgram(*pl, *l.scene, p.name, program::Dialect::Default(), out);
  return {out.str(), pl->StitchLengthMm()};
}

std::string Describe(const Outcome& o) {
  std::string s;
  for (const auto& d : o.diagnostics) s += FormatDiagnostic(d) + "\n";
  for (const auto& r : o.report.rules) {
    for (const auto& f : r.findings) {
      s += r.id + " line " + std::to_string(f.line) + ": " + f.message + "\n";
      if (s.size() > 2000) return s;
    }
  }
  return s;
}

TEST(Verify, EveryDecoupledPlannerProgrammeVerifiesClean) {
  for (const char* name : {"flat_straight", "circle_8in", "cutout_slot", "cylinder_r90_frame",
                           "arcs_planar", "blade_demo"}) {
    const Loaded l = Load(name);
    for (const auto& p : l.scene->paths) {
      const auto [text, ls] = PlanText(l, p, planner::Mode::kDecoupled);
      const Outcome o = Verify(l, text, ls);
      EXPECT_TRUE(o.input_ok) << name << "/" << p.name;
      EXPECT_EQ(o.report.verdict, "pass") << name << "/" << p.name << "\n" << Describe(o);
      EXPECT_GT(o.report.stitches, 0);
    }
  }
}

TEST(Verify, CoupledCircleFailsSideForceAndRotationOnEveryStitchLine) {
  const Loaded l = Load("circle_8in");
  const auto [text, ls] = PlanText(l, l.scene->paths.front(), planner::Mode::kCoupled);
  const Outcome o = Verify(l, text, ls);
  ASSERT_TRUE(o.input_ok);
  EXPECT_EQ(o.report.verdict, "fail");
  EXPECT_GT(o.Errors("needle.side_force"), 0);
  EXPECT_GT(o.Errors("needle.rotation_in_preform"), 0);
  // Each coupled line is one stitch: the findings sit on the stitch lines (stitch i on the
  // i-th G1 line after the start line), insertion needle worst.
  std::istringstream in(text);
  std::vector<int> stitch_lines;
  std::string line_text;
  for (int n = 1; std::getline(in, line_text); ++n) {
    if (line_text.rfind("G1", 0) == 0) stitch_lines.push_back(n);
  }
  ASSERT_EQ(stitch_lines.size(), static_cast<std::size_t>(o.report.stitches));
  const RuleSummary* rot = o.Rule("needle.rotation_in_preform");
  ASSERT_EQ(rot->errors, o.report.stitches);
  for (const Finding& f : rot->findings) {
    ASSERT_GE(f.stitch, 1);
    EXPECT_EQ(f.line, stitch_lines[static_cast<std::size_t>(f.stitch - 1)]);
    EXPECT_EQ(f.subject, "about z");
  }
  const RuleSummary* sf = o.Rule("needle.side_force");
  EXPECT_EQ(sf->worst_line, stitch_lines[static_cast<std::size_t>(sf->worst_stitch - 1)]);
  EXPECT_NEAR(*sf->worst_value, 17.0 * 0.7 * 5.0 / (8 * 25.4), 0.03);
}

TEST(Verify, CoupledStraightAndWideArcsPass) {
  {
    const Loaded l = Load("flat_straight");
    const auto [text, ls] = PlanText(l, l.scene->paths.front(), planner::Mode::kCoupled);
    const Outcome o = Verify(l, text, ls);
    EXPECT_EQ(o.report.verdict, "pass") << Describe(o);
    EXPECT_LT(*o.Rule("needle.side_force")->worst_value, 1e-6);
  }
  const Loaded l = Load("arcs_planar");
  for (const char* p : {"arc_r30", "arc_r48"}) {
    const auto [text, ls] = PlanText(l, *l.scene->FindPath(p), planner::Mode::kCoupled);
    const Outcome o = Verify(l, text, ls);
    EXPECT_EQ(o.report.verdict, "pass") << p << "\n" << Describe(o);
  }
  for (const char* p : {"arc_r8", "arc_r12", "arc_r20"}) {
    const auto [text, ls] = PlanText(l, *l.scene->FindPath(p), planner::Mode::kCoupled);
    EXPECT_EQ(Verify(l, text, ls).report.verdict, "fail") << p;
  }
}

// A straight chord across the 5.4 in frame flange: the head keeps the start frame and runs
// in a straight line in space, as the seed's Boeing panel was stitched.
TEST(Verify, CylinderChordStitchWidthVariesAboutSixPercent) {
  const Loaded l = Load("cylinder_r90_frame");
  const scene::PathSpec& p = *l.scene->FindPath("frame_flange");
  const geom::Surface& s = *l.scene->surface;
  const Eigen::Vector3d a = s.Point(p.curve->Start());
  const Eigen::Vector3d b = s.Point(p.curve->End());
  const double chord = (b - a).norm();
  const int n = *geom::StitchCount(chord, 5.0);
  const double ls = chord / n;
  const Eigen::Matrix3d frame =
      *geom::FrameFromNormalAndDirection(s.Normal(p.curve->Start()), b - a);
  const Eigen::Vector3d abc = geom::EulerFromRotation(geom::EulerOrder{}, frame) * kRadToDeg;
  std::ostringstream prog;
  prog.precision(10);
  prog << "%\n(STITCHSIM stitch_length_mm=" << ls << ")\nG21 G90\nT1 M6\n";
  auto pose = [&](const Eigen::Vector3d& q) {
    prog << " X" << q.x() << " Y" << q.y() << " Z" << q.z() << " A" << abc.x() << " B" << abc.y()
         << " C" << abc.z();
  };
  prog << "G0";
  pose(a);
  prog << " U0 V0\nM10\n";
  for (int i = 1; i <= n; ++i) {
    prog << "G1";
    pose(a + (b - a) * (static_cast<double>(i) / n));
    prog << " U" << i * ls << " V" << i * ls << (i == 1 ? " F1500" : "") << "\n";
  }
  prog << "M11\nM30\n%\n";
  const Outcome o = Verify(l, prog.str(), ls);
  ASSERT_TRUE(o.input_ok) << Describe(o);
  const RuleSummary* w = o.Rule("stitch.width");
  ASSERT_NE(w, nullptr);
  // Worst in the middle of the chord, about 6 % (seed 000 figure 9), a warning by default.
  EXPECT_NEAR(*w->worst_value, 6.0, 0.6);
  EXPECT_NEAR(static_cast<double>(w->worst_stitch), n / 2.0, 2.0);
  EXPECT_EQ(w->errors, 0);
  EXPECT_GT(w->warnings, 0);
  for (const Finding& f : w->findings) {
    EXPECT_EQ(f.severity, FindingSeverity::kWarning);
    EXPECT_GT(f.stitch, 2);
    EXPECT_LT(f.stitch, n - 1);
  }
  // The planner's curved programme keeps the width.
  const auto [curved, ls2] = PlanText(l, p, planner::Mode::kDecoupled);
  EXPECT_LT(*Verify(l, curved, ls2).Rule("stitch.width")->worst_value, 0.5);
}

constexpr const char* kHead = "%\nG21 G90\nT1 M6\nG0 X0 Y0 Z0 A0 B0 C-90 U0 V0\nM10\n";

TEST(Verify, FaultyProgrammesAreCaughtWithTheirLine) {
  const Loaded l = Load("flat_straight");
  {  // Out of reach: 3 m further from the rail.
    const Outcome o = Verify(l, std::string(kHead) + "G1 X5 Y3000 Z0 U5 V5 F1500\nM30\n%\n", 5.0);
    ASSERT_TRUE(o.input_ok);
    ASSERT_GT(o.Errors("kin.reach"), 0) << Describe(o);
    EXPECT_EQ(o.Rule("kin.reach")->findings.front().line, 6);
  }
  {  // Joint limit: the programme puts the rail beyond its travel.
    const Outcome o =
        Verify(l, std::string(kHead) + "G1 X5 U5 V5 F1500\nG1 X10 E15000 U10 V10\nM30\n%\n", 5.0);
    ASSERT_GT(o.Errors("kin.joint_limit"), 0) << Describe(o);
    EXPECT_EQ(o.Rule("kin.joint_limit")->findings.front().line, 7);
    EXPECT_EQ(o.Rule("kin.joint_limit")->findings.front().subject, "rail_x");
  }
  {  // Joint limit: the head tipped up past what a5 can reach.
    const Outcome o = Verify(
        l, std::string(kHead) + "G1 X5 U5 V5 F1500\nG1 X10 A0 B150 C-90 U10 V10\nM30\n%\n", 5.0);
    EXPECT_GT(o.Errors("kin.joint_limit") + o.Errors("kin.reach"), 0) << Describe(o);
  }
  {  // A rotation line that advances U: the head turns with the needles in.
    const Outcome o = Verify(
        l, std::string(kHead) + "G1 X5 U5 V5 F1500\nG1 C-80 U10 V10\nG1 X10 U15 V15\nM30\n%\n",
        5.0);
    ASSERT_GT(o.Errors("needle.rotation_in_preform"), 0) << Describe(o);
    EXPECT_EQ(o.Rule("needle.rotation_in_preform")->findings.front().line, 7);
    ASSERT_GT(o.Errors("program.sync"), 0);
    EXPECT_EQ(o.Rule("program.sync")->findings.front().line, 7);
    EXPECT_GT(o.Errors("needle.side_force"), 0);
  }
  {  // U and V disagree with each other, and V with the tool travel.
    const Outcome o = Verify(
        l, std::string(kHead) + "G1 X5 U5 V5 F1500\nG1 X10 U10 V12\nG1 X15 U20 V20\nM30\n%\n", 5.0);
    const RuleSummary* sync = o.Rule("program.sync");
    ASSERT_EQ(sync->errors, 2) << Describe(o);
    EXPECT_EQ(sync->findings[0].line, 7);
    EXPECT_EQ(sync->findings[1].line, 8);
  }
  {  // NaN is bad input with its line, never a report.
    const Outcome o =
        Verify(l, std::string(kHead) + "G1 X5 U5 V5 F1500\nG1 Xnan U10 V10\n%\n", 5.0);
    EXPECT_FALSE(o.input_ok);
    ASSERT_FALSE(o.diagnostics.empty());
    EXPECT_EQ(o.diagnostics.front().location.line, 7);
  }
  {  // An empty programme never passes.
    const Outcome o = Verify(l, "%\nG21 G90\nT1 M6\nM30\n%\n", 5.0);
    EXPECT_EQ(o.report.verdict, "fail");
    EXPECT_EQ(o.Errors("program.empty"), 1);
  }
}

// Issue S6 item 1: the side-force proxy follows the needle shafts inside the preform (tool z
// in [0, t]). A line that turns the head 0.6 deg about tool y while moving 0.1 mm along tool
// x: in the 70 % window the insertion needle's shaft top drifts 0.07 + 12 sin(0.42 deg) =
// 0.158 mm (over the 0.10 mm limit); followed below the surface it looked like 0.07 mm.
TEST(Verify, SideForceOfATurnAboutToolYFiresOnItsLine) {
  const Loaded l = Load("flat_straight");
  // Tool frame at C-90: tool x is part -y, tool y is part +x.
  const Eigen::Matrix3d flat = geom::RotationFromEuler({}, {0, 0, -90 * kDeg});
  const Eigen::Matrix3d tilted =
      flat * Eigen::AngleAxisd(0.6 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d abc = geom::EulerFromRotation({}, tilted) / kDeg;
  char angles[96];
  std::snprintf(angles, sizeof angles, "A%.6f B%.6f C%.6f", abc.x(), abc.y(), abc.z());
  const std::string text = std::string(kHead) + "G1 X5 U5 V5 F1500\nG1 X10 Y-0.1 Z0 " + angles +
                           " U10 V10\nG1 X15 Y-0.1 Z0 " + angles + " U15 V15\nM11\nM30\n%\n";
  const Outcome o = Verify(l, text, 5.0);
  ASSERT_TRUE(o.input_ok);
  const RuleSummary* sf = o.Rule("needle.side_force");
  ASSERT_GE(sf->errors, 1) << Describe(o);
  for (const Finding& f : sf->findings) EXPECT_EQ(f.line, 7);
  // By hand, in the tool frame at entry: the head moves dx along x and turns phi about y over
  // the window; the shaft tops (z = 12 mm) move to Ry(phi) p + dx, measured across the turned
  // needle axis. Insertion: p = (17, 0, 12), axis -z; catcher: p = (-12, 0, 12), axis
  // (1, 0, -1)/sqrt 2.
  const double dx = 0.1 * 0.7, phi = 0.6 * kDeg * 0.7, c = std::cos(phi), s = std::sin(phi);
  auto drift = [&](double px, double pz, double ax, double az) {
    double ex = c * px + s * pz + dx - px, ez = -s * px + c * pz - pz;
    const double bx = c * ax + s * az, bz = -s * ax + c * az, along = ex * bx + ez * bz;
    ex -= along * bx;
    ez -= along * bz;
    return std::hypot(ex, ez);
  };
  const double insertion = drift(17, 12, 0, -1);
  const double catcher = drift(-12, 12, std::sqrt(0.5), -std::sqrt(0.5));
  EXPECT_NEAR(insertion, 0.1584, 1e-4);
  EXPECT_NEAR(*sf->worst_value, std::max(insertion, catcher), 1e-4);
}

// Issue S6 item 1: a planner-made coupled 36 in arc on a twisted plate keeps the side-force
// limit (worst 0.098 mm); with the shafts followed below the surface it failed 24 stitches.
TEST(Verify, CoupledArcOnATwistedPlatePasses) {
  const Loaded l = testing::LoadFile(kSource / "tests/data/scenes/twisted_arc36.yaml");
  ASSERT_TRUE(l.scene && l.robot);
  const auto [text, ls] = PlanText(l, l.scene->paths.front(), planner::Mode::kCoupled);
  const Outcome o = Verify(l, text, ls);
  EXPECT_EQ(o.report.verdict, "pass") << Describe(o);
  EXPECT_GT(*o.Rule("needle.side_force")->worst_value, 0.09);
  EXPECT_LT(*o.Rule("needle.side_force")->worst_value, 0.10);
}

// A rule checked on a hand-made trace: a needle window in which the head yaws.
TEST(Verify, SideForceRuleOnAHandMadeTrace) {
  const Loaded l = Load("flat_straight");
  const process::ProcessModel model = process::MakeProcessModel(*l.scene, 5.0);
  const trace::CellDescription cell_description = sim::DescribeCell(*l.robot, nullptr);
  RuleContext ctx{l.scene.get(), &cell_description, &model};
  Verifier v(ctx, false);
  const double yaw = 0.01;  // rad during the window
  for (int i = 0; i <= 10; ++i) {
    sim::TraceSample s;
    s.source_line = 42;
    s.stitch = 1;
    s.drive_advancing = true;
    s.needles_in = true;
    s.event = i == 0 ? sim::SampleEvent::kNeedleEntry
                     : (i == 10 ? sim::SampleEvent::kNeedleExit : sim::SampleEvent::kNone);
    s.tool_part.linear() =
        Eigen::AngleAxisd(yaw * i / 10, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    v.OnSample(s);
  }
  Report r;
  v.Finish(r);
  const RuleSummary* sf = nullptr;
  for (const auto& x : r.rules) {
    if (x.id == "needle.side_force") sf = &x;
  }
  ASSERT_NE(sf, nullptr);
  EXPECT_NEAR(*sf->worst_value, 17.0 * yaw, 1e-3);  // the insertion needle sweeps w * yaw
  EXPECT_EQ(sf->worst_line, 42);
  // Insertion 0.17 mm; the inclined catcher's upper shaft (12 mm off the axis) 0.12 mm: both
  // over the limit on line 42, one finding for the line with its worst, the insertion's.
  EXPECT_EQ(sf->errors, 1);
  ASSERT_EQ(sf->findings.size(), 1u);
  EXPECT_EQ(sf->findings.front().subject, "insertion");
  EXPECT_EQ(sf->findings.front().value, *sf->worst_value);
}

}  // namespace
}  // namespace stitchsim::verify
