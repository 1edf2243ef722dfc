// The AFP close-ups (family kAfp): scenes/afp_panel.yaml's ply skin_0 planned, its second course
// moved 1 mm aside (+y) in the programme text, verified: afp.gap and afp.overlap find the seam
// 1 mm wide on that course's edges. Their close-ups frame the worst finding from above: the
// subject (the seam's edge points, drawn at least 0.8 mm wide, lifted off the surface) covers
// a set share of the picture and nothing hides it (the part need not be made see-through).
// Second route: the finding's place lies on the moved course's edge, half the head's 16 tows
// (50.8 mm) across from that course's programmed centre line, 1 mm beyond where it was planned.
#include <gtest/gtest.h>

#include "afp_close_up_support.h"

namespace stitchsim::run {
namespace {

using testing::RuleOf;

constexpr int kMovedCourse = 2;
constexpr double kMoveMm = 1.0;
constexpr double kHalfHeadMm = 8 * 6.35;  // 16 tows of 6.35 mm: the course's half width

struct MovedRun {
  std::unique_ptr<VerifyRun> run;
  double course_y = 0.0;    ///< the moved course's programmed y before the move, mm
  int first = 0, last = 0;  ///< its first and last G1 line (1-based)
};

class AfpCloseUp : public ::testing::Test {
 protected:
  // skin_0 with its course 2 moved kMoveMm aside (+y): each G1 line's Y.
  static void SetUpTestSuite() {
    const std::string text = testing::PanelSkin0Text();
    ASSERT_FALSE(text.empty());
    moved_ = new MovedRun;
    const std::string edited =
        testing::EditCourse(text, kMovedCourse, [](int number, Eigen::Vector3d& xyz) {
          moved_->course_y = xyz.y();
          if (moved_->first == 0) moved_->first = number;
          moved_->last = number;
          xyz.y() += kMoveMm;
          return std::string();
        });
    moved_->run = testing::VerifyPanelText(edited, *dir_, "moved.nc");
    ASSERT_TRUE(moved_->run);
  }
  static void TearDownTestSuite() {
    delete moved_;
    moved_ = nullptr;
  }

  static const verify::Rule* Rule(const std::string& id) { return RuleOf(*moved_->run, id); }

  static inline MovedRun* moved_ = nullptr;
  static inline testing::ScratchDir* dir_ = new testing::ScratchDir("afp-close-up");
};

// Where the finding lies (y, part frame, mm) against the moved course's planned centre line:
// the courses run along x, course 1 at -y, course 3 at +y; course 2 moved +1 mm opens a gap
// at its own -y edge (moved) and overlaps course 3, whose -y edge is found where course 2's
// edge was planned. The edge lies about half the head (50.8 mm; the surface's arc) across.
double EdgeOffset(const verify::Finding& f, const MovedRun& m, bool gap) {
  return (*f.position_mm)[1] - (m.course_y + (gap ? kMoveMm : 0.0));
}

TEST_F(AfpCloseUp, GapAndOverlapOfACourseMovedAside) {
  for (const char* id : {"afp.gap", "afp.overlap"}) {
    SCOPED_TRACE(id);
    const verify::Rule* rule = Rule(id);
    ASSERT_NE(rule, nullptr);
    ASSERT_GT(rule->Summary().errors, 0);
    const verify::Finding* f = FocusFinding(*rule);
    ASSERT_NE(f, nullptr);
    EXPECT_NEAR(f->value, kMoveMm, 0.15);
    ASSERT_TRUE(f->position_mm.has_value());
    const bool gap = std::string(id) == "afp.gap";
    EXPECT_NEAR(EdgeOffset(*f, *moved_, gap), gap ? -kHalfHeadMm : kHalfHeadMm, 0.3) << f->message;
    // The gap is found laying the moved course (its lines), the overlap laying course 3.
    if (gap) {
      EXPECT_GE(f->line, moved_->first);
      EXPECT_LE(f->line, moved_->last);
    } else {
      EXPECT_GT(f->line, moved_->last);
    }
  }
}

// A 1 mm seam (drawn 1 mm wide) over a 50 mm frame: a few pixels wide, the frame's length:
// at least 0.5 % of the picture.
TEST_F(AfpCloseUp, TheSeamIsSeenFromAboveAndNotHidden) {
  for (const char* id : {"afp.gap", "afp.overlap"}) {
    testing::ExpectSubjectSeen(*moved_->run, id, 320L * 240L / 200);
  }
}

}  // namespace
}  // namespace stitchsim::run
