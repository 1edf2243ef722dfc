// The stitch planner, read back through the parser: line structure, U/V bookkeeping, poses
// on the path, round trip, and the auto-mode decisions of seed 000's guidance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string_view>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/planner/plan_status.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/writer.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
using program::Axis;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

std::unique_ptr<scene::Scene> Load(const std::string& name) {
  DiagnosticSink sink;
  auto s = scene::LoadScene(kSource / "scenes" / (name + ".yaml"), sink);
  EXPECT_NE(s, nullptr) << name;
  return s;
}

struct Written {
  std::string text;
  ProgramSummary summary;
  double stitch_length_mm = 0;
  int count = 0;
};

Written Plan(const scene::Scene& s, const scene::PathSpec& p, Mode mode) {
  DiagnosticSink sink;
  StitchPlanOptions o;
  o.mode = mode;
  auto planner = StitchPathPlanner::Create(s, p, o, sink);
  EXPECT_TRUE(planner.has_value());
  std::ostringstream out;
  Written w;
  w.stitch_length_mm = planner->StitchLengthMm();
  w.count = planner->StitchCount();
  w.summary = WriteStitchProgram(*planner, s, p.name, program::Dialect::Default(), out);
  w.text = out.str();
  return w;
}

// A resolved motion line of a programme.
struct Motion {
  int line;
  bool is_move;
  std::array<double, program::kAxisCount> before{};
  std::array<double, program::kAxisCount> after{};
};

