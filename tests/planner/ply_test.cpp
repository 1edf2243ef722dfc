// The ply planner (issue 12, S8, Done-when 1): band offset plies at 0 and 45 deg on the
// bundled doubly curved panel and on a STEP part; the programme read back through the parser
// and the modal state; tool points and tow edges on the surface; the tows rebuilt from the
// programme's poses by process::TowsAt equal to the CSV; the coverage policies' boundaries.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "ply_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/geom/polygon2.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/tool_pose.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
using testing::Folder;
using testing::Load;
using testing::Plies;
using testing::SceneText;

struct CsvRow {
  int course = 0, tow = 0;
  double s = 0.0;
  Eigen::Vector3d left, right;
};
std::vector<CsvRow> ReadCsv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "course,tow,segment,s_start_mm,s_end_mm,s_mm,left_x,left_y,left_z,right_x,right_y,"
            "right_z");
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
    EXPECT_EQ(v.size(), 12u);
    if (v.size() != 12u) continue;
    rows.push_back({static_cast<int>(v[0]), static_cast<int>(v[1]), v[5],
                    Eigen::Vector3d(v[6], v[7], v[8]), Eigen::Vector3d(v[9], v[10], v[11])});
  }
  return rows;
}

/// A programme move inside a course: the pose read back and the tows laying over the move.
struct Move {
  int course = 0;
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  std::uint64_t tows = 0;
};
std::vector<Move> ReadMoves(const std::string& text) {
  DiagnosticSink sink;
  const auto blocks = program::ParseString(text, program::Dialect::Default(), "ply.nc", sink);
  program::ModalState state(program::Dialect::Default(), "ply.nc", sink);
  const geom::EulerOrder order = program::EulerOrderOf(program::Dialect::Default());
  std::vector<Move> moves;
  for (const auto& b : blocks) {
    const program::Step& step = state.Update(b);
    const auto& st = state.State();
    if (!step.is_move || st.course == 0 || !b.axes[0].has_value()) continue;
    if (b.motion == program::Motion::kRapid) continue;
    using program::Axis;
    auto at = [&](Axis a) { return *st.axes[static_cast<std::size_t>(a)]; };
    Move m;
    m.course = st.course;
    m.tows = st.tows;
    m.tool.translation() = Eigen::Vector3d(at(Axis::kX), at(Axis::kY), at(Axis::kZ));
    m.tool.linear() = geom::RotationFromEuler(
        order, Eigen::Vector3d(at(Axis::kA), at(Axis::kB), at(Axis::kC)) * kDeg);
    moves.push_back(m);
  }
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return moves;
}

double OffSurface(const geom::Surface& s, const Eigen::Vector3d& p) {
  return std::abs(s.Project(p).signed_distance_mm);
}

