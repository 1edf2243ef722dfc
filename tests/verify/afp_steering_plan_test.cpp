// issue 26 item 3: the steering radius the ply planner reports and the one afp.steering_radius
// reads from the programme are one measure (process/afp_steering.h): per tow they agree on
// every bundled ply, with projected and geodesic references; and on a cylinder, where the
// projected fibre axis has a closed form in the unrolled plane, both equal it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "afp_test_support.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::verify {
namespace {

using namespace testing;
namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;

// The programme read back as the executor's line records (part frame poses, tows, course).
std::vector<trace::LineRecord> LinesOf(const std::string& text) {
  DiagnosticSink sink;
  const program::Dialect& dialect = program::Dialect::Default();
  const auto blocks = program::ParseString(text, dialect, "ply.nc", sink);
  program::ModalState state(dialect, "ply.nc", sink);
  const geom::EulerOrder order = program::EulerOrderOf(dialect);
  std::vector<trace::LineRecord> lines;
  for (const auto& b : blocks) {
    const program::Step& step = state.Update(b);
    if (!step.is_move) continue;
    const auto from = program::ToolPoseOf(state.Previous(), order);
    const auto to = program::ToolPoseOf(state.State(), order);
    if (!to) continue;
    trace::LineRecord l;
    l.source_line = step.source_line;
    l.from = from.value_or(*to);
    l.to = *to;
    l.rapid = step.motion == program::Motion::kRapid;
    l.head_retracted = state.State().head_retracted;
    l.tows = state.State().tows;
    l.course = state.State().course;
    l.ply = state.State().ply;
    l.feed_mm_per_min = state.State().feed_mm_per_min.value_or(0.0);
    lines.push_back(l);
  }
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return lines;
}

struct Radii {
  std::vector<double> planner, verifier;  ///< per tow (index t - 1): smallest over the courses
};

Radii PlanAndVerify(const scene::Scene& scene, const scene::PlySpec& ply) {
  Radii out;
  DiagnosticSink sink;
  const auto plan = planner::PlanPly(scene, ply, {}, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  if (!plan) return out;
  out.planner.assign(static_cast<std::size_t>(plan->layout.tows), INFINITY);
  for (const auto& c : plan->courses)
    for (const auto& t : c.tows) {
      double& r = out.planner[static_cast<std::size_t>(t.tow) - 1];
      r = std::min(r, t.min_radius_mm);
    }
  std::ostringstream text;
  planner::WritePlyProgram(*plan, scene, program::Dialect::Default(), text);
  const Report report = RunLines(scene, LinesOf(text.str()));
  const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
  if (rule == nullptr) {
    ADD_FAILURE() << "no afp.steering_radius";
    return out;
  }
  for (const SubjectFigure& f : rule->subjects)
    out.verifier.push_back(f.worst_value.value_or(INFINITY));
  return out;
}

// Agree within 1 % where steered; a radius over 100 m is straight for a head (the rounding of
// the programme's numbers, 1e-6 mm, reads as a radius of some 1e8 mm over the window).
void ExpectAgree(const Radii& r, const std::string& what) {
  ASSERT_GE(r.verifier.size(), r.planner.size()) << what;
  for (std::size_t i = 0; i < r.planner.size(); ++i) {
    const double p = r.planner[i], v = r.verifier[i];
    if (p > 1e5 && v > 1e5) continue;
    EXPECT_NEAR(v, p, 0.01 * p) << what << " tow " << i + 1;
  }
}

std::unique_ptr<scene::Scene> Load(const fs::path& file) {
  DiagnosticSink sink;
  auto s = scene::LoadScene(file, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return s;
}

// Every ply of the scene named in `only` (empty: every ply), both references.
void ExpectScenePliesAgree(const std::string& scene_name, const std::vector<std::string>& only) {
  auto s = Load(kSource / "scenes" / scene_name);
  ASSERT_NE(s, nullptr);
  for (scene::PlySpec& ply : s->plies) {
    if (!only.empty() && std::find(only.begin(), only.end(), ply.name) == only.end()) continue;
    for (const bool geodesic : {false, true}) {
      ply.reference_path =
          geodesic ? scene::ReferencePath::kGeodesic : scene::ReferencePath::kProjected;
      const Radii r = PlanAndVerify(*s, ply);
      if (r.planner.empty() || r.verifier.empty()) continue;
      std::printf("%s %s %s: smallest tow radius, planner %.1f mm, verifier %.1f mm\n",
                  scene_name.c_str(), ply.name.c_str(), geodesic ? "geodesic" : "projected",
                  *std::min_element(r.planner.begin(), r.planner.end()),
                  *std::min_element(r.verifier.begin(), r.verifier.end()));
      ExpectAgree(r, scene_name + " " + ply.name + (geodesic ? " geodesic" : " projected"));
    }
  }
}

// The fibre axis at 30 deg on the crown of a cylinder of radius 600 mm, projected along -z:
// in the unrolled plane (u axial, v arc) the reference is v = R asin(u tan(30 deg) / R), and
// an offset (corrected method) or a tow a distance d to its left is its parallel, whose radius
// is 1 / kappa - d. Computed here from the 3D tow centres, not from the planner's (u, v).
struct UnrolledAxis {
  double r = 600.0, k = std::tan(30.0 * kPi / 180.0);
  double V(double u) const { return r * std::asin(k * u / r); }
  double V1(double u) const { return k / std::sqrt(1.0 - std::pow(k * u / r, 2)); }
  double V2(double u) const {
    const double w = k * u / r;
    return k * k * w / r / std::pow(1.0 - w * w, 1.5);
  }
  // Radius of the parallel curve through the unrolled point (u, v).
  double RadiusAt(double u, double v) const {
    double a = u;  // the foot on the reference: Newton on (a - u) + (V(a) - v) V'(a) = 0
    for (int i = 0; i < 50; ++i) {
      const double f = (a - u) + (V(a) - v) * V1(a);
      const double df = 1.0 + V1(a) * V1(a) + (V(a) - v) * V2(a);
      a -= f / df;
    }
    const double norm = std::sqrt(1.0 + V1(a) * V1(a));
    const double d = (-(u - a) * V1(a) + (v - V(a))) / norm;  // to the left of (1, V')
    const double kappa = V2(a) / std::pow(norm, 3);
    return std::abs(1.0 / kappa - d);
  }
};

TEST(AfpSteeringPlan, ProjectedReferenceOnACylinderSteersAsItsClosedForm) {
  const std::string yaml =
      "stitchsim_scene: 1\nname: cyl600\nunits: mm\nhead: afp\npart:\n  mount: table\n"
      "  position: [0, -400, 300]\nsurface:\n  type: cylinder\n  radius: 600\n"
      "  side: outside\n  length: 1400\n  arc_length: 900\npreform:\n  thickness: 2\n"
      "mold:\n  depth: 40\npaths:\n  - {name: crown, type: line, from: [-300, 0], to: [300, 0]}\n"
      "plies:\n  - name: p30\n    angle_deg: 30\n"
      "    reference: {origin: [0, 0, 100], direction: [1, 0, 0]}\n"
      "    boundary_uv: [[-400, -180], [400, -180], [400, 180], [-400, 180]]\n"
      "    rule: offset\n    method: corrected\n    coverage: 50\n";
  const fs::path dir =
      fs::temp_directory_path() / ("stitchsim_steer_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  { std::ofstream(dir / "cyl600.yaml") << yaml; }
  auto s = Load(dir / "cyl600.yaml");
  ASSERT_NE(s, nullptr);
  // The tows as the boundary cuts them: a short piece extended past its course's curve runs
  // on along the curve's end geodesic, which is not the parallel of the closed form.
  s->head.afp.cut_to_roller_mm.reset();
  s->head.afp.min_restart_mm.reset();
  DiagnosticSink sink;
  const auto plan = planner::PlanPly(*s, s->plies.front(), {}, sink);
  ASSERT_TRUE(plan);
  const UnrolledAxis axis;
  const double half_window = 25.0;
  std::vector<double> closed(16, INFINITY), planned(16, INFINITY);
  double reference_closed = INFINITY, reference_planned = INFINITY;
  for (const auto& c : plan->courses) {
    for (const auto& tow : c.tows) {
      const std::size_t t = static_cast<std::size_t>(tow.tow);
      double expected = INFINITY;
      for (const auto& seg : tow.laid) {
        for (const auto& p : c.points) {
          if (p.s_mm < seg.start_mm + half_window || p.s_mm > seg.end_mm - half_window) continue;
          const Eigen::Vector3d q = 0.5 * (p.boundary[t - 1] + p.boundary[t]);
          expected =
              std::min(expected, axis.RadiusAt(q.x(), axis.r * std::atan2(q.y(), q.z() + axis.r)));
        }
      }
      if (!std::isfinite(expected)) continue;  // laid over less than a window
      EXPECT_NEAR(tow.min_radius_mm, expected, 0.01 * expected)
          << "course " << c.offset_index << " tow " << t;
      closed[t - 1] = std::min(closed[t - 1], expected);
      planned[t - 1] = std::min(planned[t - 1], tow.min_radius_mm);
      if (c.offset_index == 0) {
        reference_closed = std::min(reference_closed, expected);
        reference_planned = std::min(reference_planned, tow.min_radius_mm);
      }
    }
  }
  std::printf("reference course: planner %.1f mm, closed form %.1f mm; ply: planner %.1f mm\n",
              reference_planned, reference_closed, plan->min_radius_mm);
  EXPECT_NEAR(reference_planned, reference_closed, 0.01 * reference_closed);
  // The verifier reads the same from the programme.
  std::ostringstream text;
  planner::WritePlyProgram(*plan, *s, program::Dialect::Default(), text);
  const Report report = RunLines(*s, LinesOf(text.str()));
  const RuleSummary* rule = RuleOf(report, "afp.steering_radius");
  ASSERT_NE(rule, nullptr);
  for (std::size_t i = 0; i < 16; ++i) {
    if (!std::isfinite(closed[i])) continue;
    ASSERT_TRUE(rule->subjects[i].worst_value);
    EXPECT_NEAR(*rule->subjects[i].worst_value, closed[i], 0.01 * closed[i]) << "tow " << i + 1;
  }
  fs::remove_all(dir);
}

TEST(AfpSteeringPlan, PlannerAndVerifierAgreePerTowOnThePanel) {
  ExpectScenePliesAgree("afp_panel.yaml", {});
}
TEST(AfpSteeringPlan, PlannerAndVerifierAgreePerTowOnTheSequencingCylinder) {
  ExpectScenePliesAgree("seq_cylinder.yaml", {});
}
TEST(AfpSteeringPlan, PlannerAndVerifierAgreePerTowOnTheSequencingPlate) {
  ExpectScenePliesAgree("seq_plate.yaml", {});
}
TEST(AfpSteeringPlan, PlannerAndVerifierAgreePerTowOnTheWing) {
  ExpectScenePliesAgree("naca_wing.yaml", {"upper_45"});
}
// upper_skin_0 is 7.1 m of span, 19 courses each way: labelled slow
// (tests/verify/CMakeLists.txt).
TEST(AfpSteeringPlan, PlannerAndVerifierAgreePerTowOnTheOtherWingPlies) {
  ExpectScenePliesAgree("naca_wing.yaml", {"upper_0", "upper_skin_0"});
}

}  // namespace
}  // namespace stitchsim::verify
