// The close-ups of afp.steering_radius, afp.compaction, afp.min_tow_length and
// afp.restart_distance (family kAfp) on scenes/afp_panel.yaml's ply skin_0, one programme with
// three planted faults of known size, one per course:
// - course 2 (y = 0) bent aside in y by a bump of three circular arcs of radius kBendMm (the
//   middle one over |x - xc| <= kArcMm, the outer two bending back): every tow's centre line
//   steers on kBendMm where the rule's 50 mm window lies on the middle arc;
// - course 1 lifted kLiftMm in z over kLiftFromX .. kLiftToX: the roller stands kLiftMm (along
//   the normal, the dome's slope aside) over the surface;
// - course 3 (tows 12-16) cuts tow kCutTow after the line nearest kCutX and adds it again after
//   the line nearest kReAddX: a short piece from its add to the cut, a restart from the cut to
//   the re-add, both shorter than the head's 100 mm.
// Second routes: the radius and the lift from the closed forms above; the piece and the restart
// as the tool path's length between the programme points that add, cut and re-add the tow;
// every finding's position against the programme points where the fault was planted. Each
// close-up's subject covers a set share of the picture and nothing hides it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

#include "afp_close_up_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::run {
namespace {

using testing::DrawnBy;
using testing::RuleOf;

constexpr double kBendMm = 400.0;    // the bump's arcs' radius
constexpr double kArcMm = 50.0;      // the middle arc's half length in x
constexpr double kLiftMm = 1.5;      // course 1 raised this much in z ...
constexpr double kLiftFromX = 30.0;  // ... on its lines ending in this x range
constexpr double kLiftToX = 60.0;
constexpr int kCutTow = 14;
constexpr double kCutX = -100.0;
constexpr double kReAddX = -60.0;
constexpr double kTowMm = 6.35;

// The bump's y at u = x - xc: the middle arc (top), then the outer arcs back to 0 at 2 kArcMm.
double Bump(double u) {
  const double a = std::abs(u);
  const double rise = kBendMm - std::sqrt(kBendMm * kBendMm - kArcMm * kArcMm);
  if (a <= kArcMm) return 2.0 * rise - (kBendMm - std::sqrt(kBendMm * kBendMm - a * a));
  if (a <= 2.0 * kArcMm) {
    const double b = 2.0 * kArcMm - a;
    return kBendMm - std::sqrt(kBendMm * kBendMm - b * b);
  }
  return 0.0;
}

// The tool points of a course in programme order, by line number (1-based).
using CoursePoints = std::map<int, Eigen::Vector3d>;

CoursePoints PointsOf(const std::string& text, int course) {
  CoursePoints points;
  testing::EditCourse(text, course, [&](int number, Eigen::Vector3d& xyz) {
    points[number] = xyz;
    return std::string();
  });
  return points;
}

// The line of `points` whose x is nearest `x`.
int NearestLine(const CoursePoints& points, double x) {
  int best = 0;
  for (const auto& [n, p] : points) {
    if (best == 0 || std::abs(p.x() - x) < std::abs(points.at(best).x() - x)) best = n;
  }
  return best;
}

// The tool path's length over `points` from line `from` to line `to` (their end points).
double PathLength(const CoursePoints& points, int from, int to) {
  double length = 0.0;
  for (auto it = points.find(from); it != points.end() && it->first < to; ++it) {
    length += (std::next(it)->second - it->second).norm();
  }
  return length;
}

struct Planted {
  std::unique_ptr<VerifyRun> run;
  double xc = 0.0;                                  // the bump's centre x
  double course1_y = 0.0;                           // course 1's programmed y
  int add_line = 0, cut_line = 0, re_add_line = 0;  // course 3: tow kCutTow's G1 lines
  CoursePoints course2, course3;                    // as verified
};

// The G1 line before the M62 P<tow> in course 3 of `text` (the point the tow is added at).
int AddLine(const std::string& text, int tow) {
  std::istringstream in(text);
  std::string l;
  int number = 0, last_g1 = 0, course = 0;
  while (std::getline(in, l)) {
    ++number;
    if (l.rfind("M71 P", 0) == 0) course = std::stoi(l.substr(5));
    if (l.rfind("G1 ", 0) == 0) last_g1 = number;
    if (course == 3 && l == "M62 P" + std::to_string(tow)) return last_g1;
  }
  return 0;
}

class AfpRuleCloseUps : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string text = testing::PanelSkin0Text();
    ASSERT_FALSE(text.empty());
    p_ = new Planted;
    const CoursePoints c2 = PointsOf(text, 2);
    p_->xc = c2.at(NearestLine(c2, 0.0)).x();
    std::string edited = testing::EditCourse(text, 2, [](int, Eigen::Vector3d& xyz) {
      xyz.y() += Bump(xyz.x() - p_->xc);
      return std::string();
    });
    edited = testing::EditCourse(edited, 1, [](int, Eigen::Vector3d& xyz) {
      p_->course1_y = xyz.y();
      if (xyz.x() >= kLiftFromX && xyz.x() <= kLiftToX) xyz.z() += kLiftMm;
      return std::string();
    });
    p_->course2 = PointsOf(edited, 2);
    const CoursePoints c3 = PointsOf(edited, 3);
    const int cut = NearestLine(c3, kCutX), re_add = NearestLine(c3, kReAddX);
    edited = testing::EditCourse(edited, 3, [&](int number, Eigen::Vector3d&) {
      const std::string tow = std::to_string(kCutTow);
      return number == cut ? "M63 P" + tow + "\n" : number == re_add ? "M62 P" + tow + "\n" : "";
    });
    // Line numbers after the two inserted lines: read them again.
    p_->course3 = PointsOf(edited, 3);
    p_->add_line = AddLine(edited, kCutTow);
    p_->cut_line = NearestLine(p_->course3, kCutX);
    p_->re_add_line = NearestLine(p_->course3, kReAddX);
    p_->run = testing::VerifyPanelText(edited, *dir_, "planted.nc");
    ASSERT_TRUE(p_->run);
  }
  static void TearDownTestSuite() {
    delete p_;
    p_ = nullptr;
  }

  // The rule's focus finding (a test failure when it has none or no position).
  static const verify::Finding* Focus(const std::string& id) {
    const verify::Rule* rule = RuleOf(*p_->run, id);
    EXPECT_NE(rule, nullptr) << id;
    if (rule == nullptr) return nullptr;
    EXPECT_GT(rule->Summary().errors, 0) << id;
    const verify::Finding* f = FocusFinding(*rule);
    EXPECT_TRUE(f != nullptr && f->position_mm) << id;
    return f != nullptr && f->position_mm ? f : nullptr;
  }

  static Eigen::Vector3d At(const verify::Finding& f) {
    return {(*f.position_mm)[0], (*f.position_mm)[1], (*f.position_mm)[2]};
  }

  static inline Planted* p_ = nullptr;
  static inline testing::ScratchDir* dir_ = new testing::ScratchDir("afp-rule-close-ups");
};

