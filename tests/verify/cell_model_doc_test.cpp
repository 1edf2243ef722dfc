// docs/cell-model.md's calibration table against what the tool computes: each figure is
// recomputed here (process model, planner, verifier) and must agree with the doc to the
// digits it prints. A closed form checks the tool where one exists.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::verify {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
constexpr double kInch = 25.4;

// The doc's table: figure name -> (value, digits after the decimal point as printed).
struct DocFigure {
  double value = 0;
  int decimals = 0;
};
std::map<std::string, DocFigure> ReadDocTable() {
  std::ifstream in(kSource / "docs/cell-model.md");
  std::map<std::string, DocFigure> out;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("<!-- calibration-table:", 0) == 0) inside = true;
    if (line.rfind("<!-- calibration-table end", 0) == 0) break;
    if (!inside || line.rfind("| ", 0) != 0 || line.rfind("| figure", 0) == 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    for (std::string c; std::getline(ss, c, '|');) {
      c.erase(0, c.find_first_not_of(' '));
      c.erase(c.find_last_not_of(' ') + 1);
      cells.push_back(c);
    }
    if (cells.size() < 2) continue;
    const std::size_t dot = cells[1].find('.');
    out[cells[0]] = {std::stod(cells[1]),
                     dot == std::string::npos ? 0 : static_cast<int>(cells[1].size() - dot - 1)};
  }
  return out;
}

// `computed` printed with the doc's decimals equals the doc's value.
void ExpectDoc(const std::map<std::string, DocFigure>& doc, const std::string& name,
               double computed) {
  const auto it = doc.find(name);
  ASSERT_NE(it, doc.end()) << "docs/cell-model.md has no figure '" << name << "'";
  const double scale = std::pow(10.0, it->second.decimals);
  EXPECT_DOUBLE_EQ(std::round(computed * scale) / scale, it->second.value)
      << name << ": the tool computes " << computed;
}

scene::HeadSpec Rs535() {
  DiagnosticSink sink;
  auto head = scene::LoadHeadSpec(kSource / "models/heads/rs535.yaml", sink);
  EXPECT_TRUE(head.has_value());
  return *head;
}

process::ProcessModel Model(const scene::HeadSpec& head, double ls) {
  process::ProcessModel m;
  m.needles = head.needles;
  m.phase_in = head.stitch.phase_in;
  m.phase_out = head.stitch.phase_out;
  m.walk_capacity_mm = head.stitch.walk_capacity_mm;
  m.preform_thickness_mm = head.stitch.preform_thickness_mm;
  m.stitch_length_mm = ls;
  m.nominal_width_mm = head.stitch.width_mm;
  const double t = m.preform_thickness_mm;
  m.shaft_heights_mm = {0.0, 0.25 * t, 0.5 * t, 0.75 * t, t};
  return m;
}

// An interior coupled stitch of a planar arc as the planner frames it (stitch points at equal
// arc length, z up, y along each chord, the line from one stitch's frame to the next's).
process::WindowMetrics ArcStitch(const process::ProcessModel& m, double radius, double ls) {
  const double step = ls / radius;
  auto point = [&](int i) {
    return Eigen::Vector3d(radius * std::sin(i * step), radius * (1 - std::cos(i * step)), 0);
  };
  auto frame = [&](int i) {
    Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d y = (point(i + 1) - point(i)).normalized();
    f.linear() << y.cross(Eigen::Vector3d::UnitZ()), y, Eigen::Vector3d::UnitZ();
    f.translation() = point(i);
    return f;
  };
  Eigen::Isometry3d to = frame(11);
  to.translation() = point(11);
  return process::EvaluateCoupledStitch(m, frame(10), to, 256);
}

// Smallest radius whose coupled arc keeps `limits` (bisection; fails below, passes above).
double SwitchRadius(const process::ProcessModel& m, const process::NeedleLimits& limits,
                    double ls) {
  double lo = 100, hi = 5000;
  for (int k = 0; k < 80; ++k) {
    const double mid = 0.5 * (lo + hi);
    (process::FirstExceededLimit(ArcStitch(m, mid, ls), limits).empty() ? hi : lo) = mid;
  }
  return hi;
}

TEST(CellModelDoc, PlanarArcSwitchAndItsFormula) {
  const auto doc = ReadDocTable();
  const scene::HeadSpec head = Rs535();
  const process::NeedleLimits limits = process::NeedleLimitsFrom(head.limits);
  const double ls = 4.98, w = head.stitch.width_mm;
  const process::ProcessModel m = Model(head, ls);
  const double r = SwitchRadius(m, limits, ls);
  ExpectDoc(doc, "coupled planar arc switch radius, l_s = 4.98 mm", r / kInch);
  ExpectDoc(doc, "coupled planar arc switch radius, l_s = 5.00 mm",
            SwitchRadius(Model(head, 5.0), limits, 5.0) / kInch);
  const process::WindowMetrics at = ArcStitch(m, r, ls);
  // The closed form of the doc agrees with the process model at the switch (to 0.1 %).
  const double formula = 0.7 * (ls / r) * std::hypot(w, 0.85 * ls);
  EXPECT_NEAR(formula, at.side_force_mm[1], 1e-3 * at.side_force_mm[1]);
  ExpectDoc(doc, "insertion needle drift at the 4.98 mm switch, formula above", formula);
  ExpectDoc(doc, "catcher drift at the 4.98 mm switch", at.side_force_mm[0]);
  ExpectDoc(doc, "rotation about z in the window at the switch", at.rotation_rad.z() / kDeg);
  ExpectDoc(doc, "walk demand at the 4.98 mm switch", at.walk_demand_mm);
  process::NeedleLimits z_only;
  z_only.side_force_error_mm = 1e9;
  z_only.rotation_error_rad[2] = limits.rotation_error_rad[2];
  ExpectDoc(doc, "radius where rotation about z alone reaches its limit, l_s = 4.98 mm",
            SwitchRadius(m, z_only, ls) / kInch);
}

