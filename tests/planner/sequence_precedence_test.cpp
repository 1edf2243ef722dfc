// Footprints, overlap and the precedence network (planner/sequence/precedence.h), on
// programmes written here and read back (program/afp_program.h). Areas against hand
// computations; the network against the seed's rule and its Figure 3; course-level moves.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/planner/sequence/precedence.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::planner {
namespace {

constexpr double kW = 6.35;  // tow width; 16 tows: 101.6 mm
const process::TowLayout kLayout{16, kW};

std::string PoseWords(const Eigen::Isometry3d& t) {
  const Eigen::Vector3d a =
      geom::EulerFromRotation(program::EulerOrderOf(program::Dialect::Default()), t.linear());
  std::ostringstream s;
  s.precision(10);
  s << "X" << t.translation().x() << " Y" << t.translation().y() << " Z" << t.translation().z()
    << " A" << RadToDeg(a.x()) << " B" << RadToDeg(a.y()) << " C" << RadToDeg(a.z());
  return s.str();
}

// A tool pose on the plane z = 0 travelling along `dir` (tool z up, x = y cross z).
Eigen::Isometry3d OnPlane(double x, double y, const Eigen::Vector2d& dir) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d yy(dir.x(), dir.y(), 0.0), z = Eigen::Vector3d::UnitZ();
  t.linear().col(0) = yy.normalized().cross(z);
  t.linear().col(1) = yy.normalized();
  t.linear().col(2) = z;
  t.translation() = Eigen::Vector3d(x, y, 0);
  return t;
}

// One course through `poses`, every tow of `mask` laying.
std::string Course(int n, const std::vector<Eigen::Isometry3d>& poses,
                   std::uint64_t mask = 0xFFFF) {
  std::ostringstream s;
  Eigen::Isometry3d above = poses.front();
  above.translation() += 100.0 * above.linear().col(2);
  s << "M71 P" << n << "\nG0 " << PoseWords(above) << " M20\nM21\nG1 " << PoseWords(poses.front())
    << " F6000\n";
  for (int t = 1; t <= 16; ++t)
    if ((mask >> (t - 1)) & 1U) s << "M62 P" << t << "\n";
  for (std::size_t i = 1; i < poses.size(); ++i) s << "G1 " << PoseWords(poses[i]) << "\n";
  s << "M63 P0\nM20\nM72\n";
  return s.str();
}

std::string Straight(int n, double x0, double y0, double x1, double y1, int steps = 4) {
  const Eigen::Vector2d d(x1 - x0, y1 - y0);
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    poses.push_back(OnPlane(x0 + t * d.x(), y0 + t * d.y(), d));
  }
  return Course(n, poses);
}

program::AfpProgram Read(const std::string& body) {
  std::istringstream in("%\nG21 G90\nT3 M6\n" + body + "M30\n%\n");
  DiagnosticSink sink;
  auto p = program::ReadAfpProgram(in, program::Dialect::Default(), "t.nc", sink);
  EXPECT_TRUE(p.has_value()) << (sink.Diagnostics().empty() ? "" : sink.Diagnostics()[0].message);
  return p ? std::move(*p) : program::AfpProgram{};
}

TEST(SequencePrecedence, OverlapAreasMatchHandComputations) {
  const auto plane = geom::MakePlane(3000, 3000);
  // Course 1: x 0..200 at y 0, its tows from y = -50.8 to +50.8. Others shifted in y.
  const auto p = Read("M70 P1\n" + Straight(1, 0, 0, 200, 0) + Straight(2, 0, 3.175, 200, 3.175) +
                      Straight(3, 0, 101.6, 200, 101.6) + Straight(4, 0, 110, 200, 110) +
                      Straight(5, 100, 0, 300, 0));
  const auto fp = CourseFootprints(*plane, kLayout, p);
  ASSERT_EQ(fp.size(), 5u);
  EXPECT_NEAR(fp[0].area_mm2, 101.6 * 200, 1e-6);
  EXPECT_NEAR(OverlapAreaMm2(*plane, fp[0], fp[1]), (101.6 - 3.175) * 200, 1e-6);  // half a tow
  EXPECT_NEAR(OverlapAreaMm2(*plane, fp[0], fp[2]), 0.0, 1e-6);                    // edge to edge
  EXPECT_EQ(OverlapAreaMm2(*plane, fp[0], fp[3]), 0.0);                            // a gap
  EXPECT_NEAR(OverlapAreaMm2(*plane, fp[0], fp[4]), 101.6 * 100, 1e-6);            // half along
  EXPECT_NEAR(OverlapAreaMm2(*plane, fp[4], fp[0]), 101.6 * 100, 1e-6);
}