TEST_F(AfpRuleCloseUps, TheSteeredTowTurnsOnTheBumpsRadiusWhereItWasBent) {
  const verify::Finding* f = Focus("afp.steering_radius");
  ASSERT_NE(f, nullptr);
  EXPECT_NEAR(f->value, kBendMm, 0.015 * kBendMm) << f->message;
  // On the middle arc (its window too: within kArcMm - 25 mm of xc), on the tow's centre line:
  // the bent tool path moved across by the tow's offset from the head's centre.
  const Eigen::Vector3d at = At(*f);
  const double u = at.x() - p_->xc;
  EXPECT_LE(std::abs(u), kArcMm - 20.0) << at.transpose();
  const int tow = std::stoi(f->subject.substr(4));
  EXPECT_NEAR(std::abs(at.y() - Bump(u)), std::abs(tow - 8.5) * kTowMm, 0.5) << f->subject;
  // The drawn window: three tow centres, the middle one the finding's, ~25 mm either side.
  const auto w = DrawnBy(*p_->run, "afp.steering_radius", "close_up:afp_steering");
  ASSERT_EQ(w.size(), 3U);
  EXPECT_LT((w[1] - at).norm(), 1e-9);
  EXPECT_NEAR((w[0] - w[1]).norm(), 27.5, 2.6);
  EXPECT_NEAR((w[2] - w[1]).norm(), 27.5, 2.6);
}

