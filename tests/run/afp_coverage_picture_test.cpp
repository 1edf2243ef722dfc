// The per-ply coverage map (run/afp_coverage_picture.h) on a plane (scenes/seq_plate.yaml, ply
// base_0: u = x, v = y): its first course moved 1 mm aside, away from its neighbour, opens a
// seam 1 mm wide. Second route: the seam's v by hand from the programme (the moved course's
// centre line y plus the move, half the head's 16 tows (50.8 mm) across; the neighbour's edge
// the same from its own centre line), turned into a row through the v axis' printed ticks (the
// tick list the picture reports, not its internal mapping): the red seam lies there within 2
// px, and the unmoved ply has no red there. On a map drawn at about 0.5 px a mm the seam (and
// the coverage map's cells of 1.6 mm) is thinner than a pixel: it is drawn enlarged, 3 px
// across, still where the scale puts it.
#include "stitchsim/run/afp_coverage_picture.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <sstream>

#include "run_test_support.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/run/verify_run.h"

namespace stitchsim::run {
namespace {

constexpr double kMoveMm = 1.0;
constexpr double kHalfHeadMm = 8 * 6.35;  // 16 tows of 6.35 mm: a course's half width
constexpr render::Rgb kRed = {220, 30, 30};

// The ply `ply` planned; its course `moved` (0-based) moved `move_mm` in y away from course
// `neighbour` (0: as planned), verified with the laid material kept. The two courses' centre
// line y (programmed, before the move) into `ya`, `yb`.
VerifyRun Verified(const testing::ScratchDir& dir, double move_mm, double& ya, double& yb,
                   const std::string& scene = "seq_plate", const std::string& ply = "base_0",
                   std::size_t moved = 0, std::size_t neighbour = 1) {
  LoadedScene ls = testing::Bundled(scene);
  DiagnosticSink sink;
  auto plan = planner::PlanPly(*ls.scene, *ls.scene->FindPly(ply), {}, sink);
  EXPECT_TRUE(plan && plan->courses.size() >= 2) << testing::AllDiagnostics(sink);
  if (!plan || plan->courses.size() < 2) return {};
  ya = plan->courses[moved].points.front().tool.translation().y();
  yb = plan->courses[neighbour].points.front().tool.translation().y();
  const double dy = ya < yb ? -move_mm : move_mm;  // away from the neighbour
  for (planner::PlyPoint& p : plan->courses[moved].points) p.tool.translation().y() += dy;
  std::ostringstream text;
  planner::WritePlyProgram(*plan, *ls.scene, program::Dialect::Default(), text);
  const std::string program = dir.File(scene + (move_mm != 0 ? "_moved.nc" : "_planned.nc"));
  std::ofstream(program) << text.str();
  VerifyRunOptions o;
  o.program = program;
  o.scene = (testing::SourceDir() / "scenes" / (scene + ".yaml")).string();
  o.keep_stitch_marks = true;
  VerifyRun run = RunVerification(o, std::move(ls), program::Dialect::Default(), nullptr, sink);
  EXPECT_EQ(run.status, RunStatus::kOk) << testing::AllDiagnostics(sink);
  return run;
}

std::vector<CoveragePicture> Pictures(const VerifyRun& run,
                                      const Eigen::Vector2i& map_px = {1000, 900}) {
  render::SnapshotFonts fonts;
  std::string error;
  EXPECT_TRUE(render::OpenSnapshotFonts(1400, fonts, error)) << error;
  if (!fonts.regular) return {};
  return AfpCoveragePictures(*run.verifier, *run.model->loaded.scene, fonts, map_px);
}

// The pixel row of `v_mm` by the v axis' printed ticks (linear between its outermost two).
double RowOf(const CoveragePicture& pic, double v_mm) {
  const AxisTick& a = pic.v_ticks.front();
  const AxisTick& b = pic.v_ticks.back();
  return a.pixel + (v_mm - a.mm) / (b.mm - a.mm) * (b.pixel - a.pixel);
}

bool IsRed(const render::Image& img, int x, int y) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return false;
  const auto k = (static_cast<std::size_t>(y) * img.width + x) * 3;
  return img.rgb[k] == kRed[0] && img.rgb[k + 1] == kRed[1] && img.rgb[k + 2] == kRed[2];
}

// The red rows in column `x` within `reach` px of `row`: first and last (-1: none).
std::pair<int, int> RedRun(const render::Image& img, int x, double row, int reach) {
  int first = -1, last = -1;
  for (int y = static_cast<int>(row) - reach; y <= static_cast<int>(row) + reach; ++y) {
    if (!IsRed(img, x, y)) continue;
    if (first < 0) first = y;
    last = y;
  }
  return {first, last};
}

class AfpCoveragePicture : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    moved_ = new VerifyRun(Verified(*dir_, kMoveMm, ya_, yb_));
    planned_ = new VerifyRun(Verified(*dir_, 0.0, ya_, yb_));
  }
  static void TearDownTestSuite() {
    delete moved_;
    delete planned_;
  }
  // The seam's v by hand: the moved course's facing edge and its neighbour's, halfway.
  static double SeamV() {
    const double side = yb_ > ya_ ? 1.0 : -1.0;
    const double moved_edge = ya_ - side * kMoveMm + side * kHalfHeadMm;
    const double neighbour_edge = yb_ - side * kHalfHeadMm;
    return 0.5 * (moved_edge + neighbour_edge);
  }
  static inline testing::ScratchDir* dir_ = new testing::ScratchDir("afp-coverage-picture");
  static inline VerifyRun* moved_ = nullptr;
  static inline VerifyRun* planned_ = nullptr;
  static inline double ya_ = 0.0, yb_ = 0.0;
};