std::vector<Motion> Moves(const std::string& text) {
  DiagnosticSink sink;
  const auto blocks = program::ParseString(text, program::Dialect::Default(), "planned.nc", sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  program::ModalState state(program::Dialect::Default(), "planned.nc", sink);
  std::vector<Motion> out;
  for (const auto& b : blocks) {
    const program::Step& step = state.Update(b);
    if (!step.is_move) continue;
    Motion m;
    m.line = b.source_line;
    m.is_move = true;
    for (std::size_t a = 0; a < program::kAxisCount; ++a) {
      if (a == static_cast<std::size_t>(Axis::kRail) ||
          a == static_cast<std::size_t>(Axis::kRotator))
        continue;
      m.after[a] = state.State().axes[a].value_or(NAN);
      m.before[a] = state.Previous().axes[a].value_or(NAN);
    }
    out.push_back(m);
  }
  EXPECT_FALSE(sink.HasErrors());
  return out;
}

bool Same(const Motion& m, Axis a, double tol = 0.0) {
  const auto i = static_cast<std::size_t>(a);
  return std::abs(m.after[i] - m.before[i]) <= tol;
}
double At(const Motion& m, Axis a) { return m.after[static_cast<std::size_t>(a)]; }

// Distance (mm) from a part-frame point to the path's 3D curve: project to the surface, then
// to the nearest point of the 2D curve (dense search + refinement), lift, and measure.
double DistanceToPath(const scene::Scene& s, const scene::PathSpec& p, const Eigen::Vector3d& q) {
  const geom::SurfaceProjection pr = s.surface->Project(q);
  double best = INFINITY;
  for (std::size_t seg = 0; seg < p.curve->SegmentCount(); ++seg) {
    const geom::CurveSegment& c = p.curve->Segment(seg);
    double bt = 0, bd = INFINITY;
    for (int k = 0; k <= 2000; ++k) {
      const double t = k / 2000.0;
      const double d = (c.At(t) - pr.uv).norm();
      if (d < bd) {
        bd = d;
        bt = t;
      }
    }
    double lo = std::max(0.0, bt - 1e-3), hi = std::min(1.0, bt + 1e-3);
    for (int it = 0; it < 200; ++it) {  // golden-section on the 3D distance
      const double m1 = lo + (hi - lo) * 0.381966, m2 = lo + (hi - lo) * 0.618034;
      const double d1 = (s.surface->Point(c.At(m1)) - q).norm();
      const double d2 = (s.surface->Point(c.At(m2)) - q).norm();
      if (d1 < d2) {
        hi = m2;
      } else {
        lo = m1;
      }
    }
    best = std::min(best, (s.surface->Point(c.At(0.5 * (lo + hi))) - q).norm());
  }
  return best;
}

const char* kScenes[] = {"flat_straight",      "circle_8in",  "cutout_slot",
                         "cylinder_r90_frame", "arcs_planar", "blade_demo"};

TEST(DecoupledProgramme, LineStructureBookkeepingAndPointsOnThePath) {
  for (const char* name : kScenes) {
    auto s = Load(name);
    for (const auto& p : s->paths) {
      SCOPED_TRACE(std::string(name) + "/" + p.name);
      const Written w = Plan(*s, p, Mode::kDecoupled);
      const auto moves = Moves(w.text);
      ASSERT_EQ(static_cast<int>(moves.size()), 1 + 2 * w.count);
      EXPECT_EQ(w.summary.decoupled, w.count);
      // Start line: U = V = 0.
      EXPECT_EQ(At(moves[0], Axis::kDrive), 0.0);
      EXPECT_EQ(At(moves[0], Axis::kPathLength), 0.0);
      for (int i = 1; i <= w.count; ++i) {
        const Motion& tr = moves[static_cast<std::size_t>(2 * i - 1)];
        const Motion& rot = moves[static_cast<std::size_t>(2 * i)];
        const double uv = i * w.stitch_length_mm;
        // U and V equal i * l_s after stitch i (6-decimal text).
        EXPECT_NEAR(At(tr, Axis::kDrive), uv, 5e-7) << "line " << tr.line;
        EXPECT_NEAR(At(tr, Axis::kPathLength), uv, 5e-7) << "line " << tr.line;
        EXPECT_EQ(At(rot, Axis::kDrive), At(tr, Axis::kDrive)) << "line " << rot.line;
        EXPECT_EQ(At(rot, Axis::kPathLength), At(tr, Axis::kPathLength)) << "line " << rot.line;
        // Translation lines keep the previous A B C.
        for (Axis a : {Axis::kA, Axis::kB, Axis::kC})
          EXPECT_TRUE(Same(tr, a)) << "line " << tr.line;
        // Rotation lines change only A B C.
        for (Axis a : {Axis::kX, Axis::kY, Axis::kZ, Axis::kDrive, Axis::kPathLength}) {
          EXPECT_TRUE(Same(rot, a)) << "line " << rot.line;
        }
        // Every stitch point lies on the path.
        const Eigen::Vector3d q(At(tr, Axis::kX), At(tr, Axis::kY), At(tr, Axis::kZ));
        EXPECT_LT(DistanceToPath(*s, p, q), 1e-6) << "line " << tr.line;
      }
      const Eigen::Vector3d q0(At(moves[0], Axis::kX), At(moves[0], Axis::kY),
                               At(moves[0], Axis::kZ));
      EXPECT_LT(DistanceToPath(*s, p, q0), 1e-6);
    }
  }
}

// The spacing is measured on a polyline of the slot's own segments (straights and elliptic
// ends, sampled densely in their parameters), not with the planner's arc length: a stitch
// lies on the path and consecutive stitches are L / n apart along it, L measured here.
TEST(DecoupledProgramme, StitchPointsAreEquallySpacedAlongThePath) {
  auto s = Load("cutout_slot");
  const auto& p = s->paths.front();
  DiagnosticSink sink;
  auto planner = StitchPathPlanner::Create(*s, p, {}, sink);
  ASSERT_TRUE(planner);
  std::vector<Eigen::Vector2d> poly;
  std::vector<double> along{0.0};
  const geom::Curve2& curve = *p.curve;
  for (std::size_t i = 0; i < curve.SegmentCount(); ++i) {
    constexpr int kSamples = 200000;
    for (int j = i == 0 ? 0 : 1; j <= kSamples; ++j) {
      poly.push_back(curve.Segment(i).At(static_cast<double>(j) / kSamples));
      if (poly.size() > 1)
        along.push_back(along.back() + (poly.back() - poly[poly.size() - 2]).norm());
    }
  }
  const auto stitches = CollectStitches(*planner);
  ASSERT_GT(stitches.size(), 20U);
  const double spacing = along.back() / static_cast<double>(stitches.size());
  EXPECT_LE(spacing, 5.0 + 1e-9);  // the scene's nominal stitch length
  std::size_t k = 0;  // the stitches run forward along the path: search onwards from the last
  double previous = 0.0;
  for (const auto& st : stitches) {
    const Eigen::Vector3d q = st.end.translation();
    EXPECT_NEAR(q.z(), 0.0, 1e-9);
    const std::size_t end = std::min(poly.size(), k + 100000);
    std::size_t best = k;
    for (std::size_t j = k; j < end; ++j) {
      if ((poly[j] - q.head<2>()).squaredNorm() < (poly[best] - q.head<2>()).squaredNorm())
        best = j;
    }
    EXPECT_LT((poly[best] - q.head<2>()).norm(), 1e-3) << "stitch " << st.index;
    EXPECT_NEAR(along[best] - previous, spacing, 2e-3) << "stitch " << st.index;
    previous = along[best];
    k = best;
  }
}

TEST(CoupledProgramme, OneLinePerStitch) {
  for (const char* name : kScenes) {
    auto s = Load(name);
    for (const auto& p : s->paths) {
      const Written w = Plan(*s, p, Mode::kCoupled);
      const auto moves = Moves(w.text);
      EXPECT_EQ(static_cast<int>(moves.size()), 1 + w.count) << name << "/" << p.name;
      EXPECT_EQ(w.summary.decoupled, 0);
    }
  }
}

TEST(Programme, RoundTripsThroughTheParserAndWriter) {
  for (const char* name : kScenes) {
    auto s = Load(name);
    for (const auto& p : s->paths) {
      for (Mode mode : {Mode::kCoupled, Mode::kDecoupled, Mode::kAuto}) {
        const Written w = Plan(*s, p, mode);
        DiagnosticSink sink;
        program::ProgramHeader header;
        const auto blocks =
            program::ParseString(w.text, program::Dialect::Default(), "a.nc", sink, &header);
        ASSERT_FALSE(sink.HasErrors());
        const std::string again = program::WriteProgramString(blocks, program::Dialect::Default());
        program::ProgramHeader header2;
        const auto blocks2 =
            program::ParseString(again, program::Dialect::Default(), "b.nc", sink, &header2);
        EXPECT_EQ(header, header2);
        for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
        ASSERT_FALSE(sink.HasErrors());
        EXPECT_EQ(blocks, blocks2) << name << "/" << p.name;
        EXPECT_EQ(again, w.text) << name << "/" << p.name;  // the planner writes canonical text
        EXPECT_EQ(header.Find("scene").value_or(""), s->name);
      }
    }
  }
}

std::vector<PlannedStitch> AutoStitches(const scene::Scene& s, const std::string& path) {
  DiagnosticSink sink;
  auto planner = StitchPathPlanner::Create(s, *s.FindPath(path), {}, sink);
  EXPECT_TRUE(planner);
  return CollectStitches(*planner);
}

TEST(AutoMode, SeedGuidanceHolds) {
  {
    auto s = Load("circle_8in");
    for (const auto& st : AutoStitches(*s, "circle")) {
      EXPECT_TRUE(st.decoupled) << st.index;
      EXPECT_EQ(st.exceeded_limit, "needle.side_force");
    }
  }
  {
    auto s = Load("flat_straight");
    for (const auto& st : AutoStitches(*s, "row")) {
      EXPECT_FALSE(st.decoupled) << st.index;
      EXPECT_LT(st.coupled.MaxSideForceMm(), 1e-9);
    }
  }
  {
    auto s = Load("arcs_planar");
    for (const char* p : {"arc_r8", "arc_r12", "arc_r20"}) {
      for (const auto& st : AutoStitches(*s, p)) EXPECT_TRUE(st.decoupled) << p << " " << st.index;
    }
    for (const char* p : {"arc_r30", "arc_r48"}) {
      for (const auto& st : AutoStitches(*s, p)) EXPECT_FALSE(st.decoupled) << p << " " << st.index;
    }
    // The proxy falls with the radius: roughly w * yaw in the needle window.
    const auto r8 = AutoStitches(*s, "arc_r8");
    const auto r48 = AutoStitches(*s, "arc_r48");
    const double expect8 = 17.0 * 0.7 * 5.0 / (8 * 25.4);
    EXPECT_NEAR(r8[10].coupled.MaxSideForceMm(), expect8, 0.1 * expect8);
    EXPECT_GT(r8[10].coupled.MaxSideForceMm(), 5.0 * r48[10].coupled.MaxSideForceMm());
  }
  {
    auto s = Load("cutout_slot");
    int straights = 0, ends = 0;
    for (const auto& st : AutoStitches(*s, "cutout")) {
      // Stitches wholly on a straight (both ends on it) stay coupled; the elliptic ends are
      // decoupled.
      const bool on_straight = std::abs(st.start.translation().y()) > 50.8 - 1e-6 &&
                               std::abs(st.end.translation().y()) > 50.8 - 1e-6 &&
                               std::abs(st.start.translation().x()) < 127 - 5.1 &&
                               std::abs(st.end.translation().x()) < 127 - 5.1;
      if (on_straight) {
        EXPECT_FALSE(st.decoupled) << st.index;
        ++straights;
      } else if (st.segment_label == "end") {
        EXPECT_TRUE(st.decoupled) << st.index;
        ++ends;
      }
    }
    EXPECT_GT(straights, 80);
    EXPECT_GT(ends, 40);
  }
}

TEST(Planner, CoupledMetricsOnRequestInFixedModes) {
  auto s = Load("circle_8in");
  for (bool evaluate : {false, true}) {
    StitchPlanOptions o;
    o.mode = Mode::kDecoupled;
    o.evaluate_coupled = evaluate;
    DiagnosticSink sink;
    auto planner = StitchPathPlanner::Create(*s, s->paths.front(), o, sink);
    ASSERT_TRUE(planner);
    PlannedStitch st;
    ASSERT_TRUE(planner->Next(st));
    EXPECT_TRUE(st.decoupled);
    if (evaluate) {
      EXPECT_GT(st.coupled.MaxSideForceMm(), 0.2);
      EXPECT_EQ(st.exceeded_limit, "needle.side_force");
    } else {
      EXPECT_TRUE(st.coupled.side_force_mm.empty());
      EXPECT_TRUE(st.exceeded_limit.empty());
    }
  }
}

TEST(AutoMode, BladeSparDecouplesOnlyTheTurnBetweenItsSegments) {
  auto s = Load("blade_demo");
  const auto st = AutoStitches(*s, "spar");
  int decoupled = 0;
  for (const auto& x : st) {
    if (!x.decoupled) continue;
    ++decoupled;
    // Near the corner at (0, 0.5 in).
    EXPECT_LT(std::abs(x.end.translation().x()), 10.0) << x.index;
  }
  EXPECT_GE(decoupled, 1);
  EXPECT_LE(decoupled, 3);
}

TEST(Planner, PathShorterThanOneStitchIsAClearError) {
  auto s = Load("flat_straight");
  scene::PathSpec tiny;
  tiny.name = "tiny";
  tiny.where = {"tiny.yaml", 3, 1};
  tiny.curve = std::make_unique<geom::Curve2>();
  tiny.curve->Add(geom::MakeLineSegment(Eigen::Vector2d(0, 0), Eigen::Vector2d(3, 0)));
  DiagnosticSink sink;
  EXPECT_FALSE(StitchPathPlanner::Create(*s, tiny, {}, sink).has_value());
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "plan-path-too-short");
  StitchPlanOptions zero;
  zero.nominal_stitch_length_mm = 0.0;
  DiagnosticSink sink2;
  EXPECT_FALSE(StitchPathPlanner::Create(*s, s->paths.front(), zero, sink2).has_value());
  EXPECT_EQ(sink2.Diagnostics().front().code, "plan-bad-stitch-length");
}

