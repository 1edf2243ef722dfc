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

// The ply base_0 planned; its first course moved `dy` mm in y (0: as planned), verified with
// the laid material kept. The two first courses' centre line y (programmed) into `ya`, `yb`.
VerifyRun Verified(const testing::ScratchDir& dir, double move_mm, double& ya, double& yb) {
  LoadedScene ls = testing::Bundled("seq_plate");
  DiagnosticSink sink;
  auto plan = planner::PlanPly(*ls.scene, *ls.scene->FindPly("base_0"), {}, sink);
  EXPECT_TRUE(plan && plan->courses.size() >= 2) << testing::AllDiagnostics(sink);
  if (!plan || plan->courses.size() < 2) return {};
  ya = plan->courses[0].points.front().tool.translation().y();
  yb = plan->courses[1].points.front().tool.translation().y();
  const double dy = ya < yb ? -move_mm : move_mm;  // away from the neighbour
  for (planner::PlyPoint& p : plan->courses[0].points) p.tool.translation().y() += dy;
  std::ostringstream text;
  planner::WritePlyProgram(*plan, *ls.scene, program::Dialect::Default(), text);
  const std::string program = dir.File(move_mm != 0 ? "moved.nc" : "planned.nc");
  std::ofstream(program) << text.str();
  VerifyRunOptions o;
  o.program = program;
  o.scene = (testing::SourceDir() / "scenes" / "seq_plate.yaml").string();
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

}  // namespace
}  // namespace stitchsim::run