TEST_F(AfpCoveragePicture, TheSeamIsRedWhereThePrintedScalePutsIt) {
  ASSERT_TRUE(moved_->verifier && planned_->verifier);
  const std::vector<CoveragePicture> moved = Pictures(*moved_);
  const std::vector<CoveragePicture> planned = Pictures(*planned_);
  ASSERT_EQ(moved.size(), 1U);
  ASSERT_EQ(planned.size(), 1U);
  const CoveragePicture& pic = moved.front();
  EXPECT_EQ(pic.name, "base_0");
  ASSERT_GE(pic.u_ticks.size(), 3U);
  ASSERT_GE(pic.v_ticks.size(), 2U);
  const double row = RowOf(pic, SeamV());
  // Three columns: the u axis' inner ticks (courses run along u: the seam crosses each).
  for (std::size_t i = 1; i + 1 < pic.u_ticks.size(); ++i) {
    const int x = pic.u_ticks[i].pixel;
    SCOPED_TRACE("u = " + std::to_string(pic.u_ticks[i].mm));
    const auto [first, last] = RedRun(pic.image, x, row, 20);
    ASSERT_GE(first, 0) << "no red near row " << row;
    EXPECT_NEAR(0.5 * (first + last), row, 2.0);
    EXPECT_EQ(RedRun(planned.front().image, x, RowOf(planned.front(), SeamV()), 20).first, -1);
  }
}

TEST_F(AfpCoveragePicture, ASeamThinnerThanAPixelIsDrawnEnlarged) {
  ASSERT_TRUE(moved_->verifier);
  // A map 500 px wide: about 0.5 px a mm, the coverage map's cells (w / 4 = 1.6 mm) under a
  // pixel too.
  const std::vector<CoveragePicture> moved = Pictures(*moved_, {500, 450});
  ASSERT_EQ(moved.size(), 1U);
  const CoveragePicture& pic = moved.front();
  ASSERT_LT(6.35 / 4 * pic.px_per_mm, 1.0) << "the seam is not thinner than a pixel here";
  const int x = pic.u_ticks[pic.u_ticks.size() / 2].pixel;
  const auto [first, last] = RedRun(pic.image, x, RowOf(pic, SeamV()), 20);
  ASSERT_GE(first, 0);
  EXPECT_GE(last - first + 1, 3);
  EXPECT_LE(last - first + 1, 4);  // enlarged to 3 px, not smeared
  EXPECT_NEAR(0.5 * (first + last), RowOf(pic, SeamV()), 2.0);
}

// The title: the moved ply fails afp.gap (1 mm > 0.76 mm) on its lines, the planned one passes;
// courses and tows laid as the plan has them (its courses; a tow piece a segment the plan
// lays); afp.gap's worst on this ply 1 mm in the moved one (the move, by hand).
TEST_F(AfpCoveragePicture, TheTitleGivesTheVerdictCoursesTowsAndWorstFigures) {
  const std::vector<CoveragePicture> moved = Pictures(*moved_), planned = Pictures(*planned_);
  ASSERT_EQ(moved.size(), 1U);
  ASSERT_EQ(planned.size(), 1U);
  ASSERT_GE(moved.front().title.size(), 3U);
  EXPECT_EQ(moved.front().title[0], "coverage map, ply 1 base_0: FAIL (afp rules on this ply)");
  EXPECT_EQ(planned.front().title[0], "coverage map, ply 1 base_0: PASS (afp rules on this ply)");
  LoadedScene ls = testing::Bundled("seq_plate");
  DiagnosticSink sink;
  const auto plan = planner::PlanPly(*ls.scene, *ls.scene->FindPly("base_0"), {}, sink);
  ASSERT_TRUE(plan);
  EXPECT_EQ(moved.front().title[1], "fibre angle 0 deg · " + std::to_string(plan->courses.size()) +
                                        " courses · " + std::to_string(plan->tow_segments) +
                                        " tows laid · (u, v) in mm, one scale on both");
  std::string figures;
  for (std::size_t i = 3; i < moved.front().title.size(); ++i) figures += moved.front().title[i];
  EXPECT_NE(figures.find("gap 1 mm (this ply)"), std::string::npos) << figures;
}