TEST(Planner, CycleTimeShowsTheDecouplingPenalty) {
  auto s = Load("circle_8in");
  const Written c = Plan(*s, s->paths.front(), Mode::kCoupled);
  const Written d = Plan(*s, s->paths.front(), Mode::kDecoupled);
  EXPECT_NEAR(c.summary.time.stitching_s, c.count * 60.0 / 300.0, 1e-9);
  EXPECT_GT(d.summary.time.Total(), c.summary.time.Total() * 1.5);
  EXPECT_NEAR(d.summary.time.rotation_s, 2 * kPi / (30.0 * kDeg) + d.count * 0.15, 1e-6);
}

// WriteStitchProgram as three steps: the moves of each stitch, their time, their text; and
// the checks plan stitch asks of a scene (its head, a path by name).

StitchPathPlanner Planner(const scene::Scene& s, Mode mode, std::optional<double> length = {}) {
  DiagnosticSink sink;
  StitchPlanOptions o;
  o.mode = mode;
  o.nominal_stitch_length_mm = length;
  auto p = StitchPathPlanner::Create(s, s.paths.front(), o, sink);
  EXPECT_TRUE(p.has_value());
  return std::move(*p);
}

TEST(StitchWriter, MovesOfADecoupledStitchTranslateFirstThenTurn) {
  PlannedStitch s;
  s.index = 3;
  s.decoupled = true;
  s.start = Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
  s.end = Eigen::Translation3d(4, 5, 6) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ());
  s.rotation_rad = 0.2;
  const StitchMoves m = MovesOf(s, 2.5);
  EXPECT_TRUE(m.decoupled);
  EXPECT_EQ(m.Lines(), 2);
  EXPECT_TRUE(m.translate.linear().isApprox(s.start.linear(), 0.0));
  EXPECT_TRUE(m.translate.translation().isApprox(s.end.translation(), 0.0));
  EXPECT_TRUE(m.end.isApprox(s.end, 0.0));
  EXPECT_EQ(m.drive_mm, 7.5);
  s.decoupled = false;
  EXPECT_EQ(MovesOf(s, 2.5).Lines(), 1);
}