TEST(SequencePrecedence, FootprintAroundACylinderHasItsClosedFormArea) {
  const double r = 300.0;
  const auto cyl = geom::MakeCylinder(r, true, 1200, 900);
  // Around the circumference at x = 0 from -0.5 to 0.5 rad: 300 mm of arc, 16 tows wide.
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i <= 20; ++i) {
    const double a = -0.5 + i / 20.0;
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d n(0, std::sin(a), std::cos(a)), y(0, std::cos(a), -std::sin(a));
    t.linear().col(0) = y.cross(n);
    t.linear().col(1) = y;
    t.linear().col(2) = n;
    t.translation() = Eigen::Vector3d(0, 0, -r) + r * n;
    poses.push_back(t);
  }
  const auto p = Read("M70 P1\n" + Course(1, poses));
  const auto fp = CourseFootprints(*cyl, kLayout, p);
  ASSERT_TRUE(fp[0].ok);
  EXPECT_NEAR(fp[0].area_mm2, 101.6 * r * 1.0, 101.6 * r * 1e-3);
}

std::vector<int> SetOf(const PrecedenceNetwork& n) { return n.set_of_course; }

TEST(SequencePrecedence, TheSeedsPlyRule) {
  const auto plane = geom::MakePlane(3000, 3000);
  // Base ply of three courses (y 0, 101.6, 203.2), three pad-ups on it apart from each other.
  const std::string base = "M70 P1\n" + Straight(1, 0, 0, 600, 0) +
                           Straight(2, 0, 101.6, 600, 101.6) + Straight(3, 0, 203.2, 600, 203.2);
  const auto p =
      Read(base + "M70 P2\n" + Straight(1, 0, 101.6, 100, 101.6) + "M70 P3\n" +
           Straight(1, 250, 101.6, 350, 101.6) + "M70 P4\n" + Straight(1, 500, 101.6, 600, 101.6));
  const auto fp = CourseFootprints(*plane, kLayout, p);
  const auto net = BuildPrecedence(*plane, p, fp, {});
  ASSERT_EQ(net.sets.size(), 2u);
  EXPECT_EQ(net.sets[0].plies, (std::vector<int>{0}));
  EXPECT_EQ(net.sets[1].plies, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(SetOf(net), (std::vector<int>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(net.blocker_of_course[3], 1);  // the pad-up sits on the base's middle course
  // Figure 3: plies 1 and 2 apart, 3 on 1, 4 on 3: L1 {1, 2}, L2 {3}, L3 {4}.
  const auto q =
      Read("M70 P1\n" + Straight(1, 0, 0, 300, 0) + "M70 P2\n" + Straight(1, 1000, 0, 1300, 0) +
           "M70 P3\n" + Straight(1, 100, 0, 200, 0) + "M70 P4\n" + Straight(1, 150, 20, 250, 20));
  const auto fq = CourseFootprints(*plane, kLayout, q);
  const auto nq = BuildPrecedence(*plane, q, fq, {});
  ASSERT_EQ(nq.sets.size(), 3u);
  EXPECT_EQ(SetOf(nq), (std::vector<int>{0, 0, 1, 2}));
}

TEST(SequencePrecedence, CourseLevelMovesOnlyWhatNothingBlocks) {
  const auto plane = geom::MakePlane(3000, 3000);
  // Ply 1 at y 0; ply 2 on it; ply 3: one course on ply 2, one far away.
  const auto p =
      Read("M70 P1\n" + Straight(1, 0, 0, 300, 0) + "M70 P2\n" + Straight(1, 0, 0, 300, 0) +
           "M70 P3\n" + Straight(1, 0, 0, 300, 0) + Straight(2, 0, 500, 300, 500));
  const auto fp = CourseFootprints(*plane, kLayout, p);
  const auto off = BuildPrecedence(*plane, p, fp, {});
  EXPECT_EQ(SetOf(off), (std::vector<int>{0, 1, 2, 2}));
  PrecedenceOptions o;
  o.course_level = true;
  const auto on = BuildPrecedence(*plane, p, fp, o);
  EXPECT_EQ(SetOf(on), (std::vector<int>{0, 1, 2, 0}));  // the far course joins the first set
  ASSERT_EQ(on.sets.size(), 3u);
  EXPECT_EQ(on.sets[0].courses, (std::vector<int>{0, 3}));
}

TEST(SequencePrecedence, AnOrderLayingACourseBeforeWhatItCoversIsRefused) {
  const auto plane = geom::MakePlane(3000, 3000);
  const auto p = Read("M70 P1\n" + Straight(1, 0, 0, 300, 0) + Straight(2, 0, 300, 300, 300) +
                      "M70 P2\n" + Straight(1, 0, 300, 100, 300));
  const auto fp = CourseFootprints(*plane, kLayout, p);
  using V = program::CourseVisit;
  EXPECT_TRUE(RespectsPrecedence(*plane, p, fp, {V{0}, V{1}, V{2}}, 1.0));
  EXPECT_TRUE(RespectsPrecedence(*plane, p, fp, {V{1, true}, V{0}, V{2}}, 1.0));
  EXPECT_TRUE(RespectsPrecedence(*plane, p, fp, {V{1}, V{2}, V{0}}, 1.0));  // 2 is not under 0
  int at = -1;
  EXPECT_FALSE(RespectsPrecedence(*plane, p, fp, {V{0}, V{2}, V{1}}, 1.0, &at));
  EXPECT_EQ(at, 2);  // laying course 1 of ply 1 after the pad-up on it
}

}  // namespace
}  // namespace stitchsim::planner
