// The ply planner against the head's cut limits and feed schedule (issue 29): short tow pieces
// extended or dropped, close restarts bridged or moved, per the ply's coverage; the slow zones
// around cuts and adds written as points and F words. On a plane (u = x, v = y) a tow is a
// straight strip, so every length is a difference of x: the expected positions are worked out
// by hand below. The afp.min_tow_length, afp.restart_distance and laydown figures of verify
// (its own measure of the programme) are the second route on the written text.
//
// The head (models/heads/afp.yaml): 16 tows of 6.35 mm, course 101.6 mm, the band centred on
// the course: tow edges at v = -50.8 + 6.35 k. Cut-to-roller and restart 100 mm; 150 mm/s
// within 25 mm of each cut and add; lay-up 200 mm/s (F12000). The ply's box runs u in
// [-300, 300], v in [-51, 44]: fifteen tows inside it (the one at [38.1, 44.45] 7 % outside,
// laid at 50 % coverage, not at 0 %); the sixteenth, [44.45, 50.8], only where a tab of the
// boundary reaches v = 52.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "ply_test_support.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/verify/laydown.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::planner {
namespace {

using testing::Folder;
using testing::Load;
using testing::Plies;
using testing::SceneText;

const std::string kPlane = "surface:\n  type: plane\n  size: [1600, 600]\n";
// A 60 mm tab over u in [-100, -40]: tow 16's only piece (and tow 15's at 0 %).
const std::string kTab =
    "[[-300, -51], [300, -51], [300, 44], [-40, 44], [-40, 52], [-100, 52], [-100, 44], "
    "[-300, 44]]";
// A 60 mm notch over u in [-100, -40] in a strip to v = 52: tow 16 (and 15 at 0 %) cut and
// added again 60 mm on.
const std::string kNotch =
    "[[-300, -51], [300, -51], [300, 52], [-40, 52], [-40, 44], [-100, 44], [-100, 52], "
    "[-300, 52]]";

// Tabs over v in [38, 52] for tows 15 and 16 alone, the left edge slanted: (-100, 38) to
// (-104, 52).
const std::string kSlantedTab =
    "[[-300, -51], [300, -51], [300, 38], [-40, 38], [-40, 52], [-104, 52], [-100, 38], "
    "[-300, 38]]";
// A 150 mm notch over u in [0, 150]: tow 16 cut at 0, added again at 150.
const std::string kNotch150 =
    "[[-300, -51], [300, -51], [300, 52], [150, 52], [150, 44], [0, 44], [0, 52], [-300, 52]]";

struct Planned {
  std::unique_ptr<scene::Scene> scene;
  PlyPlan plan;
};

Planned PlanOne(const std::string& name, const std::string& boundary, int coverage,
                const std::string& extra = "") {
  Planned p;
  const auto dir = Folder(name);
  std::ofstream(dir / "s.yaml") << SceneText(kPlane, Plies(boundary, coverage, "0"), extra);
  p.scene = Load(dir / "s.yaml");
  if (p.scene == nullptr) return p;
  DiagnosticSink sink;
  auto plan = PlanPly(*p.scene, p.scene->plies.front(), {}, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  if (plan) p.plan = std::move(*plan);
  return p;
}

/// The x of the course point at course length s (a test failure if there is none).
double XAt(const PlyCourse& c, double s) {
  for (const PlyPoint& p : c.points)
    if (p.s_mm == s) return p.tool.translation().x();
  ADD_FAILURE() << "no point at s " << s;
  return NAN;
}

/// Each tow's laid pieces as [x_start, x_end], by head tow number.
std::map<int, std::vector<std::pair<double, double>>> Pieces(const PlyCourse& c) {
  std::map<int, std::vector<std::pair<double, double>>> out;
  for (const PlyTow& t : c.tows)
    for (const TowSegment& g : t.laid) out[t.tow].push_back({XAt(c, g.start_mm), XAt(c, g.end_mm)});
  return out;
}

/// The tows whose pieces are not the one full [-300, 300] piece.
std::map<int, std::vector<std::pair<double, double>>> Odd(const PlyCourse& c) {
  auto all = Pieces(c);
  std::erase_if(all, [](const auto& kv) {
    return kv.second.size() == 1 && std::abs(kv.second[0].first + 300) < 0.01 &&
           std::abs(kv.second[0].second - 300) < 0.01;
  });
  return all;
}

TEST(PlyTowPieces, AShortPieceIsExtendedAtHalfCoverageAndDroppedAtNone) {
  {
    SCOPED_TRACE("coverage 50 %");
    const Planned p = PlanOne("short50", kTab, 50);
    ASSERT_EQ(p.plan.courses.size(), 1u);
    EXPECT_EQ(p.plan.min_tow_length_mm, 100.0);
    const auto odd = Odd(p.plan.courses[0]);
    ASSERT_EQ(odd.size(), 1u);  // tow 16's 60 mm piece, the others full length
    const auto& pieces = odd.begin()->second;
    ASSERT_EQ(pieces.size(), 1u);
    // 60 mm lacks 40 mm (+ the 0.1 mm margin): 20.05 mm more at each end, round u = -70.
    EXPECT_NEAR(pieces[0].first, -120.05, 0.01);
    EXPECT_NEAR(pieces[0].second, -19.95, 0.01);
    EXPECT_EQ(p.plan.fixes.pieces_extended, 1);
    EXPECT_EQ(p.plan.fixes.pieces_dropped, 0);
    EXPECT_NEAR(p.plan.shortest_piece_mm, 100.1, 0.01);
  }
  {
    SCOPED_TRACE("coverage 0 %");
    const Planned p = PlanOne("short0", kTab, 0);
    ASSERT_EQ(p.plan.courses.size(), 1u);
    // Tows 15 and 16 lay only in the tab at 0 %: both 60 mm pieces are left bare.
    EXPECT_TRUE(Odd(p.plan.courses[0]).empty());
    EXPECT_EQ(p.plan.fixes.pieces_dropped, 2);
    EXPECT_EQ(p.plan.fixes.pieces_extended, 0);
    int empty = 0;
    for (const PlyTow& t : p.plan.courses[0].tows) empty += t.laid.empty() ? 1 : 0;
    EXPECT_EQ(empty, 2);
    EXPECT_NEAR(p.plan.shortest_piece_mm, 600.0, 0.01);
  }
}

// Two short pieces side by side: tows 15 (centre v = 41.275) and 16 (v = 47.625) laid only in
// a tab whose left edge runs from (-100, 38) to (-104, 52), u = -100 - 4 (v - 38) / 14, right
// edge u = -40 (the box stops at v = 38). Tow 15: 60.936 mm from u = -100.936, extended
// 19.582 mm each way to [-120.518, -20.418]; tow 16: 62.75 mm from -102.75, 18.675 mm each way
// to [-121.425, -21.325]. Extended ends within a tow width of one another go together to the
// outermost: both tows lay [-121.425, -20.418].
TEST(PlyTowPieces, ExtendedTowsSideBySideStartAndStopTogether) {
  const Planned p = PlanOne("together", kSlantedTab, 50);
  ASSERT_EQ(p.plan.courses.size(), 1u);
  const auto odd = Odd(p.plan.courses[0]);
  ASSERT_EQ(odd.size(), 2u);
  for (const auto& [tow, pieces] : odd) {
    SCOPED_TRACE(tow);
    ASSERT_EQ(pieces.size(), 1u);
    EXPECT_NEAR(pieces[0].first, -121.425, 0.01);
    EXPECT_NEAR(pieces[0].second, -20.418, 0.01);
  }
  EXPECT_EQ(p.plan.fixes.pieces_extended, 2);
}

// A piece at the ply's end extended past the course's curve (the region ends 60.8 mm beyond
// the ply): a 300 mm minimum makes the 60 mm piece at u in [-300, -240] reach 120.05 mm beyond
// each end, to u = -420.05, and the course is planned again on a longer curve.
TEST(PlyTowPieces, APieceRunningPastTheCourseGetsALongerCourse) {
  const std::string tab_at_end =
      "[[-300, -51], [300, -51], [300, 44], [-240, 44], [-240, 52], [-300, 52]]";
  const Planned p =
      PlanOne("past_end", tab_at_end, 50, "limits:\n  afp.min_tow_length: {min_mm: 300}\n");
  ASSERT_EQ(p.plan.courses.size(), 1u);
  const PlyCourse& c = p.plan.courses[0];
  const auto odd = Odd(c);
  ASSERT_EQ(odd.size(), 1u);
  ASSERT_EQ(odd.begin()->second.size(), 1u);
  EXPECT_NEAR(odd.begin()->second[0].first, -420.05, 0.01);
  EXPECT_NEAR(odd.begin()->second[0].second, -119.95, 0.01);
  EXPECT_NEAR(c.points.front().tool.translation().x(), -420.05, 0.01);  // the course grew
  EXPECT_EQ(p.plan.fixes.pieces_extended, 1);
}

TEST(PlyTowPieces, ACloseRestartIsBridgedAtHalfCoverageAndMovedAtNone) {
  {
    SCOPED_TRACE("coverage 50 %");
    const Planned p = PlanOne("restart50", kNotch, 50);
    ASSERT_EQ(p.plan.courses.size(), 1u);
    EXPECT_EQ(p.plan.min_restart_mm, 100.0);
    EXPECT_TRUE(Odd(p.plan.courses[0]).empty());  // tow 16 laid through the 60 mm notch
    EXPECT_EQ(p.plan.fixes.restarts_bridged, 1);
    EXPECT_EQ(p.plan.fixes.restarts_moved, 0);
  }
  {
    SCOPED_TRACE("coverage 0 %");
    const Planned p = PlanOne("restart0", kNotch, 0);
    ASSERT_EQ(p.plan.courses.size(), 1u);
    const auto odd = Odd(p.plan.courses[0]);
    ASSERT_EQ(odd.size(), 2u);  // tows 15 and 16: cut at -100, added again 100.1 mm on
    for (const auto& [tow, pieces] : odd) {
      SCOPED_TRACE(tow);
      ASSERT_EQ(pieces.size(), 2u);
      EXPECT_NEAR(pieces[0].first, -300.0, 0.01);
      EXPECT_NEAR(pieces[0].second, -100.0, 0.01);
      EXPECT_NEAR(pieces[1].first, 0.1, 0.01);
      EXPECT_NEAR(pieces[1].second, 300.0, 0.01);
    }
    EXPECT_EQ(p.plan.fixes.restarts_moved, 2);
    EXPECT_EQ(p.plan.fixes.restarts_bridged, 0);
  }
}

/// The programme's lines as the executor records them (no simulation: poses from the text).
std::vector<trace::LineRecord> Records(const std::string& text) {
  DiagnosticSink sink;
  const auto blocks = program::ParseString(text, program::Dialect::Default(), "ply.nc", sink);
  program::ModalState state(program::Dialect::Default(), "ply.nc", sink);
  std::vector<trace::LineRecord> out;
  auto pose = [](const program::MachineState& st) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    using program::Axis;
    t.translation() = Eigen::Vector3d(st[Axis::kX].value_or(0), st[Axis::kY].value_or(0),
                                      st[Axis::kZ].value_or(0));
    return t;
  };
  for (const auto& b : blocks) {
    const program::Step& step = state.Update(b);
    if (!step.is_move) continue;
    const program::MachineState& st = state.State();
    trace::LineRecord l;
    l.source_line = step.source_line;
    l.rapid = step.motion == program::Motion::kRapid;
    l.from = pose(state.Previous());
    l.to = pose(st);
    l.feed_mm_per_min = st.feed_mm_per_min.value_or(0.0);
    l.head_retracted = st.head_retracted;
    l.tows = st.tows;
    l.ply = st.ply;
    l.course = st.course;
    out.push_back(l);
  }
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return out;
}

// One straight course, tow 16 cut at u = 0 and added again at u = 150 (a 150 mm notch): the
// zones [-300, -275], [-25, 25], [125, 175], [275, 300] at 150 mm/s, the rest at 200 mm/s.
TEST(PlyTowPieces, TheSlowZonesAreWrittenAroundEveryCutAndAdd) {
  const Planned p = PlanOne("zones", kNotch150, 50);
  ASSERT_EQ(p.plan.courses.size(), 1u);
  std::ostringstream out;
  WritePlyProgram(p.plan, *p.scene, program::Dialect::Default(), out);
  const std::vector<trace::LineRecord> lines = Records(out.str());
  std::vector<double> xs;           // every feed move's end x inside the course
  std::vector<double> feeds;        // the F in force on each such move, mm/min
  std::vector<double> laying_feed;  // per laying move: its feed
  for (const trace::LineRecord& l : lines) {
    if (l.rapid || l.course == 0 || l.head_retracted) continue;
    xs.push_back(l.to.translation().x());
    EXPECT_NEAR(l.to.translation().y(), 0.0, 1e-6);
    if (feeds.empty() || feeds.back() != l.feed_mm_per_min) feeds.push_back(l.feed_mm_per_min);
    if (l.tows == 0) continue;
    // By hand: a move is slow when its middle lies within 25 mm of -300, 0, 150 or 300.
    const double mid = 0.5 * (l.from.translation().x() + l.to.translation().x());
    const bool slow = std::abs(mid + 300) < 25 || std::abs(mid) < 25 || std::abs(mid - 150) < 25 ||
                      std::abs(mid - 300) < 25;
    EXPECT_EQ(l.feed_mm_per_min, slow ? 9000.0 : 12000.0) << "move to x " << l.to.translation().x();
  }
  for (const double edge : {-275.0, -25.0, 25.0, 125.0, 175.0, 275.0}) {
    const bool found =
        std::any_of(xs.begin(), xs.end(), [&](double x) { return std::abs(x - edge) < 0.01; });
    EXPECT_TRUE(found) << "no programme point at the zone edge x = " << edge;
  }
  // The plunge at the lay-up speed, then slow / fast alternating over the four zones.
  const std::vector<double> expected = {12000, 9000, 12000, 9000, 12000, 9000, 12000, 9000};
  EXPECT_EQ(feeds, expected);
  // verify's laydown meter applies the zones to the programmed feeds itself: the programme
  // already runs them, so its time equals the lines' own (150 mm at 150 mm/s, 450 at 200).
  verify::LaydownParams params;
  params.cut_add_feed_mm_s = 150;
  params.cut_add_zone_mm = 25;
  verify::LaydownMeter meter(params);
  double programmed_s = 0.0;
  for (const trace::LineRecord& l : lines) {
    meter.OnLine(l);
    const bool laying = !l.rapid && !l.head_retracted && l.course != 0 && l.tows != 0;
    if (laying)
      programmed_s +=
          (l.to.translation() - l.from.translation()).norm() / (l.feed_mm_per_min / 60.0);
  }
  meter.Finish();
  const auto figures = meter.Figures();
  ASSERT_FALSE(figures.empty());
  EXPECT_NEAR(programmed_s, 150.0 / 150 + 450.0 / 200, 1e-6);
  EXPECT_NEAR(figures.front().laydown_s, programmed_s, 1e-9);
}

/// Runs verify's afp rules over `text` on `scene` (lines only: the afp.* rules read lines).
verify::Report VerifyLines(const scene::Scene& scene, const std::string& text) {
  const process::ProcessModel model = process::MakeProcessModel(scene, 5.0);
  trace::CellDescription cell;
  cell.lower_limits.setConstant(-10.0);
  cell.upper_limits.setConstant(10.0);
  cell.max_velocities.setConstant(10.0);
  verify::Verifier v(verify::RuleContext{&scene, &cell, &model}, false);
  for (const auto& l : Records(text)) v.OnLine(l);
  verify::Report r;
  v.Finish(r);
  return r;
}

long ErrorsOf(const verify::Report& r, const std::string& id) {
  for (const auto& s : r.rules)
    if (s.id == id) return s.errors;
  ADD_FAILURE() << id << " did not run";
  return -1;
}

// A 45 deg ply on a rectangle with a slot 60 mm wide: short pieces at every corner, and tows
// crossing the slot cut and added again 85 mm on. verify's rules (their own measure, on the
// written text) pass the mended plan and fail the plan made without the limits.
TEST(PlyTowPieces, TheMendedPlanPassesVerifysPieceRules) {
  const std::string limits =
      "limits:\n  afp.min_tow_length: {min_mm: 100}\n  afp.restart_distance: {min_mm: 100}\n";
  const std::string boundary =
      "[[-300, -150], [300, -150], [300, 250], [60, 250], [60, 20], [0, 20], [0, 250], "
      "[-300, 250]]";
  const std::string plane = "surface:\n  type: plane\n  size: [1600, 800]\n";
  for (const int coverage : {0, 50}) {
    SCOPED_TRACE(coverage);
    const auto dir = Folder("verify" + std::to_string(coverage));
    std::ofstream(dir / "s.yaml") << SceneText(plane, Plies(boundary, coverage, "45"), limits);
    auto s = Load(dir / "s.yaml");
    ASSERT_NE(s, nullptr);
    DiagnosticSink sink;
    const auto plan = PlanPly(*s, s->plies.front(), {}, sink);
    ASSERT_TRUE(plan);
    EXPECT_GT(plan->fixes.pieces_dropped + plan->fixes.pieces_extended, 0);
    EXPECT_GT(plan->fixes.restarts_moved + plan->fixes.restarts_bridged, 0);
    std::ostringstream text;
    WritePlyProgram(*plan, *s, program::Dialect::Default(), text);
    const verify::Report r = VerifyLines(*s, text.str());
    EXPECT_EQ(ErrorsOf(r, "afp.min_tow_length"), 0);
    EXPECT_EQ(ErrorsOf(r, "afp.restart_distance"), 0);
    // Planned without the limits (the scene's removed, the head's cleared): the rules fire.
    scene::Scene bare;
    bare.name = s->name;
    bare.head = s->head;
    bare.head.afp.cut_to_roller_mm.reset();
    bare.head.afp.min_restart_mm.reset();
    bare.surface = std::move(s->surface);
    bare.plies = s->plies;
    const auto unmended = PlanPly(bare, bare.plies.front(), {}, sink);
    ASSERT_TRUE(unmended);
    EXPECT_EQ(unmended->fixes.pieces_dropped + unmended->fixes.pieces_extended, 0);
    std::ostringstream raw;
    WritePlyProgram(*unmended, bare, program::Dialect::Default(), raw);
    s->surface = std::move(bare.surface);
    const verify::Report unmended_report = VerifyLines(*s, raw.str());
    EXPECT_GT(ErrorsOf(unmended_report, "afp.min_tow_length"), 0);
    EXPECT_GT(ErrorsOf(unmended_report, "afp.restart_distance"), 0);
  }
}

}  // namespace
}  // namespace stitchsim::planner