// The outer laid tow edge of course `course` (the programme's M71 number) nearest `toward`
// (v, mm) at the middle station of its middle strip, v in mm, from the laid material (the
// tows' boundaries the verifier sampled: not what the rules measured).
double CourseEdgeV(const verify::LaidMaterial& laid, int course, double toward) {
  std::vector<std::size_t> strips;
  for (std::size_t i = 0; i < laid.strips.size(); ++i) {
    if (laid.strips[i].course == course) strips.push_back(i);
  }
  EXPECT_FALSE(strips.empty());
  if (strips.empty()) return NAN;
  const verify::LaidStrip& s = laid.strips[strips[strips.size() / 2]];
  const std::size_t st = s.first_station + s.station_count / 2;
  const int left = std::countr_zero(s.tows), right = 64 - std::countl_zero(s.tows);
  const double a = laid.BoundaryUv(st, left).y(), b = laid.BoundaryUv(st, right).y();
  return std::abs(a - toward) < std::abs(b - toward) ? a : b;
}

// scenes/afp_panel.yaml (a dome): the 1 mm seam is narrower than the afp.coverage map's cells
// of 1.6 mm, which miss it (0 % bare); afp.gap measures it and the picture draws it red, on
// the moved course's facing edge as the laid material gives it (rows by the printed ticks),
// reaching into the seam between the two courses' edges.
TEST(AfpCoveragePictureDome, ASeamTheCoverageCellsMissIsRedOnTheMovedCoursesEdge) {
  const testing::ScratchDir dir("afp-coverage-dome");
  double ya = 0, yb = 0;
  // Course 2 moved 1 mm away from course 1 (as tests/run/afp_close_up_test.cpp does).
  const VerifyRun moved = Verified(dir, kMoveMm, ya, yb, "afp_panel", "skin_0", 1, 0);
  const VerifyRun planned = Verified(dir, 0.0, ya, yb, "afp_panel", "skin_0", 1, 0);
  ASSERT_TRUE(moved.verifier && planned.verifier);
  // The coverage map's cells miss the seam: nothing bare (so the red is afp.gap's).
  int coverage = 0;
  for (const verify::RuleSummary& r : moved.report.rules) {
    if (r.id != "afp.coverage") continue;
    ++coverage;
    ASSERT_EQ(r.subjects.front().subject, "skin_0 bare");
    EXPECT_EQ(*r.subjects.front().worst_value, 0.0);
  }
  EXPECT_EQ(coverage, 1);
  const std::vector<CoveragePicture> pics = Pictures(moved), plain = Pictures(planned);
  ASSERT_EQ(pics.size(), 1U);
  ASSERT_EQ(plain.size(), 1U);
  const CoveragePicture& pic = pics.front();
  const verify::LaidMaterial& laid = moved.verifier->Laid();
  ASSERT_FALSE(laid.Empty());
  // Courses 1 and 2 (numbered right to left, course 1 at the lower v): the seam between them.
  const double v2 = CourseEdgeV(laid, 2, -1e9);  // course 2's edge toward course 1 (lower v)
  const double v1 = CourseEdgeV(laid, 1, v2);
  EXPECT_NEAR(std::abs(v2 - v1), kMoveMm, 0.2);  // the seam, 1 mm
  const double r1 = RowOf(pic, v1), r2 = RowOf(pic, v2);
  for (std::size_t i = 1; i + 1 < pic.u_ticks.size(); ++i) {
    SCOPED_TRACE("u = " + std::to_string(pic.u_ticks[i].mm));
    const int x = pic.u_ticks[i].pixel;
    const auto [first, last] = RedRun(pic.image, x, 0.5 * (r1 + r2), 20);
    ASSERT_GE(first, 0);
    // afp.gap samples the moved course's facing edge (course 2's): the red line lies on it,
    // 3 px wide, and reaches into the seam between the edges.
    EXPECT_NEAR(0.5 * (first + last), r2, 2.0);
    EXPECT_GE(last + 1, std::min(r1, r2));
    EXPECT_LE(first, std::max(r1, r2));
    EXPECT_EQ(RedRun(plain.front().image, x, 0.5 * (r1 + r2), 20).first, -1);
  }
}

}  // namespace
}  // namespace stitchsim::run