TEST(StitchWriter, TimeOfAStitchByHand) {
  scene::StitchProcessSpec spec;
  spec.stitch_rate_per_min = 300.0;  // 0.2 s a stitch
  spec.rotation_speed_deg_s = 30.0;
  spec.settle_time_s = 0.15;
  const StitchTiming t = StitchTimingOf(spec);
  StitchMoves m;
  m.rotation_rad = 15.0 * kDeg;  // 0.5 s at 30 deg/s
  CycleTime coupled;
  AddStitchTime(m, t, coupled);
  EXPECT_NEAR(coupled.stitching_s, 0.5, 1e-12);  // the turn is slower than the stitch
  EXPECT_EQ(coupled.rotation_s, 0.0);
  m.decoupled = true;
  CycleTime decoupled;
  AddStitchTime(m, t, decoupled);
  EXPECT_NEAR(decoupled.stitching_s, 0.2, 1e-12);
  EXPECT_NEAR(decoupled.rotation_s, 0.5 + 0.15, 1e-12);
}

// The summary of the written programme against the same stitches planned again and summed
// here, for each mode; the motion lines against the text's lines with an axis word.

// A word of an axis letter and a number (X12.5, C-90, Y.5), at the line's start or after a
// space: a motion line of the stitch programme.
bool HasAxisWord(const std::string& line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (i > 0 && line[i - 1] != ' ' && line[i - 1] != '\t') continue;
    if (std::string_view("XYZABCUV").find(line[i]) == std::string_view::npos) continue;
    std::size_t j = i + 1;
    if (j < line.size() && line[j] == '-') ++j;
    if (j < line.size() && (std::isdigit(static_cast<unsigned char>(line[j])) || line[j] == '.'))
      return true;
  }
  return false;
}

