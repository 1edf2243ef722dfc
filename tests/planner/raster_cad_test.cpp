// The raster planner in a surface's own (u, v) (docs/raster.md): the wing_cover skin made with
// the kernel as a Bezier patch, written to a STEP file and read back through the `step` kind,
// raster-plans a window of the cover like the polynomial skin does (stitch count within a few,
// every stitch on the surface within 0.01 mm), verifies clean with the wing_cover rules, and
// constraint.crossing judges its programme in (u, v): a stitch moved onto a stringer and a
// needles-down traverse across an intercostal each fire on their line. A cylinder: rows a row
// spacing apart on the surface, no stitch in a footprint.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "../scene/scene_test_support.h"
#include "raster_test_support.h"
#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/scene/footprint.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
constexpr double kInch = 25.4;
constexpr double kCamberPerIn = -0.002;  // wing_cover: z = -0.002 y^2 (inches)

// The wing_cover skin (z = -0.002 y^2 in inches over x in [-240, 240], y in [-48, 48]) is
// exactly a Bezier patch, degree 1 along x (u) and 2 along y (v); the middle pole lies where
// the end tangents meet (z = 4.608 in). Poles in mm.
geom::BSplineSpec Skin() {
  geom::BSplineSpec s;
  s.degree_u = 1;
  s.degree_v = 2;
  const double edge = kCamberPerIn * 48 * 48;
  for (double x : {-240.0, 240.0}) {
    s.poles.push_back({Eigen::Vector3d(x, -48, edge) * kInch, Eigen::Vector3d(x, 0, -edge) * kInch,
                       Eigen::Vector3d(x, 48, edge) * kInch});
  }
  return s;
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// scenes/wing_cover.yaml with its surface replaced by a STEP face (the skin written here) and its
// path moved into the face's (u, v); nullptr and a failure if it does not load.
std::unique_ptr<scene::Scene> StepWingCover() {
  const fs::path dir = scene::testing::Folder("raster_cad", "wing");
  std::string error;
  // In inches, as the scene: the step kind reads the file's unit.
  EXPECT_TRUE(geom::WriteBSplineCad({Skin()}, {"skin"}, dir / "wing_skin.step",
                                    geom::CadFormat::kStep, "INCH", error))
      << error;
  std::string text = ReadText(kSource / "scenes" / "wing_cover.yaml");
  const std::size_t surface = text.find("\nsurface:\n"), preform = text.find("\npreform:");
  const std::size_t paths = text.find("\npaths:");
  EXPECT_TRUE(surface != std::string::npos && preform > surface && paths > preform);
  text = text.substr(0, surface) + "\nsurface: {type: step, file: wing_skin.step, face: 0}" +
         text.substr(preform, paths - preform) +
         "\npaths:\n  - {name: bay_row, type: line, from: [210, 26], to: [270, 26]}\n";
  scene::testing::Write(dir / "wing_cover_step.yaml", text);
  DiagnosticSink sink;
  auto s = scene::LoadScene(dir / "wing_cover_step.yaml", sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return s;
}

std::unique_ptr<scene::Scene> Load(const std::string& name) {
  DiagnosticSink sink;
  auto s = scene::LoadScene(kSource / "scenes" / name, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return s;
}

// A 30 x 20 in window of the cover (part frame x, y in inches) with stringer_2 (y = -15),
// stringer_3 (y = 0) and intercostal_3 (x = -40).
const Eigen::AlignedBox2d kWindowIn(Eigen::Vector2d(-55, -18), Eigen::Vector2d(-25, 2));

RasterOptions PolynomialWindow(const scene::Scene& s, RasterStrategy strategy) {
  RasterOptions o = RasterOptionsFor(s);
  o.strategy = strategy;
  o.region = Eigen::AlignedBox2d(kWindowIn.min() * kInch, kWindowIn.max() * kInch);
  return o;
}

// The same window on the STEP face: the (u, v) of the window's corners on the skin.
RasterOptions StepWindow(const scene::Scene& s, RasterStrategy strategy) {
  RasterOptions o = PolynomialWindow(s, strategy);
  Eigen::AlignedBox2d uv;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d xy = kWindowIn.corner(static_cast<Eigen::AlignedBox2d::CornerType>(k));
    const Eigen::Vector3d p(xy.x(), xy.y(), kCamberPerIn * xy.y() * xy.y());
    uv.extend(s.surface->Project(p * kInch).uv);
  }
  o.region = uv;
  return o;
}

// The part-frame positions of the programme's stitches (its G1 moves), read back through the
// parser and the modal state, with their lines.
struct Stitch {
  int line = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};
std::vector<Stitch> Stitches(const std::string& text) {
  DiagnosticSink sink;
  const auto blocks = program::ParseString(text, program::Dialect::Default(), "a.nc", sink);
  program::ModalState state(program::Dialect::Default(), "a.nc", sink);
  std::vector<Stitch> out;
  for (const auto& b : blocks) {
    const program::Step& step = state.Update(b);
    if (!step.is_move || step.motion != program::Motion::kFeed) continue;
    using program::Axis;
    const auto& st = state.State();
    out.push_back({step.source_line, Eigen::Vector3d(*st[Axis::kX], *st[Axis::kY], *st[Axis::kZ])});
  }
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return out;
}

// The STEP face and the polynomial: the same window, nearly the same stitches (rows are spaced
// along the surface on the face, in y on the polynomial; footprints are projected onto the
// surface along its normals on the face, along z on the polynomial: 15990 both in this window),
// and every stitch of the face's programme lies on the face and on the polynomial skin within
// 0.01 mm.
TEST(RasterOnCadSurface, StepWingCoverPlansLikeThePolynomialSkin) {
  const auto poly = Load("wing_cover.yaml");
  const auto step = StepWingCover();
  ASSERT_TRUE(poly && step);
  EXPECT_FALSE(step->surface->IsHeightField());
  for (RasterStrategy strategy : {RasterStrategy::kJump, RasterStrategy::kSerpentine}) {
    SCOPED_TRACE(std::string(ToString(strategy)));
    RasterSummary a, b;
    testing::Plan(*poly, PolynomialWindow(*poly, strategy), &a);
    const std::string text = testing::Plan(*step, StepWindow(*step, strategy), &b);
    EXPECT_GT(a.stitches, 10000);
    EXPECT_LE(std::abs(a.stitches - b.stitches), 5) << a.stitches << " " << b.stitches;
    EXPECT_EQ(a.rows, b.rows);
    // Serpentine: the polynomial retracts where a row end at a bay edge grazes a footprint
    // (the exact slab test of a height field); the face does not.
    if (strategy == RasterStrategy::kJump) {
      EXPECT_EQ(a.jumps, b.jumps);
    }
    EXPECT_LE(b.jumps, a.jumps);
    const std::vector<Stitch> stitches = Stitches(text);
    ASSERT_EQ(static_cast<long>(stitches.size()), b.stitches);
    double worst_face = 0.0, worst_poly = 0.0;
    for (const Stitch& s : stitches) {
      worst_face = std::max(worst_face, std::abs(step->surface->Project(s.p).signed_distance_mm));
      const double y_in = s.p.y() / kInch;
      worst_poly = std::max(worst_poly, std::abs(s.p.z() - kCamberPerIn * y_in * y_in * kInch));
    }
    EXPECT_LT(worst_face, 0.01);
    EXPECT_LT(worst_poly, 0.01);
  }
}

// scenes/wing_cover_step.yaml reads scenes/parts/wing_skin.step, the skin of Skin() in mm,
// written by this test when STITCHSIM_WRITE_PARTS=1 (the command in the scene's comment). The
// face is the polynomial skin, and the window plans as the scratch fixture's does.
TEST(RasterOnCadSurface, BundledStepPartIsTheWingSkin) {
  const fs::path part = kSource / "scenes" / "parts" / "wing_skin.step";
  if (const char* write = std::getenv("STITCHSIM_WRITE_PARTS");
      write && std::string(write) == "1") {
    std::string error;
    ASSERT_TRUE(
        geom::WriteBSplineCad({Skin()}, {"skin"}, part, geom::CadFormat::kStep, "MM", error))
        << error;
  }
  EXPECT_LT(fs::file_size(part), 16u * 1024u);
  const auto bundled = Load("wing_cover_step.yaml");
  ASSERT_TRUE(bundled);
  const geom::Surface& face = *bundled->surface;
  EXPECT_NEAR(face.Domain().max.x(), 480 * kInch, 1e-6);
  for (double fu : {0.0, 0.3, 1.0}) {
    for (double fv : {0.0, 0.25, 0.5, 0.9, 1.0}) {
      const Eigen::Vector3d p = face.Point(face.Domain().max.cwiseProduct(Eigen::Vector2d(fu, fv)));
      const double y_in = p.y() / kInch;
      EXPECT_NEAR(p.z(), kCamberPerIn * y_in * y_in * kInch, 1e-6) << fu << " " << fv;
    }
  }
  const auto fixture = StepWingCover();
  ASSERT_TRUE(fixture);
  RasterSummary a, b;
  testing::Plan(*fixture, StepWindow(*fixture, RasterStrategy::kJump), &a);
  testing::Plan(*bundled, StepWindow(*bundled, RasterStrategy::kJump), &b);
  EXPECT_EQ(a.stitches, b.stitches);
}

// The window of the STEP face verifies like wing_cover: every rule, the collision world
// included, no error and no warning; constraint.crossing checked it.
TEST(RasterOnCadSurface, StepWingCoverWindowVerifiesClean) {
  const auto step = StepWingCover();
  ASSERT_TRUE(step);
  for (RasterStrategy strategy : {RasterStrategy::kJump, RasterStrategy::kSerpentine}) {
    SCOPED_TRACE(std::string(ToString(strategy)));
    const RasterOptions o = StepWindow(*step, strategy);
    RasterSummary sum;
    const std::string text = testing::Plan(*step, o, &sum);
    const verify::Report r = testing::VerifyText(*step, text, o.pitch_mm);
    EXPECT_EQ(r.stitches, sum.stitches);
    EXPECT_EQ(r.verdict, "pass") << testing::Errors(r);
    const verify::RuleSummary* crossing = testing::RuleOf(r, "constraint.crossing");
    ASSERT_NE(crossing, nullptr);
    EXPECT_GT(crossing->checked, 0);
    EXPECT_EQ(crossing->errors, 0);
    for (const auto& rule : r.rules) {
      EXPECT_EQ(rule.warnings, 0) << rule.id << ": "
                                  << (rule.findings.empty() ? "" : rule.findings[0].message);
    }
  }
}

using testing::Join;
using testing::Lines;

// `text` with its stitch number `index` (from 0) moved to `p` (its X kept); and its line.
std::pair<std::string, int> MoveStitch(const std::string& text, std::size_t index,
                                       const Eigen::Vector3d& p) {
  std::vector<std::string> lines = Lines(text);
  const std::vector<Stitch> stitches = Stitches(text);
  EXPECT_GT(stitches.size(), index);
  if (stitches.size() <= index) return {text, 0};
  const int line = stitches[index].line;
  std::string& l = lines[static_cast<std::size_t>(line - 1)];
  const std::size_t at_y = l.find(" Y"), at_a = l.find(" A");
  EXPECT_TRUE(at_y != std::string::npos && at_a != std::string::npos) << l;
  l = l.substr(0, at_y) + " Y" + std::to_string(p.y()) + " Z" + std::to_string(p.z()) +
      l.substr(at_a);
  return {Join(lines), line};
}

// constraint.crossing has errors, all on `subject`, one on `line`.
void ExpectCrossingOnLine(const verify::Report& r, int line, const std::string& subject) {
  const verify::RuleSummary* c = testing::RuleOf(r, "constraint.crossing");
  ASSERT_NE(c, nullptr);
  ASSERT_GT(c->errors, 0);
  bool on_line = false;
  for (const auto& f : c->findings) {
    EXPECT_NE(f.subject.find(subject), std::string::npos) << f.subject;
    on_line = on_line || f.line == line;
  }
  EXPECT_TRUE(on_line) << "expected line " << line << ", first finding on line "
                       << c->findings.front().line;
}

// constraint.crossing on a (u, v)-planned programme off a height field: a stitch moved onto
// stringer_2 (its point on the skin there) fires on its line; a traverse across intercostal_3
// with the needles down (a jump's retract, lift and flight removed) fires on its line.
TEST(RasterOnCadSurface, CrossingRuleJudgesTheStepProgrammeInUv) {
  const auto step = StepWingCover();
  ASSERT_TRUE(step);
  const RasterOptions o = StepWindow(*step, RasterStrategy::kJump);
  const std::vector<std::string> clean = Lines(testing::Plan(*step, o));
  // A stitch of the first row (clear of everything) moved onto stringer_2 at y = -15 in.
  const Eigen::Vector3d on_stringer(0, -15.0 * kInch, kCamberPerIn * 15.0 * 15.0 * kInch);
  const auto [moved, line] = MoveStitch(Join(clean), 19, on_stringer);
  ExpectCrossingOnLine(testing::VerifyText(*step, moved, o.pitch_mm, false), line, "stringer_2");
  // The first jump: M11, M20, G0 up, G0 over, G0 down, M21, M10: keep the last G0 only.
  std::vector<std::string> lines = clean;
  std::size_t m20 = 0;
  while (m20 < lines.size() && lines[m20] != "M20") ++m20;
  ASSERT_TRUE(m20 > 1 && m20 + 4 < lines.size());
  ASSERT_EQ(lines[m20 - 1], "M11");
  ASSERT_EQ(lines[m20 + 4], "M21");
  lines.erase(lines.begin() + static_cast<long>(m20) + 4);
  lines.erase(lines.begin() + static_cast<long>(m20) - 1,
              lines.begin() + static_cast<long>(m20) + 3);
  const int g0_line = static_cast<int>(m20);
  ASSERT_EQ(lines[static_cast<std::size_t>(g0_line - 1)].rfind("G0", 0), 0u);
  const verify::Report r = testing::VerifyText(*step, Join(lines), o.pitch_mm, false);
  const verify::RuleSummary* c = testing::RuleOf(r, "constraint.crossing");
  ASSERT_NE(c, nullptr);
  ASSERT_EQ(c->errors, 1);
  EXPECT_EQ(c->findings.front().line, g0_line);
  EXPECT_NE(c->findings.front().subject.find("intercostal_3"), std::string::npos)
      << c->findings.front().subject;
}

// Coarse: the geometry, not the density, is under test.
RasterOptions CylinderOptions() {
  RasterOptions o;
  o.pitch_mm = 5.0;
  o.row_spacing_mm = 20.0;
  o.margin_mm = 2.0;
  return o;
}

// A footprint off a height field holds the closest points of its grown box's corners; a
// constraint beside the surface does not project. On a height field it is the (x, y) one.
TEST(RasterOnCadSurface, FootprintOnACylinderInItsUv) {
  const auto s = Load("cylinder_r90_frame.yaml");
  ASSERT_TRUE(s);
  ASSERT_FALSE(s->constraints.empty());
  const scene::Constraint& c = s->constraints.front();
  std::string error;
  const auto f = scene::ConstraintFootprintOn(c, *s->surface, 5.0, error);
  ASSERT_TRUE(f.has_value()) << error;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner(((k & 1) ? 0.5 : -0.5) * c.size_mm.x(),
                                 ((k & 2) ? 0.5 : -0.5) * c.size_mm.y(),
                                 ((k & 4) ? 0.5 : -0.5) * c.size_mm.z());
    const Eigen::Vector2d uv = s->surface->Project(c.pose_mm * corner).uv;
    // Inside by about the margin across the stringer (its ends are clamped to the domain).
    const Eigen::Vector2d d = uv - f->centre;
    EXPECT_GE(f->half_mm.y() - std::abs(d.dot(f->axis_y)), 5.0 - 0.1) << k;
  }
  scene::Constraint away = c;
  away.pose_mm.translation().y() += 10000.0;
  EXPECT_FALSE(scene::ConstraintFootprintOn(away, *s->surface, 5.0, error).has_value());
  EXPECT_FALSE(error.empty());
  // The planner reports it at the constraint's line (`c` refers into the vector pushed to).
  const int line = c.where.line;
  s->constraints.push_back(away);
  DiagnosticSink sink;
  EXPECT_FALSE(PlanRaster(*s, CylinderOptions(), sink).has_value());
  ASSERT_FALSE(sink.Diagnostics().empty());
  EXPECT_EQ(sink.Diagnostics().front().code, "plan-raster-footprint");
  EXPECT_EQ(sink.Diagnostics().front().location.line, line);
  EXPECT_GT(line, 0);
  const auto wing = Load("wing_cover.yaml");
  ASSERT_TRUE(wing);
  for (const scene::Constraint& w : wing->constraints) {
    const auto on = scene::ConstraintFootprintOn(w, *wing->surface, 5.0, error);
    const scene::Footprint xy = scene::ConstraintFootprint(w, 5.0);
    ASSERT_TRUE(on.has_value());
    EXPECT_EQ(on->centre, xy.centre);
    EXPECT_EQ(on->axis_x, xy.axis_x);
    EXPECT_EQ(on->half_mm, xy.half_mm);
  }
}

// Off a height field the rows are one row spacing apart on the surface (3D chord at the
// middle of the region), every pass starts and ends outside the footprints, and the pitch is
// a 3D chord along the row.
TEST(RasterOnCadSurface, CylinderRowsSpacedOnTheSurface) {
  const auto s = Load("cylinder_r90_frame.yaml");
  ASSERT_TRUE(s);
  RasterOptions o = CylinderOptions();
  DiagnosticSink sink;
  const std::optional<RasterPlan> plan = PlanRaster(*s, o, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  ASSERT_TRUE(plan.has_value());
  std::vector<double> vs;
  for (const RasterRegion& r : plan->regions) {
    for (const RasterRowPiece& p : r.pieces) {
      if (vs.empty() || p.v_mm > vs.back()) vs.push_back(p.v_mm);
      for (const scene::Footprint& f : plan->footprints) {
        EXPECT_LE(f.Depth({p.u_begin_mm, p.v_mm}), 1e-9) << f.name;
        EXPECT_LE(f.Depth({p.u_end_mm, p.v_mm}), 1e-9) << f.name;
      }
    }
  }
  ASSERT_GT(vs.size(), 10u);
  const geom::Domain2 dom = s->surface->Domain();
  const double u = 0.5 * (dom.min.x() + dom.max.x());
  for (std::size_t k = 0; k + 1 < vs.size(); ++k) {
    const double chord = (s->surface->Point({u, vs[k + 1]}) - s->surface->Point({u, vs[k]})).norm();
    // Rows cut out by a footprint leave gaps of whole spacings.
    const double rows = std::round(chord / o.row_spacing_mm);
    EXPECT_GE(rows, 1.0);
    if (rows == 1.0) {
      EXPECT_NEAR(chord, o.row_spacing_mm, 1e-6) << k;
    }
  }
  // Arc length on the cylinder: a chord of 20 mm spans a little more than 20 mm of v.
  EXPECT_GT(vs[1] - vs[0], o.row_spacing_mm);
  std::ostringstream text;
  const RasterSummary sum = WriteRasterProgram(*plan, *s, program::Dialect::Default(), text);
  const std::vector<Stitch> stitches = Stitches(text.str());
  ASSERT_EQ(static_cast<long>(stitches.size()), sum.stitches);
  int pitches = 0;
  for (std::size_t k = 0; k + 1 < stitches.size(); ++k) {
    const double d = (stitches[k + 1].p - stitches[k].p).norm();
    if (stitches[k + 1].line == stitches[k].line + 1) {
      EXPECT_NEAR(d, o.pitch_mm, 1e-6);
      ++pitches;
    }
  }
  EXPECT_GT(pitches, 100);
}

}  // namespace
}  // namespace stitchsim::planner