TEST(CellModelDoc, ChordOnTheNinetyInchPanel) {
  const auto doc = ReadDocTable();
  DiagnosticSink sink;
  const auto s = scene::LoadScene(kSource / "scenes/cylinder_r90_frame.yaml", sink);
  ASSERT_NE(s, nullptr);
  const scene::PathSpec& p = *s->FindPath("frame_flange");
  const geom::Surface& surface = *s->surface;
  const Eigen::Vector3d a = surface.Point(p.curve->Start()), b = surface.Point(p.curve->End());
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.linear() = *geom::FrameFromNormalAndDirection(surface.Normal(p.curve->Start()), b - a);
  tool.translation() = 0.5 * (a + b);
  // The dip: closed form of a chord in a circle, and the surface's own closest point.
  const double r = 90 * kInch, half = 0.5 * (b - a).norm();
  const double dip = r - std::sqrt(r * r - half * half);
  EXPECT_NEAR((surface.Project(tool.translation()).point - tool.translation()).norm(), dip, 1e-6);
  ExpectDoc(doc, "5.4 in chord on a 90 in radius panel: dip at its middle", dip);
  const process::ProcessModel m = process::MakeProcessModel(*s, 5.0);
  const auto pierce = process::PenetrationPoints(m, surface, tool);
  ASSERT_TRUE(pierce[0] && pierce[1]);
  const double width = (*pierce[1] - *pierce[0]).norm();
  ExpectDoc(doc, "5.4 in chord on a 90 in radius panel: stitch width at its middle",
            100.0 * (width - m.nominal_width_mm) / m.nominal_width_mm);
}

// The switch end to end: a planner-made coupled arc of 61 stitches of 4.98 mm fails at 24.0 in
// and passes at 24.1 in; auto mode decouples all of the first and none of the second.
TEST(CellModelDoc, ArcsEitherSideOfTheSwitchEndToEnd) {
  const fs::path dir = fs::path(STITCHSIM_BINARY_DIR) / "cell_model_doc_test";
  fs::create_directories(dir);
  for (const double radius_in : {24.0, 24.1}) {
    const double length_mm = 61 * 4.98, sweep_deg = length_mm / (radius_in * kInch) / kDeg;
    const fs::path file = dir / ("arc_" + std::to_string(radius_in) + ".yaml");
    std::ofstream yaml(file);
    yaml.precision(15);
    yaml << "stitchsim_scene: 1\nname: arc\nunits: in\nhead: rs535\n"
         << "part: {mount: table, position: [0, 0, 2]}\n"
         << "surface: {type: plane, size: [60, 36]}\npreform: {thickness: 12 mm}\n"
         << "mold: {depth: 2}\nstitch: {nominal_length: 4.98 mm}\npaths:\n"
         << "  - {name: arc, type: arc, center: [0, " << -radius_in + 6
         << "], radius: " << radius_in << ", start_deg: " << 90 - sweep_deg / 2
         << ", end_deg: " << 90 + sweep_deg / 2 << "}\n";
    yaml.close();
    DiagnosticSink sink;
    auto s = scene::LoadScene(file, sink);
    ASSERT_NE(s, nullptr) << file;
    auto robot = sim::LoadRobotModel(s->cell_urdf, sink);
    ASSERT_TRUE(robot.has_value());
    for (const planner::Mode mode : {planner::Mode::kCoupled, planner::Mode::kAuto}) {
      planner::StitchPlanOptions opt;
      opt.mode = mode;
      auto pl = planner::StitchPathPlanner::Create(*s, s->paths.front(), opt, sink);
      ASSERT_TRUE(pl.has_value());
      ASSERT_NEAR(pl->StitchLengthMm(), 4.98, 1e-9);
      std::ostringstream text;
      const planner::ProgramSummary summary =
          planner::WriteStitchProgram(*pl, *s, "arc", program::Dialect::Default(), text);
      const bool fails = radius_in < 24.06;
      if (mode == planner::Mode::kAuto) {
        // Every interior stitch is alike; the first and last see the path's ends.
        EXPECT_EQ(summary.decoupled >= 59, fails) << radius_in << " in: " << summary.decoupled;
        EXPECT_EQ(summary.decoupled == 0, !fails) << radius_in << " in: " << summary.decoupled;
        continue;
      }
      const sim::CellSetup cell = sim::MakeCellSetup(*robot, *s);
      const process::ProcessModel model = process::MakeProcessModel(*s, 4.98);
      const trace::CellDescription cell_description = sim::DescribeCell(*robot, nullptr);
      const RuleContext ctx{s.get(), &cell_description, &model};
      Verifier verifier(ctx, false);
      std::istringstream in(text.str());
      ASSERT_TRUE(sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, "arc.nc",
                                      sim::ExecuteOptionsFor(*s), sink, verifier)
                      .ok);
      Report report;
      verifier.Finish(report);
      long side_force_errors = 0;
      for (const auto& rule : report.rules) {
        if (rule.id == "needle.side_force") side_force_errors = rule.errors;
      }
      EXPECT_EQ(side_force_errors > 0, fails) << radius_in << " in";
      EXPECT_EQ(report.verdict, fails ? "fail" : "pass") << radius_in << " in";
    }
  }
}

}  // namespace
}  // namespace stitchsim::verify