TEST(StitchWriter, SummaryIsTheSumOverTheStitchesPlannedAgain) {
  const auto s = Load("circle_8in");
  ASSERT_NE(s, nullptr);
  const StitchTiming timing = StitchTimingOf(s->head.stitch);
  for (Mode mode : {Mode::kCoupled, Mode::kDecoupled, Mode::kAuto}) {
    StitchPathPlanner writing = Planner(*s, mode);
    std::ostringstream out;
    const ProgramSummary sum =
        WriteStitchProgram(writing, *s, s->paths.front().name, program::Dialect::Default(), out);
    StitchPathPlanner again = Planner(*s, mode);
    const std::vector<PlannedStitch> stitches = CollectStitches(again);
    double stitching = 0, rotation = 0;
    int decoupled = 0;
    for (const PlannedStitch& p : stitches) {
      const double turn_s = p.rotation_rad / (s->head.stitch.rotation_speed_deg_s * kDeg);
      if (p.decoupled) {
        ++decoupled;
        stitching += timing.stitch_time_s;
        rotation += turn_s + s->head.stitch.settle_time_s;
      } else {
        stitching += std::max(timing.stitch_time_s, turn_s);
      }
    }
    EXPECT_EQ(sum.stitches, static_cast<int>(stitches.size()));
    EXPECT_EQ(sum.decoupled, decoupled);
    EXPECT_NEAR(sum.time.stitching_s, stitching, 1e-9);
    EXPECT_NEAR(sum.time.rotation_s, rotation, 1e-9);
    std::istringstream text(out.str());
    long axis_lines = 0;
    for (std::string line; std::getline(text, line);) {
      axis_lines += HasAxisWord(line.substr(0, line.find('(')));  // outside comments
    }
    EXPECT_EQ(sum.motion_lines, axis_lines);
    EXPECT_EQ(sum.motion_lines, 1 + sum.stitches + sum.decoupled);
    if (mode == Mode::kDecoupled) {
      EXPECT_EQ(decoupled, sum.stitches);
    }
    if (mode == Mode::kCoupled) {
      EXPECT_EQ(decoupled, 0);
    }
  }
}

