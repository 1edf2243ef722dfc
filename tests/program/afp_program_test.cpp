// An AFP programme read back by course and written again (program/afp_program.h): the
// approach / lay-up / retract split and lay-up stations of a hand-written programme, every
// sequence-* diagnostic at its line, reversal (masks mirrored, poses turned, twice = once),
// a round trip that copies lay-ups byte for byte, and, on a planned ply, that a reversed
// course lays the same tow boundaries on the surface as the forward one (process::TowsAt).
#include "stitchsim/program/afp_program.h"

#include <gtest/gtest.h>

#include <sstream>

#include "stitchsim/common/files.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/process/afp_tows.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::program {
namespace {

// Two courses of ply 1 on the plane z = 0, travel +x (tool z up: A = 180 turns the flange's
// down-pointing z up... here A B C = 0 keeps the tool frame = part frame: z up, y along +y).
// Course 1: tows 1-4 added at x = 0, tow 4 cut at x = 50, the rest cut at x = 100.
constexpr char kProgramme[] = R"(%
(STITCHSIM scene=t head=afp)
G21 G90
T3 M6
M70 P1 (PLY name=a)
M71 P1 (COURSE 1)
G0 X0 Y0 Z100 A0 B0 C0 M20
M21
G1 X0 Y0 Z0 F6000
M62 P1
M62 P2
M62 P3
M62 P4
G1 X0 Y50 Z0
M63 P4
G1 X0 Y100 Z0
M63 P0
M20
G0 X0 Y100 Z100
M72
M71 P2 (COURSE 2)
G0 X30 Y0 Z100 A0 B0 C0
M21
G1 X30 Y0 Z0
M62 P0
G1 X30 Y100 Z0
M63 P0
M20
G0 X30 Y100 Z100
M72
M30
%
)";

std::optional<AfpProgram> Read(const std::string& text, DiagnosticSink& sink) {
  std::istringstream in(text);
  return ReadAfpProgram(in, Dialect::Default(), "t.nc", sink);
}

TEST(AfpProgram, SplitsCoursesIntoApproachLayupRetract) {
  DiagnosticSink sink;
  const auto p = Read(kProgramme, sink);
  ASSERT_TRUE(p.has_value()) << (sink.Diagnostics().empty() ? "" : sink.Diagnostics()[0].message);
  ASSERT_EQ(p->plies.size(), 1u);
  EXPECT_EQ(p->plies[0].courses, (std::vector<int>{0, 1}));
  ASSERT_EQ(p->courses.size(), 2u);
  const AfpCourse& c = p->courses[0];
  EXPECT_EQ(c.begin_line, 6);
  EXPECT_EQ(c.layup_first_line, 10);  // the first M62
  EXPECT_EQ(c.layup_last_line, 17);   // M63 P0
  EXPECT_EQ(c.end_line, 20);
  ASSERT_EQ(c.stations.size(), 3u);
  EXPECT_EQ(c.stations[0].tows, 0xFu);
  EXPECT_EQ(c.stations[1].tows, 0x7u);
  EXPECT_EQ(c.stations[2].tows, 0u);
  EXPECT_NEAR(c.stations[1].pose.translation().y(), 50.0, 1e-12);
  EXPECT_EQ(c.stations[0].feed_mm_per_min, 6000.0);
  EXPECT_FALSE(c.entry.head_retracted);
  EXPECT_EQ(c.entry.motion, Motion::kFeed);
  EXPECT_DOUBLE_EQ(c.layup_length_mm, 100.0);
  EXPECT_EQ(p->courses[1].layup_first_line, 25);
  EXPECT_EQ(p->prologue_last_line, 4);
  EXPECT_EQ(p->Line(10), "M62 P1");
  // Off-part by hand: 100 down, 100 up, to (30, 0, 100): hypot(30, 100), 100 down, 100 up.
  EXPECT_NEAR(p->offpart_length_mm, 100 + 100 + std::hypot(30.0, 100.0) + 100 + 100, 1e-9);
  ASSERT_TRUE(p->first_pose.has_value());
  EXPECT_NEAR(p->first_pose->translation().z(), 100.0, 1e-12);
}