// The bent course's tows turn off the ply's 0 deg (x) most on the programme's steepest chord,
// where the middle arc meets an outer one (|x - xc| = kArcMm: at most asin(kArcMm / kBendMm),
// 7.2 deg).
TEST_F(AfpRuleCloseUps, TheBentCourseIsFoundOffItsFibreDirectionOnItsSteepestChord) {
  const verify::Finding* f = Focus("afp.fiber_angle");
  ASSERT_NE(f, nullptr);
  double steepest = 0.0;  // the programme's chords of course 2, in x-y (the dome's slope aside)
  for (auto it = p_->course2.begin(); std::next(it) != p_->course2.end(); ++it) {
    const Eigen::Vector3d d = std::next(it)->second - it->second;
    if (std::abs(d.x()) > 1.0) steepest = std::max(steepest, std::atan(std::abs(d.y() / d.x())));
  }
  // The executor moves straight between programme points 5 mm apart: the steepest chord turns
  // less than the arcs' tangent there by up to half a chord's turn, 2.5 / kBendMm rad.
  EXPECT_LE(steepest, std::asin(kArcMm / kBendMm));
  EXPECT_GE(steepest, std::asin(kArcMm / kBendMm) - 2.6 / kBendMm);
  EXPECT_NEAR(f->value, steepest * kRadToDeg, 0.15) << f->message;
  const Eigen::Vector3d at = At(*f);
  EXPECT_NEAR(std::abs(at.x() - p_->xc), kArcMm, 5.0) << at.transpose();
  const int tow = std::stoi(f->subject.substr(4));
  EXPECT_NEAR(std::abs(at.y() - Bump(at.x() - p_->xc)), std::abs(tow - 8.5) * kTowMm, 0.5);
  // The drawing: the point, then the laid and the design directions' tips 10 mm from it, as
  // far apart as the angle.
  const auto d = DrawnBy(*p_->run, "afp.fiber_angle", "close_up:afp_fiber");
  ASSERT_EQ(d.size(), 3U);
  EXPECT_LT((d[0] - at).norm(), 1e-9);
  EXPECT_NEAR(std::acos((d[1] - d[0]).normalized().dot((d[2] - d[0]).normalized())) * kRadToDeg,
              f->value, 1e-6);
}

TEST_F(AfpRuleCloseUps, TheRollerIsFoundLiftedWhereCourse1WasRaised) {
  const verify::Finding* f = Focus("afp.compaction");
  ASSERT_NE(f, nullptr);
  const Eigen::Vector3d at = At(*f);
  EXPECT_GE(at.x(), kLiftFromX - 5.1) << at.transpose();
  EXPECT_LE(at.x(), kLiftToX + 5.1) << at.transpose();
  EXPECT_NEAR(at.y(), p_->course1_y, 1.0);
  // The lift: kLiftMm in z is kLiftMm along the normal within the dome's slope (a few deg).
  const verify::Rule* rule = RuleOf(*p_->run, "afp.compaction");
  const auto& lift = rule->Summary().subjects.front();
  ASSERT_EQ(lift.subject, "lift");
  ASSERT_TRUE(lift.worst_value);
  EXPECT_NEAR(*lift.worst_value, kLiftMm / 0.25 * 100.0, 0.01 * kLiftMm / 0.25 * 100.0);
  // The drawn roller: over each of the 17 tow boundaries kLiftMm above its foot, the head's
  // width (101.6 mm) across.
  const auto r = DrawnBy(*p_->run, "afp.compaction", "close_up:afp_roller");
  ASSERT_EQ(r.size(), 34U);
  for (std::size_t j = 0; j < 17; ++j) EXPECT_NEAR((r[j] - r[j + 17]).norm(), kLiftMm, 0.05) << j;
  EXPECT_NEAR((r[33] - r[17]).norm(), 16 * kTowMm, 0.5);
}