TEST(StitchWriter, SummarySaysTheNominalLengthAskedFor) {
  const auto s = Load("circle_8in");
  ASSERT_NE(s, nullptr);
  for (std::optional<double> asked : {std::optional<double>(), std::optional<double>(3.3)}) {
    StitchPathPlanner p = Planner(*s, Mode::kCoupled, asked);
    std::ostringstream out;
    const ProgramSummary sum =
        WriteStitchProgram(p, *s, s->paths.front().name, program::Dialect::Default(), out);
    EXPECT_EQ(sum.nominal_stitch_length_mm, asked.value_or(s->nominal_stitch_length_mm));
    EXPECT_EQ(sum.stitch_length_mm, sum.path_length_mm / sum.stitches);
  }
}

TEST(PlanStatus, AStitchPlanNeedsAStitchingHeadAndAPathByName) {
  const auto stitching = Load("circle_8in");
  const auto afp = Load("afp_panel");
  ASSERT_TRUE(stitching && afp);
  EXPECT_TRUE(StitchingHeadStatus(*stitching).Ok());
  const PlanStatus wrong = StitchingHeadStatus(*afp);
  EXPECT_EQ(wrong.code, "plan-wrong-head");
  EXPECT_EQ(wrong.message, "head '" + afp->head.name +
                               "' does not stitch; use `stitchsim plan afp` for fiber placement");
  const PathChoice first = ChoosePath(*stitching, "");
  EXPECT_TRUE(first.status.Ok());
  EXPECT_EQ(first.path, &stitching->paths.front());
  const PathChoice named = ChoosePath(*stitching, stitching->paths.back().name);
  EXPECT_EQ(named.path, &stitching->paths.back());
  const PathChoice none = ChoosePath(*stitching, "nowhere");
  EXPECT_EQ(none.path, nullptr);
  EXPECT_EQ(none.status.code, "plan-unknown-path");
  std::string names;
  for (const auto& p : stitching->paths) names += (names.empty() ? "" : ", ") + p.name;
  EXPECT_EQ(none.status.message, "no path named 'nowhere' (paths: " + names + ")");
}

}  // namespace
}  // namespace stitchsim::planner
