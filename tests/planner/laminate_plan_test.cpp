// The laminate planner (issue 29) on a flat plate, against closed forms: n plies of thickness t
// on one boundary put ply k's tool at z = (k - 1) t wherever every ply below covers; a pad-up
// lifts the ply above by its own t over the pad-up and nowhere else; same-angle plies have
// their course centre lines W / (w + 1) apart, and afp.stagger passes on the programme where
// the unshifted plan fails it; the programme is the same bytes for 1 and 2 threads; a stagger
// a course cannot hold is refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "stitchsim/common/units.h"
#include "stitchsim/planner/laminate_planner.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/robot_model.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;

constexpr double kCourseMm = 16 * 6.35;  // the bundled head: 16 tows of 6.35 mm
constexpr double kT = 0.25;              // ply thickness, mm (sums of it are exact)

// A 1200 x 1000 mm plate (part frame z = 0, (u, v) = (x, y)) and one laminate `plate` whose
// stack is `stack` (YAML list items), with the stagger rule given.
fs::path Folder() {
  const fs::path dir =
      fs::temp_directory_path() / ("stitchsim_laminate_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::unique_ptr<scene::Scene> Plate(
    const std::string& stack, const std::string& stagger, const std::string& tag,
    const std::string& surface = "surface:\n  type: plane\n  size: [1200, 1000]\n") {
  const fs::path file = Folder() / (tag + ".yaml");
  std::ofstream(file)
      << "stitchsim_scene: 1\nname: plate\nunits: mm\nhead: afp\npart:\n  mount: table\n"
         "  position: [0, -400, 50]\n"
      << surface
      << "preform:\n  thickness: 2\nmold:\n  depth: 40\npaths:\n  - name: row\n    type: line\n"
         "    from: [100, 100]\n    to: [200, 100]\nlaminates:\n  - name: plate\n"
         "    rosette: {origin: [0, 0, 100], direction: [1, 0, 0]}\n    stagger: "
      << stagger << "\n    stack:\n"
      << stack;
  DiagnosticSink sink;
  auto s = scene::LoadScene(file, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return s;
}

std::string Entry(int angle_deg, const std::string& box) {
  return "      - {angle_deg: " + std::to_string(angle_deg) + ", boundary_uv: " + box +
         ", thickness: " + std::to_string(kT) + "}\n";
}
const std::string kBig = "[[-200, -150], [200, -150], [200, 150], [-200, 150]]";

std::optional<LaminatePlan> Plan(const scene::Scene& s, int jobs = 2) {
  DiagnosticSink sink;
  LaminatePlanOptions o;
  o.jobs = jobs;
  auto plan = PlanLaminate(s, s.laminates.front(), o, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return plan;
}

bool Inside(const Eigen::Vector2d& p, double u0, double v0, double u1, double v1) {
  return p.x() > u0 && p.x() < u1 && p.y() > v0 && p.y() < v1;
}

// A one-tow course between points at u 0 and 100, its tow's edges at v = lo and hi, laid from
// s0 to s1.
planner::PlyCourse OneTowCourse(double lo, double hi, double s0, double s1) {
  planner::PlyCourse course;
  for (const double u : {0.0, 100.0}) {
    planner::PlyPoint p;
    p.s_mm = u;
    p.boundary_uv = {Eigen::Vector2d(u, lo), Eigen::Vector2d(u, hi)};
    course.points.push_back(p);
  }
  planner::PlyTow tow;
  tow.tow = 1;
  tow.laid = {planner::TowSegment{s0, s1}};
  course.tows.push_back(tow);
  return course;
}

// A tow piece that starts and ends between two course points (its add and cut) lays only that
// part of the step: a tow over v 0..9 laid from s 30 to 70 raises the cells u 30..70 by t and
// none beyond (cells of 2 mm centred on odd mm, centre lookup). A second course abutting it
// with a seam of 1e-4 mm through the cell centres at v = 9 (the walk's rounding) leaves no
// trench there.
TEST(LaminatePlanner, AThicknessFieldPaintsPiecesEndingBetweenPointsAndClosesRoundingSeams) {
  planner::PlyPlan plan;
  plan.band = process::TowBand{1, 1};
  plan.courses = {OneTowCourse(0.0, 8.99995, 30.0, 70.0), OneTowCourse(9.00005, 18.0, 0.0, 100.0)};
  planner::ThicknessField field(geom::Domain2{Eigen::Vector2d(-50, -50), Eigen::Vector2d(150, 60)},
                                2.0);
  field.AddPly(plan, 0.18);
  for (const double u : {31.0, 50.0, 69.0}) EXPECT_NEAR(field.At({u, 5.0}), 0.18, 1e-12) << u;
  for (const double u : {10.0, 27.0, 73.0, 90.0}) EXPECT_NEAR(field.At({u, 5.0}), 0.0, 1e-12) << u;
  for (const double u : {31.0, 51.0, 69.0}) EXPECT_NEAR(field.At({u, 9.0}), 0.18, 1e-12) << u;
}

TEST(LaminatePlanner, FlatPlateStackLiftsPlyKByKMinusOneThicknesses) {
  // Angles 0, 90, 45, -45: no stagger shift, every ply on the same boundary.
  const auto s = Plate(Entry(0, kBig) + Entry(90, kBig) + Entry(45, kBig) + Entry(-45, kBig),
                       "{offset: 10, plies_before_repeat: 1}", "stack");
  ASSERT_NE(s, nullptr);
  const auto plan = Plan(*s);
  ASSERT_TRUE(plan);
  ASSERT_EQ(plan->plies.size(), 4u);
  // Every ply covers the box but a band of one tow (coverage 50 %: half a tow) and a cell
  // along its boundary; inside that, all plies below lie under ply k.
  const double m = 6.35 + 2.0 + 1e-6;
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    const LaminatePly& p = plan->plies[k];
    int checked = 0;
    for (const PlyCourse& c : p.plan.courses)
      for (const PlyPoint& q : c.points) {
        if (!Inside(q.uv, -200 + m, -150 + m, 200 - m, 150 - m)) continue;
        ASSERT_NEAR(q.tool.translation().z(), k * kT, 1e-9) << q.uv.transpose();
        // The lift is along the plate's normal only.
        ASSERT_NEAR(q.tool.translation().x(), q.uv.x(), 1e-9);
        ASSERT_NEAR(q.tool.translation().y(), q.uv.y(), 1e-9);
        ++checked;
      }
    EXPECT_GT(checked, 100);
    EXPECT_EQ(p.stagger_shift_mm, 0.0);
    EXPECT_NEAR(p.below_max_mm, k * kT, 1e-12);
  }
  EXPECT_NEAR(plan->max_thickness_mm, 4 * kT, 1e-12);
}

TEST(LaminatePlanner, APadUpLiftsThePlyAboveByItsThicknessOverThePadUpOnly) {
  // The pad-up's lateral edges lie on tow edges (5 tows past its middle course's half width:
  // 50.8 + 5 x 6.35 = 82.55 mm), its ends on its boundary (tows cut at 50 %).
  const double e = 82.55;
  const std::string pad = "[[-80, -82.55], [80, -82.55], [80, 82.55], [-80, 82.55]]";
  const auto s =
      Plate(Entry(0, pad) + Entry(90, kBig), "{offset: 10, plies_before_repeat: 1}", "padup");
  ASSERT_NE(s, nullptr);
  const auto plan = Plan(*s);
  ASSERT_TRUE(plan);
  const LaminatePly& above = plan->plies[1];
  const double ramp = 2.0 + 1e-6;  // one cell either side of the pad-up's edge
  int on = 0, off = 0;
  for (const PlyCourse& c : above.plan.courses)
    for (const PlyPoint& q : c.points) {
      const double z = q.tool.translation().z();
      if (Inside(q.uv, -80 + ramp, -e + ramp, 80 - ramp, e - ramp)) {
        ASSERT_NEAR(z, kT, 1e-9) << q.uv.transpose();
        ++on;
      } else if (!Inside(q.uv, -80 - ramp, -e - ramp, 80 + ramp, e + ramp)) {
        ASSERT_NEAR(z, 0.0, 1e-9) << q.uv.transpose();
        ++off;
      }
    }
  EXPECT_GT(on, 25);  // the course at x = 0 crosses the pad-up (points <= 5 mm apart)
  EXPECT_GT(off, 50);
  EXPECT_NEAR(above.below_min_mm, 0.0, 1e-12);
  EXPECT_NEAR(above.below_max_mm, kT, 1e-12);
}

// Distance of `y` from the nearest of the lines offset + n W, mm.
double FromLattice(double y, double offset) {
  return std::abs(std::remainder(y - offset, kCourseMm));
}

verify::Report VerifyText(const scene::Scene& s, const std::string& text) {
  DiagnosticSink sink;
  auto robot = sim::LoadRobotModel(s.cell_urdf, sink);
  EXPECT_TRUE(robot.has_value());
  const sim::CellSetup cell = sim::MakeCellSetup(*robot, s);
  const process::ProcessModel model = process::MakeProcessModel(s, 5.0);
  const trace::CellDescription description = sim::DescribeCell(*robot, nullptr);
  verify::Verifier verifier(verify::RuleContext{&s, &description, &model}, false);
  std::istringstream in(text);
  sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, "laminate.nc",
                      sim::ExecuteOptionsFor(s), sink, verifier);
  EXPECT_FALSE(sink.HasErrors());
  verify::Report report;
  verifier.Finish(report);
  return report;
}

const verify::RuleSummary* Stagger(const verify::Report& r) {
  for (const auto& rule : r.rules)
    if (rule.id == "afp.stagger") return &rule;
  return nullptr;
}

TEST(LaminatePlanner, SameAnglePliesAreStaggeredAndAfpStaggerPassesWhereUnshiftedFails) {
  const auto s =
      Plate(Entry(0, kBig) + Entry(0, kBig), "{offset: 10, plies_before_repeat: 1}", "stagger");
  ASSERT_NE(s, nullptr);
  const auto plan = Plan(*s);
  ASSERT_TRUE(plan);
  // Closed form: ply 1's centre lines at y = n W, ply 2's at W / 2 + n W (w = 1).
  EXPECT_NEAR(plan->plies[1].stagger_shift_mm, kCourseMm / 2, 1e-12);
  for (std::size_t k = 0; k < 2; ++k)
    for (const PlyCourse& c : plan->plies[k].plan.courses)
      for (const PlyPoint& q : c.points) ASSERT_LT(FromLattice(q.uv.y(), k * kCourseMm / 2), 1e-6);

  std::ostringstream staggered;
  WriteLaminateProgram(*plan, *s, program::Dialect::Default(), staggered);
  const verify::Report good = VerifyText(*s, staggered.str());
  const verify::RuleSummary* passed = Stagger(good);
  ASSERT_NE(passed, nullptr);
  EXPECT_EQ(passed->errors, 0);
  EXPECT_GT(passed->checked, 0);
  // No seam of ply 1 within the rule's reach (offset + a seam piece) of one of ply 2.
  if (passed->worst_value) {
    EXPECT_GE(*passed->worst_value, 10.0);
  }

  // Both plies planned on their own (no shift): the seams lie on one another.
  std::vector<PlyPlan> alone;
  for (const auto& entry : s->laminates.front().stack) {
    DiagnosticSink sink;
    alone.push_back(*PlanPly(*s, s->plies[entry.ply], {}, sink));
  }
  const PlyPlan* both[] = {&alone[0], &alone[1]};
  std::ostringstream unshifted;
  WritePlyProgram(both, *s, program::Dialect::Default(), unshifted, "plate");
  const verify::Report bad = VerifyText(*s, unshifted.str());
  const verify::RuleSummary* fired = Stagger(bad);
  ASSERT_NE(fired, nullptr);
  EXPECT_GT(fired->errors, 0);
  ASSERT_TRUE(fired->worst_value);
  EXPECT_LT(*fired->worst_value, 1e-6);
}

// On the seed-002 wing (an OpenCASCADE surface, whose projection starts from the last answer
// on its thread) as on the plate: the programme must not depend on which thread planned which
// ply (it did, in the sixth decimal, before each ply got a thread of its own).
TEST(LaminatePlanner, OneAndTwoThreadsWriteTheSameProgramme) {
  std::ifstream in(fs::path(STITCHSIM_SOURCE_DIR) / "scenes" / "naca_wing.yaml");
  std::stringstream wing_text;
  wing_text << in.rdbuf();
  std::string wing = wing_text.str();
  wing = wing.substr(0, wing.find("\nlaminates:\n") + 1);
  const std::string box = "[[700, 3500], [1100, 3500], [1100, 3900], [700, 3900]]";
  std::string lam =
      "laminates:\n  - name: plate\n    rosette: {origin: [1000, 3750, 400], direction: [0, 1, "
      "0]}\n    stagger: {offset: 10, plies_before_repeat: 1}\n    stack:\n";
  for (int angle : {0, 45, 0}) lam += Entry(angle, box);
  const fs::path file = Folder() / "wing.yaml";
  std::ofstream(file) << wing << lam;
  DiagnosticSink sink;
  const auto wing_scene = scene::LoadScene(file, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  ASSERT_NE(wing_scene, nullptr);
  const auto plate = Plate(Entry(0, kBig) + Entry(45, kBig) + Entry(0, kBig) + Entry(90, kBig),
                           "{offset: 10, plies_before_repeat: 1}", "jobs");
  ASSERT_NE(plate, nullptr);
  for (const scene::Scene* s : {plate.get(), wing_scene.get()}) {
    SCOPED_TRACE(s->name);
    std::string text[2];
    for (int jobs : {1, 2}) {
      const auto plan = Plan(*s, jobs);
      ASSERT_TRUE(plan);
      std::ostringstream out;
      WriteLaminateProgram(*plan, *s, program::Dialect::Default(), out);
      text[jobs - 1] = out.str();
    }
    EXPECT_FALSE(text[0].empty());
    EXPECT_TRUE(text[0] == text[1]);
    EXPECT_NE(text[0].find("laminate=plate"), std::string::npos);
  }
}

TEST(LaminatePlanner, AStaggerACourseCannotHoldIsRefused) {
  // Three seam positions in a course of 101.6 mm are 33.87 mm apart: an offset of 40 mm cannot
  // be kept (the scene accepts it: it is under a course).
  const auto s =
      Plate(Entry(0, kBig) + Entry(0, kBig), "{offset: 40, plies_before_repeat: 2}", "refused");
  ASSERT_NE(s, nullptr);
  DiagnosticSink sink;
  EXPECT_FALSE(PlanLaminate(*s, s->laminates.front(), {}, sink));
  ASSERT_EQ(sink.Diagnostics().size(), 1u);
  EXPECT_EQ(sink.Diagnostics()[0].code, "plan-laminate-stagger");
  EXPECT_NE(sink.Diagnostics()[0].message.find("33.87"), std::string::npos);
}

}  // namespace
}  // namespace stitchsim::planner