TEST(AfpProgram, EveryDiagnosticAtItsLine) {
  const std::string base = kProgramme;
  auto edit = [&](const std::string& from, const std::string& to) {
    std::string t = base;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  struct Case {
    std::string text, code;
    int line;
  };
  const std::vector<Case> cases = {
      {edit("M71 P2 (COURSE 2)", "M71 P1"), "sequence-marks-order", 21},
      {edit("M70 P1 (PLY name=a)\n", ""), "sequence-marks-order", 5},
      {edit("M62 P0\n", ""), "sequence-empty-course", 21},
      {edit("M63 P0\nM20\nG0 X30", "M20\nG0 X30"), "sequence-open-tows", 29},
      {"%\nG21\nG0 X0 Y0 Z0 A0 B0 C0\nM30\n%\n", "sequence-no-courses", 5},
      {"%\nG21\nM70 P1\nM71 P1\nG0 X0 Y0 Z1\nM62 P1\nG1 X1 F100\nM63 P0\nM72\nM30\n%\n",
       "sequence-incomplete-pose", 6},
  };
  for (const Case& c : cases) {
    DiagnosticSink sink;
    EXPECT_FALSE(Read(c.text, sink).has_value()) << c.code;
    ASSERT_TRUE(sink.HasErrors()) << c.code;
    EXPECT_EQ(sink.Diagnostics().front().code, c.code) << c.text;
    EXPECT_EQ(sink.Diagnostics().front().location.line, c.line) << c.code;
    EXPECT_EQ(sink.Diagnostics().front().location.file, "t.nc");
  }
}

TEST(AfpProgram, ReversalMirrorsTowsAndTurnsPoses) {
  DiagnosticSink sink;
  const auto p = Read(kProgramme, sink);
  ASSERT_TRUE(p.has_value());
  const AfpCourse& c = p->courses[0];
  EXPECT_EQ(MirrorTow(1, 16), 16);
  EXPECT_EQ(MirrorTows(0xFu, 16), 0xF000u);
  const auto r = ReversedStations(c, 16);
  ASSERT_EQ(r.size(), 3u);
  // Backwards: from y = 100 to 50 the forward move 50 -> 100 laid tows 1-3: mirrored 14-16.
  EXPECT_NEAR(r[0].pose.translation().y(), 100.0, 1e-12);
  EXPECT_EQ(r[0].tows, 0xE000u);
  EXPECT_EQ(r[1].tows, 0xF000u);
  EXPECT_EQ(r[2].tows, 0u);
  EXPECT_TRUE(r[0].pose.linear().col(2).isApprox(c.stations[2].pose.linear().col(2), 1e-12));
  EXPECT_TRUE(r[0].pose.linear().col(1).isApprox(-c.stations[2].pose.linear().col(1), 1e-12));
  EXPECT_TRUE(LayupStartPose(c, true).isApprox(r[0].pose, 1e-12));
  EXPECT_TRUE(LayupEndPose(c, true).isApprox(r[2].pose, 1e-12));
  AfpCourse twice = c;
  twice.stations = r;
  const auto back = ReversedStations(twice, 16);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(back[k].pose.isApprox(c.stations[k].pose, 1e-12)) << k;
    if (k < 2) {
      EXPECT_EQ(back[k].tows, c.stations[k].tows) << k;
    }
  }
}

// Writes `p` in `order` with an approach straight down onto each lay-up start.
std::string Write(const AfpProgram& p, const std::vector<CourseVisit>& order) {
  std::ostringstream out;
  const OffPartSource source = [&](std::size_t i) {
    std::vector<OffPartBlock> b;
    if (i >= order.size()) return b;
    const Eigen::Isometry3d start =
        LayupStartPose(p.courses[static_cast<std::size_t>(order[i].course)], order[i].reversed);
    OffPartBlock above;
    above.pose = start;
    above.pose.translation() += 100.0 * start.linear().col(2);
    b.push_back(above);
    OffPartBlock down;
    down.pose = start;
    down.motion = Motion::kFeed;
    down.head_retracted = false;
    down.feed_mm_per_min = 6000.0;
    b.push_back(down);
    return b;
  };
  WriteAfpProgram(out, p, Dialect::Default(), order, source, AfpWriteOptions{16, {{"k", "v"}}});
  return out.str();
}

