// The AFP close-ups (family kAfp): scenes/afp_panel.yaml's ply skin_0 planned, its second course
// moved 1 mm aside (+y) in the programme text, verified: afp.gap and afp.overlap find the seam
// 1 mm wide on that course's edges. Their close-ups frame the worst finding from above: the
// subject (the seam's edge points, drawn at least 0.8 mm wide, lifted off the surface) covers
// a set share of the picture and nothing hides it (the part need not be made see-through).
// Second route: the finding's place lies on the moved course's edge, half the head's 16 tows
// (50.8 mm) across from that course's programmed centre line, 1 mm beyond where it was planned.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "run_test_support.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/render/scene_model.h"
#include "stitchsim/run/close_up.h"
#include "stitchsim/run/verify_run.h"

namespace stitchsim::run {
namespace {

constexpr int kMovedCourse = 2;
constexpr double kMoveMm = 1.0;
constexpr double kHalfHeadMm = 8 * 6.35;  // 16 tows of 6.35 mm: the course's half width

// The programme's Y on each line of course `course` (its M71 P<course> up to the next M71 or
// M72) plus `dy`; the course's centre line y (programmed, before the move) into `course_y`,
// and the first and last line of the course into `first` / `last` (1-based).
std::string MoveCourse(const std::string& text, int course, double dy, double& course_y, int& first,
                       int& last) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string l;
  bool inside = false;
  int number = 0;
  course_y = 0.0;
  while (std::getline(in, l)) {
    ++number;
    if (l.rfind("M71 P", 0) == 0) {
      inside = std::stoi(l.substr(5)) == course;
      if (inside) first = number;
    } else if (l.rfind("M72", 0) == 0) {
      inside = false;
    }
    const std::size_t y = l.find(" Y");
    if (inside && y != std::string::npos && l.rfind("G1", 0) == 0) {
      const std::size_t end = l.find(' ', y + 2);
      course_y = std::stod(l.substr(y + 2, end - y - 2));
      l = l.substr(0, y + 2) + std::to_string(course_y + dy) + l.substr(end);
      last = number;
    }
    out << l << "\n";
  }
  return out.str();
}

struct MovedRun {
  VerifyRun run;
  double course_y = 0.0;  ///< the moved course's programmed y before the move, mm
  int first = 0, last = 0;
};

struct PanelModel {
  render::MjModelPtr model;
  render::MjDataPtr data;
};

class AfpCloseUp : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    LoadedScene ls = testing::Bundled("afp_panel");
    ASSERT_TRUE(ls.scene);
    DiagnosticSink sink;
    const auto plan = planner::PlanPly(*ls.scene, *ls.scene->FindPly("skin_0"), {}, sink);
    ASSERT_TRUE(plan) << testing::AllDiagnostics(sink);
    ASSERT_GE(plan->courses.size(), 3U);
    std::ostringstream text;
    planner::WritePlyProgram(*plan, *ls.scene, program::Dialect::Default(), text);
    moved_ = new MovedRun;
    const std::string program = dir_->File("moved.nc");
    std::ofstream(program) << MoveCourse(text.str(), kMovedCourse, kMoveMm, moved_->course_y,
                                         moved_->first, moved_->last);
    VerifyRunOptions o;
    o.program = program;
    o.scene = (testing::SourceDir() / "scenes" / "afp_panel.yaml").string();
    o.keep_stitch_marks = true;
    moved_->run = RunVerification(o, std::move(ls), program::Dialect::Default(), nullptr, sink);
    ASSERT_EQ(moved_->run.status, RunStatus::kOk) << testing::AllDiagnostics(sink);
  }
  static void TearDownTestSuite() {
    delete moved_;
    moved_ = nullptr;
  }

  static const verify::Rule* Rule(const std::string& id) {
    for (const auto& r : moved_->run.verifier->Rules()) {
      if (r->Summary().id == id) return r.get();
    }
    return nullptr;
  }

  // The close-up of `id` planned and shot at 320 x 240.
  static void Shoot(const std::string& id, CloseUpPlan& plan, Shot& shot) {
    const verify::Rule* rule = Rule(id);
    ASSERT_NE(rule, nullptr);
    ASSERT_GT(rule->Summary().errors, 0) << id;
    DiagnosticSink sink;
    const LoadedScene& ls = moved_->run.model->loaded;
    PanelModel m;
    m.model = render::LoadSceneModel(*ls.scene, sink);
    ASSERT_TRUE(m.model);
    m.model->vis.map.znear = std::min<float>(m.model->vis.map.znear, 0.01 / m.model->stat.extent);
    m.data.reset(mj_makeData(m.model.get()));
    const verify::Verifier& v = *moved_->run.verifier;
    const CloseUpContext ctx{&ls,
                             moved_->run.model->process.get(),
                             &moved_->run.model->description,
                             m.model.get(),
                             m.data.get(),
                             &v.StitchMarks(),
                             &v};
    std::optional<CloseUpPlan> planned;
    std::string error;
    ASSERT_TRUE(PlanCloseUp(ctx, *rule, planned, error)) << error;
    ASSERT_TRUE(planned.has_value()) << id;
    plan = *planned;
    ASSERT_TRUE(ShootCloseUp(m.model.get(), m.data.get(), plan, 320, 240, shot, error)) << error;
  }

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

TEST_F(AfpCloseUp, TheSeamIsSeenFromAboveAndNotHidden) {
  for (const char* id : {"afp.gap", "afp.overlap"}) {
    SCOPED_TRACE(id);
    CloseUpPlan plan;
    Shot shot;
    Shoot(id, plan, shot);
    if (HasFatalFailure()) return;
    EXPECT_EQ(plan.family, verify::CloseUpFamily::kAfp);
    ASSERT_EQ(shot.pixels.size(), 1U);
    const SubjectPixels& s = shot.pixels.front();
    const long picture = 320L * 240L;
    // A 1 mm seam (drawn 1 mm wide) over a 50 mm frame: a few pixels wide, the frame's length.
    EXPECT_GE(s.visible, picture / 200) << s.visible;  // at least 0.5 % of the picture
    EXPECT_EQ(s.hidden, 0);
    EXPECT_GE(s.visible, s.alone * 9 / 10);
    // Lifted above the surface: nothing had to be made see-through to show it.
    EXPECT_TRUE(shot.see_through.empty()) << shot.see_through.front();
    ASSERT_FALSE(plan.legend.empty());
    EXPECT_NE(plan.legend.front().label.find("limit"), std::string::npos);
  }
}

}  // namespace
}  // namespace stitchsim::run