namespace stitchsim::planner {
namespace {

// On the cylinder the stringers' boxes stand on the crown's tangent plane: at their place the
// surface lies 2 mm below them, out of reach of the box grown by the rule's 1 mm margin. Judged
// in (u, v), a stitch on the surface under stringer_right fires on its line; the programme
// planned in (u, v) passes.
TEST(RasterOnCadSurface, CrossingRuleOnACylinderUnderAFloatingStringer) {
  const auto s = Load("cylinder_r90_frame.yaml");
  ASSERT_TRUE(s);
  RasterOptions o = CylinderOptions();
  o.region = Eigen::AlignedBox2d(Eigen::Vector2d(-200, 0), Eigen::Vector2d(200, 300));
  const std::string clean = testing::Plan(*s, o);
  const verify::Report r = testing::VerifyText(*s, clean, o.pitch_mm, false);
  const verify::RuleSummary* c = testing::RuleOf(r, "constraint.crossing");
  ASSERT_NE(c, nullptr);
  EXPECT_GT(c->checked, 0);
  EXPECT_EQ(c->errors, 0) << testing::Errors(r);
  const scene::Constraint& stringer = s->constraints.back();
  ASSERT_EQ(stringer.name, "stringer_right");
  const geom::SurfaceProjection under = s->surface->Project(stringer.pose_mm.translation());
  ASSERT_GT(std::abs(under.signed_distance_mm), 0.5 * stringer.size_mm.z() + 1.5);
  const auto [moved, line] = MoveStitch(clean, 5, under.point);
  ExpectCrossingOnLine(testing::VerifyText(*s, moved, o.pitch_mm, false), line, "stringer_right");
}

}  // namespace
}  // namespace stitchsim::planner