TEST_F(AfpRuleCloseUps, TheShortPieceAndTheRestartAreFoundWhereTheTowWasCutAndAdded) {
  const verify::Finding* piece = Focus("afp.min_tow_length");
  const verify::Finding* restart = Focus("afp.restart_distance");
  ASSERT_TRUE(piece != nullptr && restart != nullptr);
  ASSERT_GT(p_->add_line, 0);
  const CoursePoints& c3 = p_->course3;
  const double piece_mm = PathLength(c3, p_->add_line, p_->cut_line);
  const double restart_mm = PathLength(c3, p_->cut_line, p_->re_add_line);
  EXPECT_NEAR(piece->value, piece_mm, 0.01 * piece_mm) << piece->message;
  EXPECT_NEAR(restart->value, restart_mm, 0.01 * restart_mm) << restart->message;
  EXPECT_EQ(piece->subject, "tow " + std::to_string(kCutTow));
  EXPECT_EQ(restart->subject, "tow " + std::to_string(kCutTow));
  // The piece's position: where the tow was added; the restart's: where it is added again;
  // each on the tow's centre line, (14 - 8.5) tows across from the tool point.
  const Eigen::Vector3d a = At(*piece), b = At(*restart);
  const Eigen::Vector3d add = c3.at(p_->add_line), re_add = c3.at(p_->re_add_line);
  EXPECT_NEAR(a.x(), add.x(), 0.5) << a.transpose();
  EXPECT_NEAR(b.x(), re_add.x(), 0.5) << b.transpose();
  EXPECT_NEAR(std::abs(a.y() - add.y()), (kCutTow - 8.5) * kTowMm, 0.5);
  EXPECT_NEAR(std::abs(b.y() - re_add.y()), (kCutTow - 8.5) * kTowMm, 0.5);
}

// Each subject at least 1 % of the 320 x 240 picture, none of it hidden (one test each: each
// shot tries several directions).
constexpr long kOnePercent = 320L * 240L / 100;

TEST_F(AfpRuleCloseUps, TheSteeredTowIsSeenAndNotHidden) {
  testing::ExpectSubjectSeen(*p_->run, "afp.steering_radius", kOnePercent);
}

TEST_F(AfpRuleCloseUps, TheRollerIsSeenAndNotHidden) {
  testing::ExpectSubjectSeen(*p_->run, "afp.compaction", kOnePercent);
}

TEST_F(AfpRuleCloseUps, TheFibreDirectionsAreSeenAndNotHidden) {
  testing::ExpectSubjectSeen(*p_->run, "afp.fiber_angle", kOnePercent);
}

TEST_F(AfpRuleCloseUps, TheShortPieceIsSeenAndNotHidden) {
  testing::ExpectSubjectSeen(*p_->run, "afp.min_tow_length", kOnePercent);
}

TEST_F(AfpRuleCloseUps, TheRestartIsSeenAndNotHidden) {
  testing::ExpectSubjectSeen(*p_->run, "afp.restart_distance", kOnePercent);
}

// afp.stagger: afp_panel with a laminate of skin_0 and an inline 0 deg ply on it (ply 3, the
// same boundary), stagger offset 10 mm over one ply; the programme lays skin_0, then again as
// ply 3 with every course kStaggerMm aside (+y): each seam of ply 3 lies kStaggerMm from
// skin_0's. Second route: the seams from the programme's course centre lines (midway between
// courses 1 and 2; course 2's edge half a head from its centre line), moved kStaggerMm.
constexpr double kStaggerMm = 2.0;