TEST(AfpProgram, RoundTripKeepsLayupsByteForByteAndReversesExactly) {
  DiagnosticSink sink;
  const auto p = Read(kProgramme, sink);
  ASSERT_TRUE(p.has_value());
  const std::string text = Write(*p, {{1, false}, {0, true}});
  DiagnosticSink sink2;
  const auto q = Read(text, sink2);
  ASSERT_TRUE(q.has_value()) << text
                             << (sink2.Diagnostics().empty() ? "" : sink2.Diagnostics()[0].message);
  EXPECT_NE(text.find("(STITCHSIM scene=t head=afp k=v)"), std::string::npos) << text;
  ASSERT_EQ(q->courses.size(), 2u);
  const AfpCourse& a = q->courses[0];  // course 2 as written
  EXPECT_EQ(a.number, 2);
  for (int l = 0; l <= a.layup_last_line - a.layup_first_line; ++l)
    EXPECT_EQ(q->Line(a.layup_first_line + l), p->Line(p->courses[1].layup_first_line + l));
  const AfpCourse& b = q->courses[1];  // course 1 backwards
  EXPECT_EQ(b.number, 1);
  const auto r = ReversedStations(p->courses[0], 16);
  ASSERT_EQ(b.stations.size(), r.size()) << text;
  for (std::size_t k = 0; k < r.size(); ++k) {
    EXPECT_LT((b.stations[k].pose.translation() - r[k].pose.translation()).norm(), 1e-6) << k;
    EXPECT_LT((b.stations[k].pose.linear() - r[k].pose.linear()).norm(), 1e-6) << k;
    EXPECT_EQ(b.stations[k].tows & 0xFFFFu, r[k].tows) << k << "\n" << text;
  }
}

// On the panel's planned ply: each reversed course's tow boundaries on the surface are the
// forward ones, mirrored (boundary b of k backwards is boundary k - b forwards), to 1e-6 mm.
TEST(AfpProgram, AReversedPlannedCourseLaysTheSameTowBoundaries) {
  DiagnosticSink sink;
  const auto scene = scene::LoadScene(DataDir() / "scenes" / "afp_panel.yaml", sink);
  ASSERT_TRUE(scene);
  const auto plan = planner::PlanPly(*scene, *scene->FindPly("skin_45"), {}, sink);
  ASSERT_TRUE(plan);
  std::ostringstream nc;
  planner::WritePlyProgram(*plan, *scene, Dialect::Default(), nc);
  const auto p = Read(nc.str(), sink);
  ASSERT_TRUE(p.has_value());
  const process::TowLayout layout = process::TowLayoutOf(scene->head);
  int compared = 0;
  for (const AfpCourse& c : p->courses) {
    const auto r = ReversedStations(c, layout.tows);
    const std::size_t n = c.stations.size();
    for (std::size_t k = 0; k < n; ++k) {
      const auto f = process::TowsAt(*scene->surface, c.stations[k].pose, layout, nullptr);
      const auto b = process::TowsAt(*scene->surface, r[n - 1 - k].pose, layout, nullptr);
      ASSERT_TRUE(f.ok && b.ok);
      for (int i = 0; i <= layout.tows; ++i, ++compared)
        EXPECT_LT((f.boundary[static_cast<std::size_t>(i)] -
                   b.boundary[static_cast<std::size_t>(layout.tows - i)])
                      .norm(),
                  1e-6);
    }
  }
  EXPECT_GT(compared, 1000);
}

}  // namespace
}  // namespace stitchsim::program