/// Plans, writes and reads back one ply; checks every Done-when 1 property.
void CheckPly(const scene::Scene& scene, const std::string& name, int min_courses,
              double seam_tol_mm = 0.05) {
  SCOPED_TRACE(name);
  const scene::PlySpec* ply = scene.FindPly(name);
  ASSERT_NE(ply, nullptr);
  DiagnosticSink sink;
  const auto plan = PlanPly(scene, *ply, {}, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  ASSERT_TRUE(plan);
  EXPECT_GE(static_cast<int>(plan->courses.size()), min_courses);
  EXPECT_TRUE(plan->findings.empty());
  EXPECT_LT(plan->max_gap_mm, seam_tol_mm);
  EXPECT_LT(plan->max_overlap_mm, seam_tol_mm);
  std::ostringstream prog, csv;
  WritePlyProgram(*plan, scene, program::Dialect::Default(), prog);
  WritePlyTowsCsv(*plan, csv);
  const std::string text = prog.str();
  EXPECT_NE(text.find("T3 M6"), std::string::npos);
  EXPECT_NE(text.find("M70 P"), std::string::npos);
  const std::vector<Move> moves = ReadMoves(text);
  const geom::Surface& surface = *scene.surface;
  // Per course, its moves in order = the plan's points in order.
  std::map<int, std::vector<const Move*>> by_course;
  for (const Move& m : moves) by_course[m.course].push_back(&m);
  ASSERT_EQ(by_course.size(), plan->courses.size());
  std::map<std::pair<int, long>, process::TowCross> rebuilt;  // (course, s in um) -> tows
  for (const PlyCourse& c : plan->courses) {
    const auto& ms = by_course[c.number];
    ASSERT_EQ(ms.size(), c.points.size());
    for (std::size_t j = 0; j < ms.size(); ++j) {
      const Move& m = *ms[j];
      EXPECT_LT(OffSurface(surface, m.tool.translation()), 0.01);
      const process::TowCross cross =
          process::TowsAt(surface, m.tool, plan->layout, &c.points[j].uv);
      ASSERT_TRUE(cross.ok);
      rebuilt[{c.number, std::lround(c.points[j].s_mm * 1e6)}] = cross;
      // The tows laying over the move into point j: those laid over [s_j-1, s_j].
      if (j == 0) continue;
      for (const PlyTow& t : c.tows) {
        bool laid = false;
        for (const TowSegment& g : t.laid)
          laid = laid || (g.start_mm <= c.points[j - 1].s_mm && c.points[j].s_mm <= g.end_mm);
        EXPECT_EQ((m.tows >> (t.tow - 1)) & 1u, laid ? 1u : 0u)
            << "course " << c.number << " tow " << t.tow << " move " << j;
      }
    }
  }
  const std::vector<CsvRow> rows = ReadCsv(csv.str());
  ASSERT_FALSE(rows.empty());
  double worst_surface = 0.0, worst_rebuilt = 0.0;
  for (const CsvRow& r : rows) {
    worst_surface =
        std::max({worst_surface, OffSurface(surface, r.left), OffSurface(surface, r.right)});
    const auto it = rebuilt.find({r.course, std::lround(r.s * 1e6)});
    ASSERT_NE(it, rebuilt.end()) << "course " << r.course << " s " << r.s;
    const auto& b = it->second.boundary;
    worst_rebuilt =
        std::max({worst_rebuilt, (b[static_cast<std::size_t>(r.tow - 1)] - r.left).norm(),
                  (b[static_cast<std::size_t>(r.tow)] - r.right).norm()});
  }
  EXPECT_LT(worst_surface, 0.01);
  EXPECT_LT(worst_rebuilt, 0.01);
}

TEST(PlyPlanner, BundledPanelPliesAtZeroAnd45) {
  const auto s = Load(kSource / "scenes" / "afp_panel.yaml");
  ASSERT_NE(s, nullptr);
  CheckPly(*s, "skin_0", 3);
  CheckPly(*s, "skin_45", 4);
}

// The panel's patch written as a STEP part by the CAD writer, the same plies on its face.
TEST(PlyPlanner, StepPartPliesAtZeroAnd45) {
  const fs::path dir = Folder("step");
  geom::BSplineSpec spec;
  spec.degree_u = spec.degree_v = 2;
  spec.poles = {{{-300, -200, 0}, {-300, 0, 20}, {-300, 200, 0}},
                {{0, -200, 20}, {0, 0, 40}, {0, 200, 20}},
                {{300, -200, 0}, {300, 0, 20}, {300, 200, 0}}};
  std::string err;
  ASSERT_TRUE(
      geom::WriteBSplineCad({spec}, {"skin"}, dir / "part.step", geom::CadFormat::kStep, "MM", err))
      << err;
  std::ofstream(dir / "s.yaml") << SceneText(
      "surface:\n  type: step\n  file: part.step\n  face: 0\n",
      Plies("[[130, 120], [475, 120], [475, 285], [130, 285]]", 50));
  const auto s = Load(dir / "s.yaml");
  ASSERT_NE(s, nullptr);
  CheckPly(*s, "p0", 3);
  CheckPly(*s, "p45", 4);
}

/// Coverage on a plane (u = x, v = y): grid points outside the ply under laid tows, and
/// grid points inside it under none.
struct Coverage {
  int covered_outside = 0;
  int bare_inside = 0;
};
Coverage Measure(const PlyPlan& plan, const std::vector<Eigen::Vector2d>& boundary) {
  const double step = 0.5;
  std::map<std::pair<long, long>, bool> covered;
  for (const PlyCourse& c : plan.courses) {
    for (const PlyTow& t : c.tows) {
      const std::size_t i = static_cast<std::size_t>(t.tow - plan.band.first + 1);
      for (std::size_t j = 1; j < c.points.size(); ++j) {
        const PlyPoint& a = c.points[j - 1];
        const PlyPoint& b = c.points[j];
        bool laid = false;
        for (const TowSegment& g : t.laid)
          laid = laid || (g.start_mm <= a.s_mm && b.s_mm <= g.end_mm);
        if (!laid) continue;
        const geom::Polygon2 quad = {a.boundary[i - 1].head<2>(), a.boundary[i].head<2>(),
                                     b.boundary[i].head<2>(), b.boundary[i - 1].head<2>()};
        Eigen::Vector2d lo = quad[0], hi = quad[0];
        for (const auto& q : quad) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
        for (long x = std::lround(std::ceil(lo.x() / step)); x * step <= hi.x(); ++x) {
          for (long y = std::lround(std::ceil(lo.y() / step)); y * step <= hi.y(); ++y) {
            const Eigen::Vector2d p(x * step, y * step);
            if (geom::InsidePolygon(quad, p) || geom::DistanceToPolygon(quad, p) < 1e-6)
              covered[{x, y}] = true;
          }
        }
      }
    }
  }
  Coverage r;
  for (const auto& [key, on] : covered) {
    const Eigen::Vector2d p(key.first * step, key.second * step);
    if (on && !geom::InsidePolygon(boundary, p) && geom::DistanceToPolygon(boundary, p) > 0.01)
      ++r.covered_outside;
  }
  for (long x = -400; x <= 400; ++x) {
    for (long y = -400; y <= 400; ++y) {
      const Eigen::Vector2d p(x * step, y * step);
      if (geom::InsidePolygon(boundary, p) && geom::DistanceToPolygon(boundary, p) > 0.01 &&
          !covered.count({x, y}))
        ++r.bare_inside;
    }
  }
  return r;
}

TEST(PlyPlanner, CoveragePoliciesAtTheBoundaryOfA45DegRectangle) {
  const std::vector<Eigen::Vector2d> box = {{-150, -100}, {150, -100}, {150, 100}, {-150, 100}};
  Coverage seen[3];
  for (int k = 0; k < 3; ++k) {
    const int pct = k * 50;
    SCOPED_TRACE(pct);
    const fs::path dir = Folder("coverage" + std::to_string(pct));
    std::ofstream(dir / "s.yaml") << SceneText(
        "surface:\n  type: plane\n  size: [600, 400]\n",
        Plies("[[-150, -100], [150, -100], [150, 100], [-150, 100]]", pct, "45"));
    const auto s = Load(dir / "s.yaml");
    ASSERT_NE(s, nullptr);
    DiagnosticSink sink;
    const auto plan = PlanPly(*s, s->plies.front(), {}, sink);
    ASSERT_TRUE(plan);
    seen[k] = Measure(*plan, box);
  }
  EXPECT_EQ(seen[0].covered_outside, 0);  // 0 %: no material past the boundary ...
  EXPECT_GT(seen[0].bare_inside, 0);      // ... and bare triangles inside it
  EXPECT_GT(seen[1].covered_outside, 0);  // 50 %: some of each
  EXPECT_GT(seen[1].bare_inside, 0);
  EXPECT_GT(seen[2].covered_outside, 0);  // 100 %: material past the boundary ...
  EXPECT_EQ(seen[2].bare_inside, 0);      // ... and none of the ply bare
  EXPECT_LT(seen[0].covered_outside, seen[1].covered_outside);
  EXPECT_LT(seen[1].bare_inside, seen[0].bare_inside);
}

// A tow steered below the head's limit is a finding of the plan (the head spec's limit raised
// above the panel's steering radius).
TEST(PlyPlanner, SteeringBelowTheHeadsRadiusIsAFinding) {
  auto s = Load(kSource / "scenes" / "afp_panel.yaml");
  ASSERT_NE(s, nullptr);
  s->head.afp.min_steering_radius_mm = 1e7;
  DiagnosticSink sink;
  const auto plan = PlanPly(*s, *s->FindPly("skin_45"), {}, sink);
  ASSERT_TRUE(plan);
  ASSERT_EQ(plan->findings.size(), 1u);
  EXPECT_EQ(plan->findings[0].code, "ply-steering-radius");
  EXPECT_LT(plan->min_radius_mm, 1e7);
  EXPECT_GT(plan->min_radius_mm, 635.0);
}

// Rule laminate_family: the courses are laminate family curves at 45 deg across the 0 deg
// reference's offsets; the same programme checks, small gaps where the courses diverge.
TEST(PlyPlanner, LaminateFamilyPlyAt45) {
  std::ifstream in(kSource / "scenes" / "afp_panel.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  for (std::size_t at; (at = yaml.find("rule: offset")) != std::string::npos;)
    yaml.replace(at, 12, "rule: laminate_family");
  const fs::path dir = Folder("laminate");
  std::ofstream(dir / "s.yaml") << yaml;
  const auto s = Load(dir / "s.yaml");
  ASSERT_NE(s, nullptr);
  ASSERT_EQ(s->FindPly("skin_45")->rule, scene::PlyRule::kLaminateFamily);
  CheckPly(*s, "skin_45", 4, 1.0);
}

}  // namespace
}  // namespace stitchsim::planner