class AfpStaggerCloseUp : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string text = testing::PanelSkin0Text();
    ASSERT_FALSE(text.empty());
    std::ifstream in(testing::SourceDir() / "scenes" / "afp_panel.yaml");
    std::stringstream scene;
    scene
        << in.rdbuf()
        << "laminates:\n  - name: skin\n    rosette: {origin: [0, 0, 100], direction: [1, 0, 0]}\n"
           "    stagger: {offset: 10, plies_before_repeat: 1}\n    stack:\n      - skin_0\n"
           "      - {angle_deg: 0, boundary_uv: [[130, 120], [475, 120], [475, 285], [130, "
           "285]]}\n";
    const std::string scene_file = dir_->File("afp_panel_laminate.yaml");
    std::ofstream(scene_file) << scene.str();
    // Ply 3 (the inline ply): skin_0's courses moved kStaggerMm aside, after skin_0's M72.
    std::string upper = text.substr(text.find("M70 P1"));
    upper.replace(0, 6, "M70 P3");
    for (int c = 1; c <= 3; ++c) {
      upper = testing::EditCourse(upper, c, [](int, Eigen::Vector3d& xyz) {
        xyz.y() += kStaggerMm;
        return std::string();
      });
    }
    const CoursePoints c1 = PointsOf(text, 1), c2 = PointsOf(text, 2);
    seams_ = {0.5 * (c1.begin()->second.y() + c2.begin()->second.y()) + kStaggerMm,
              c2.begin()->second.y() + 8 * kTowMm + kStaggerMm};
    run_ = testing::VerifyPanelText(text.substr(0, text.rfind("M30")) + upper, *dir_, "laminate.nc",
                                    scene_file)
               .release();
    ASSERT_NE(run_, nullptr);
  }
  static void TearDownTestSuite() {
    delete run_;
    run_ = nullptr;
  }

  static inline VerifyRun* run_ = nullptr;
  static inline std::array<double, 2> seams_{};  // ply 3's seams' y, mm
  static inline testing::ScratchDir* dir_ = new testing::ScratchDir("afp-stagger-close-up");
};

TEST_F(AfpStaggerCloseUp, TheUpperSeamIsFoundItsOffsetFromTheLowerOne) {
  const verify::Rule* rule = RuleOf(*run_, "afp.stagger");
  ASSERT_NE(rule, nullptr);
  ASSERT_GT(rule->Summary().errors, 0);
  const verify::Finding* f = FocusFinding(*rule);
  ASSERT_TRUE(f != nullptr && f->position_mm);
  EXPECT_EQ(f->subject, "ply 3");
  EXPECT_NEAR(f->value, kStaggerMm, 0.05) << f->message;
  const double y = (*f->position_mm)[1];
  EXPECT_LT(std::min(std::abs(y - seams_[0]), std::abs(y - seams_[1])), 0.3) << y;
  // The drawing: the seam point, then the lower seam's nearest point, the value apart.
  const auto d = DrawnBy(*run_, "afp.stagger", "close_up:afp_stagger");
  ASSERT_EQ(d.size(), 2U);
  EXPECT_NEAR((d[1] - d[0]).norm(), f->value, 1e-9);
  EXPECT_LT((d[0] - Eigen::Vector3d((*f->position_mm)[0], y, (*f->position_mm)[2])).norm(), 1e-9);
}

// Two dots and the 2 mm between them in a frame 20 mm across: at least 0.5 % of the picture.
TEST_F(AfpStaggerCloseUp, TheTwoSeamsAreSeenAndNotHidden) {
  testing::ExpectSubjectSeen(*run_, "afp.stagger", kOnePercent / 2);
}

}  // namespace
}  // namespace stitchsim::run
