// Issue S11: a programme verified in parts (cut where the needles are out), each part by its
// own verifier after a warm-up, merged in programme order, gives byte for byte the report of
// one verifier over the whole programme; so do the parts' partials through JSON; equal
// carries are what make a part exact, and a short warm-up shows in the carry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "afp_test_support.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/writer.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"
#include "verify_test_support.h"

namespace stitchsim::verify {
namespace {

using testing::Load;
using testing::Loaded;

// The trace as the verifier is given it: each line and the samples after it.
struct Recorder : trace::TraceSink {
  std::vector<trace::LineRecord> lines;
  std::vector<std::vector<trace::TraceSample>> samples;
  void OnLine(const trace::LineRecord& l) override {
    lines.push_back(l);
    samples.emplace_back();
  }
  void OnSample(const trace::TraceSample& s) override {
    ASSERT_FALSE(lines.empty());
    samples.back().push_back(s);
  }
};

// A recorded run and the context its verifiers share.
struct RecordedRun {
  Loaded loaded;
  process::ProcessModel model;
  trace::CellDescription cell;
  Recorder trace;
  RuleContext ctx;
  int Lines() const { return static_cast<int>(trace.lines.size()); }
};

std::unique_ptr<RecordedRun> Record(const std::string& scene, const std::string& text, double ls) {
  auto run = std::make_unique<RecordedRun>();
  run->loaded = Load(scene);
  const Loaded& l = run->loaded;
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  run->model = process::MakeProcessModel(*l.scene, ls);
  run->cell = sim::DescribeCell(*l.robot, nullptr);
  run->ctx = RuleContext{l.scene.get(), &run->cell, &run->model};
  DiagnosticSink sink;
  std::istringstream in(text);
  const sim::ExecutionSummary s =
      sim::ExecuteProgram(cell, run->model, program::Dialect::Default(), in, "test.nc",
                          sim::ExecuteOptionsFor(*l.scene), sink, run->trace);
  EXPECT_TRUE(s.ok);
  EXPECT_TRUE(sink.Diagnostics().empty());
  return run;
}

// Collision, timing and tracking figures written into the recorded samples (as a trace file
// could hold them), so the collision.*, kin.acceleration, kin.torque and dyn.tracking rules
// run too, with findings on many lines.
void Decorate(RecordedRun& run) {
  run.cell.collision_checked = true;
  run.cell.bodies = {"head:foot", "mold", "link_3", "rail"};
  run.cell.timed = true;
  run.cell.dynamic = true;
  run.cell.max_accelerations.setConstant(2.0);
  run.cell.max_efforts.setConstant(500.0);
  long k = 0;
  for (auto& line : run.trace.samples) {
    for (trace::TraceSample& s : line) {
      ++k;
      s.collision.checked = true;
      if (k % 29 == 0) {
        s.collision.contacts.push_back({trace::ContactClass::kHeadPart, 0, 1,
                                        0.0002 * static_cast<double>(k % 5 + 1), true,
                                        Eigen::Vector3d(0.1, 0.2, 0.3)});
      }
      if (k % 31 == 0) {
        s.collision.contacts.push_back({trace::ContactClass::kRobotCell, 2,
                                        static_cast<int>(3 - k % 2), 0.001, true,
                                        Eigen::Vector3d::Zero()});
      }
      if (s.collision.contacts.empty()) {
        s.collision.min_clearance_m = 0.004 + 0.001 * static_cast<double>(k % 23);
        s.collision.clearance_body_a = 0;
        s.collision.clearance_body_b = 2;
      }
      s.has_timing = s.has_joints;
      for (int j = 0; j < trace::kNumJoints; ++j) {
        s.joint_accelerations[j] = 2.2 * std::sin(0.37 * static_cast<double>(k + j));
        s.joint_torques[j] = 560.0 * std::cos(0.11 * static_cast<double>(k * (j + 1)));
      }
      s.tracked = true;
      s.tracking_error_mm = 0.05 * static_cast<double>(k % 17);
      s.tracking_error_deg = 0.01;
    }
  }
}

// Feeds lines [from, to) and their samples.
void Feed(const RecordedRun& run, Verifier& v, int from, int to) {
  for (int i = std::max(0, from); i < to; ++i) {
    v.OnLine(run.trace.lines[static_cast<std::size_t>(i)]);
    for (const auto& s : run.trace.samples[static_cast<std::size_t>(i)]) v.OnSample(s);
  }
}

struct Texts {
  std::string json, text, junit;
};

Texts Finish(Verifier& v) {
  Report r;
  v.Finish(r);
  return {ReportToJson(r), ReportToText(r), ReportToJunit(r)};
}

// Where two texts part (a short excerpt: a report is long).
std::string FirstDifference(const std::string& a, const std::string& b) {
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  const std::size_t from = i < 80 ? 0 : i - 80;
  return "at byte " + std::to_string(i) + ":\n  " + a.substr(from, 160) + "\n  vs\n  " +
         b.substr(from, 160);
}

// Byte-identical JSON, text and JUnit; else one failure naming where they part.
bool Same(const Texts& a, const Texts& b, const std::string& what) {
  for (const auto& [x, y, kind] :
       {std::tuple{&a.json, &b.json, "JSON"}, std::tuple{&a.text, &b.text, "text"},
        std::tuple{&a.junit, &b.junit, "JUnit"}}) {
    if (*x == *y) continue;
    ADD_FAILURE() << what << ": the " << kind << " reports differ " << FirstDifference(*x, *y);
    return false;
  }
  return true;
}

Texts Serial(const RecordedRun& run) {
  Verifier v(run.ctx, false);
  Feed(run, v, 0, run.Lines());
  return Finish(v);
}

// Lines c where a part may start: the line before has the needles out (stitching off or the
// head retracted).
std::vector<int> SafeCuts(const RecordedRun& run) {
  std::vector<int> cuts;
  for (int c = 1; c < run.Lines(); ++c) {
    const trace::LineRecord& before = run.trace.lines[static_cast<std::size_t>(c - 1)];
    if (!before.stitching || before.head_retracted) cuts.push_back(c);
  }
  return cuts;
}

// The verifier of the part starting at line `from`: a warm-up of `warmup` lines, a reset,
// then the part's lines up to `to`.
std::unique_ptr<Verifier> Part(const RecordedRun& run, int from, int to, int warmup, bool marks,
                               std::string* carry_after_warmup = nullptr) {
  auto v = std::make_unique<Verifier>(run.ctx, marks);
  Feed(run, *v, from - warmup, from);
  v->ResetAccumulators();
  EXPECT_FALSE(v->SawAnything());
  if (carry_after_warmup) *carry_after_warmup = v->Carry();
  Feed(run, *v, from, to);
  return v;
}

// Cut once at every safe line: part A is the lines before it; B warms up on the `warmup`
// lines before it. Equal carries must give the serial report; a full warm-up always carries
// equal. Returns the number of cuts whose carries were equal.
int CheckEveryCut(const RecordedRun& run, const Texts& serial, int warmup) {
  int equal = 0;
  for (const int c : SafeCuts(run)) {
    Verifier a(run.ctx, false);
    Feed(run, a, 0, c);
    std::string carry;
    auto b = Part(run, c, run.Lines(), warmup, false, &carry);
    if (a.Carry() != carry) {
      EXPECT_LT(warmup, c) << "a full warm-up carries what the part before ends with, cut " << c;
      continue;
    }
    ++equal;
    a.Absorb(*b);
    if (!Same(Finish(a), serial, "cut before line index " + std::to_string(c))) return -1;
  }
  return equal;
}

// Parts starting at `starts` (the first is 0), each with a warm-up.
std::vector<std::unique_ptr<Verifier>> Parts(const RecordedRun& run, const std::vector<int>& starts,
                                             int warmup, bool marks) {
  std::vector<std::unique_ptr<Verifier>> parts;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const int to = i + 1 < starts.size() ? starts[i + 1] : run.Lines();
    parts.push_back(Part(run, starts[i], to, warmup, marks));
    // Each part's start carries what the part before ended with.
    if (i > 0) {
      std::string carry;
      Part(run, starts[i], starts[i], warmup, marks, &carry);
      EXPECT_EQ(carry, parts[i - 1]->Carry()) << "part " << i;
    }
  }
  return parts;
}

// Every `every`-th safe cut, from 0.
std::vector<int> Starts(const RecordedRun& run, std::size_t every) {
  std::vector<int> starts = {0};
  const std::vector<int> cuts = SafeCuts(run);
  for (std::size_t i = every / 2; i < cuts.size(); i += every) starts.push_back(cuts[i]);
  return starts;
}

// The parts merged in memory and through their partials (JSON text, parsed again, loaded into
// fresh verifiers) give the serial report.
void CheckParts(const RecordedRun& run, const Texts& serial, const std::vector<int>& starts) {
  ASSERT_GE(starts.size(), 3u);
  // In memory, with the stitch marks: merged marks are the serial verifier's.
  {
    auto parts = Parts(run, starts, run.Lines(), true);
    for (std::size_t i = 1; i < parts.size(); ++i) parts[0]->Absorb(*parts[i]);
    Verifier whole(run.ctx, true);
    Feed(run, whole, 0, run.Lines());
    ASSERT_EQ(parts[0]->StitchMarks().size(), whole.StitchMarks().size());
    for (std::size_t i = 0; i < whole.StitchMarks().size(); ++i) {
      EXPECT_EQ(parts[0]->StitchMarks()[i].severity, whole.StitchMarks()[i].severity) << i;
      EXPECT_EQ(parts[0]->StitchMarks()[i].position_mm, whole.StitchMarks()[i].position_mm) << i;
    }
    Same(Finish(*parts[0]), serial, std::to_string(starts.size()) + " parts");
  }
  // Through JSON: each partial round-trips exactly.
  auto parts = Parts(run, starts, 2, false);
  std::vector<std::unique_ptr<Verifier>> loaded;
  for (auto& p : parts) {
    p->CloseNeedleWindow();
    const std::string text = p->SavePartial().dump();
    auto v = std::make_unique<Verifier>(run.ctx, false);
    std::string error;
    ASSERT_TRUE(v->LoadPartial(nlohmann::json::parse(text), error)) << error;
    EXPECT_EQ(v->SavePartial().dump(), text);
    loaded.push_back(std::move(v));
  }
  for (std::size_t i = 1; i < loaded.size(); ++i) loaded[0]->Absorb(*loaded[i]);
  Same(Finish(*loaded[0]), serial, std::to_string(starts.size()) + " partials");
}

// Stitch blocks, each a seam of a plain stitch, a head turn with the needles in and back, a
// stitch whose V runs ahead of U, then stitching off and a traverse far too fast; one block
// out of reach and one beyond the rail's travel.
std::string ManyFindingsProgramme(int blocks) {
  std::ostringstream p;
  p << "%\nG21 G90\nT1 M6\nG0 X0 Y0 Z0 A0 B0 C-90 U0 V0\n";
  double u = 0, v = 0;
  for (int b = 0; b < blocks; ++b) {
    const double x = b % 2 == 0 ? 0.0 : 100.0;
    p << "M10\n";
    p << "G1 X" << x + 5 << " U" << (u += 5) << " V" << (v += 5) << " F1500\n";
    p << "G1 X" << x + 5 << " C-80 U" << (u += 5) << " V" << (v += 5) << "\n";
    p << "G1 X" << x + 10 << " C-90 U" << (u += 5) << " V" << (v += 5) << "\n";
    p << "G1 X" << x + 15 << " U" << (u += 5) << " V" << (v += 7) << "\n";
    p << "M11\n";
    if (b == blocks / 2) p << "G1 X5 Y3000 Z0 F1500\nG1 X" << x + 15 << " Y0 Z0\n";
    p << "G1 X" << (b % 2 == 0 ? 100 : 0) << " F300000\n";
  }
  p << "M30\n%\n";
  return p.str();
}

long ErrorsOf(const RecordedRun& run, const std::string& id, bool* truncated = nullptr) {
  Verifier v(run.ctx, false);
  Feed(run, v, 0, run.Lines());
  Report r;
  v.Finish(r);
  for (const RuleSummary& s : r.rules) {
    if (s.id != id) continue;
    if (truncated) *truncated = s.truncated;
    return s.errors + s.warnings;
  }
  return -1;
}

TEST(VerifierParts, ManyRulesWithFindingsMergeToTheSerialReport) {
  const std::unique_ptr<RecordedRun> run = Record("flat_straight", ManyFindingsProgramme(130), 5.0);
  Decorate(*run);
  run->ctx.declared_stitches = 321;  // not what it makes: program.stitch_count fires
  // Findings in many rules, and more than a rule keeps in some.
  bool truncated = false;
  EXPECT_GT(ErrorsOf(*run, "program.sync", &truncated), static_cast<long>(kMaxFindingsPerRule));
  EXPECT_TRUE(truncated);
  for (const char* id :
       {"needle.rotation_in_preform", "needle.side_force", "kin.joint_speed", "kin.reach",
        "program.stitch_count", "collision.head_mold", "collision.robot_cell",
        "collision.clearance", "kin.acceleration", "kin.torque", "dyn.tracking"}) {
    EXPECT_GT(ErrorsOf(*run, id), 0) << id;
  }
  const Texts serial = Serial(*run);
  const int cuts = static_cast<int>(SafeCuts(*run).size());
  ASSERT_GT(cuts, 120);
  EXPECT_EQ(CheckEveryCut(*run, serial, run->Lines()), cuts);
  // One line of warm-up (the line before the cut) carries all there is to carry, but after
  // the line out of reach (no joint state on it).
  EXPECT_GE(CheckEveryCut(*run, serial, 1), cuts - 2);
  CheckParts(*run, serial, Starts(*run, 7));
  CheckParts(*run, serial, Starts(*run, 1));
}

std::pair<std::string, double> PlanText(const Loaded& l, const scene::PathSpec& p,
                                        planner::Mode mode) {
  DiagnosticSink sink;
  planner::StitchPlanOptions opt;
  opt.mode = mode;
  auto pl = planner::StitchPathPlanner::Create(*l.scene, p, opt, sink);
  EXPECT_TRUE(pl.has_value());
  std::ostringstream out;
  planner::WriteStitchProgram(*pl, *l.scene, p.name, program::Dialect::Default(), out);
  return {out.str(), pl->StitchLengthMm()};
}

TEST(VerifierParts, PlannerProgrammesMergeToTheSerialReport) {
  for (const auto& [scene, mode] : {std::pair{"circle_8in", planner::Mode::kCoupled},
                                    std::pair{"arcs_planar", planner::Mode::kCoupled},
                                    std::pair{"cutout_slot", planner::Mode::kDecoupled},
                                    std::pair{"blade_demo", planner::Mode::kDecoupled}}) {
    const Loaded l = Load(scene);
    const auto [text, ls] = PlanText(l, l.scene->paths.front(), mode);
    const std::unique_ptr<RecordedRun> run = Record(scene, text, ls);
    const Texts serial = Serial(*run);
    const int cuts = static_cast<int>(SafeCuts(*run).size());
    SCOPED_TRACE(std::string(scene) + ", " + std::to_string(cuts) + " safe cuts");
    ASSERT_GE(cuts, 1);
    EXPECT_EQ(CheckEveryCut(*run, serial, run->Lines()), cuts);
    EXPECT_GT(CheckEveryCut(*run, serial, 2), 0);
    if (cuts >= 2) CheckParts(*run, serial, Starts(*run, 1));
  }
}

TEST(VerifierParts, ACarryTellsAShortWarmUpOrAnotherJointState) {
  const std::unique_ptr<RecordedRun> run = Record("flat_straight", ManyFindingsProgramme(6), 5.0);
  const std::vector<int> cuts = SafeCuts(*run);
  ASSERT_GT(cuts.size(), 4u);
  const int c = cuts[4];
  Verifier a(run->ctx, false);
  Feed(*run, a, 0, c);
  std::string full, none;
  Part(*run, c, c, c, false, &full);
  Part(*run, c, c, 0, false, &none);
  EXPECT_EQ(a.Carry(), full);
  EXPECT_NE(a.Carry(), none);  // no warm-up: no joint state, no line
  // The same warm-up with the last joint sample a hair off.
  Recorder& t = run->trace;
  trace::TraceSample* last = nullptr;
  for (int i = 0; i < c; ++i) {
    for (auto& s : t.samples[static_cast<std::size_t>(i)]) {
      if (trace::JointsUsable(s)) last = &s;
    }
  }
  ASSERT_NE(last, nullptr);
  last->joints[trace::kA1] += 1e-12;
  std::string moved;
  Part(*run, c, c, c, false, &moved);
  EXPECT_NE(a.Carry(), moved);
}

TEST(VerifierParts, LoadPartialRefusesWhatDoesNotFit) {
  const std::unique_ptr<RecordedRun> run = Record("flat_straight", ManyFindingsProgramme(3), 5.0);
  Verifier v(run->ctx, false);
  Feed(*run, v, 0, run->Lines());
  const nlohmann::json partial = v.SavePartial();
  std::string error;
  {
    nlohmann::json j = partial;
    j["format"] = "stitchsim-report";
    Verifier f(run->ctx, false);
    EXPECT_FALSE(f.LoadPartial(j, error));
    EXPECT_NE(error.find("format"), std::string::npos) << error;
  }
  {  // Another rule set: a header that declares its stitches adds program.stitch_count.
    RuleContext declared = run->ctx;
    declared.declared_stitches = 3;
    Verifier f(declared, false);
    EXPECT_FALSE(f.LoadPartial(partial, error));
    EXPECT_NE(error.find("rules"), std::string::npos) << error;
  }
  {  // Cut short.
    const std::string text = partial.dump();
    const auto cut = nlohmann::json::parse(text.substr(0, text.size() / 2), nullptr, false);
    Verifier f(run->ctx, false);
    EXPECT_FALSE(f.LoadPartial(cut, error));
    EXPECT_NE(error.find("cut short"), std::string::npos) << error;
  }
  {  // A rule's field missing.
    nlohmann::json j = partial;
    j["rules"][2]["summary"].erase("errors");
    Verifier f(run->ctx, false);
    EXPECT_FALSE(f.LoadPartial(j, error));
    EXPECT_NE(error.find("errors"), std::string::npos) << error;
    EXPECT_FALSE(f.SawAnything());
  }
  {  // Another scene (other limits, other name).
    const std::unique_ptr<RecordedRun> other =
        Record("circle_8in", "%\nG21 G90\nT1 M6\nM30\n%\n", 5.0);
    Verifier f(other->ctx, false);
    EXPECT_FALSE(f.LoadPartial(partial, error));
    EXPECT_NE(error.find("scene"), std::string::npos) << error;
  }
}

// A rule that records where it is told to (Rule::Record is the rule's own).
class RecordingRule : public Rule {
 public:
  RecordingRule() : Rule("test.record", "records what it is told", "mm") {}
  void At(int line, FindingSeverity severity = FindingSeverity::kError) {
    Record(severity, 1.0, 0.5, line, 0, "x", "line " + std::to_string(line), nullptr);
  }
};

TEST(VerifierParts, OneFindingPerLineUnderAndPastTheCap) {
  for (const bool past_cap : {false, true}) {
    RecordingRule r;
    long before = 0;
    if (past_cap) {
      for (int line = 1; line <= static_cast<int>(kMaxFindingsPerRule); ++line) r.At(line);
      before = static_cast<long>(kMaxFindingsPerRule);
    }
    r.At(1000, FindingSeverity::kWarning);
    r.At(1001);
    r.At(1000, FindingSeverity::kWarning);
    EXPECT_EQ(r.Summary().errors + r.Summary().warnings, before + 2) << past_cap;
    // A warning line that turns out an error counts as one error, kept or not.
    r.At(1000);
    EXPECT_EQ(r.Summary().errors, before + 2) << past_cap;
    EXPECT_EQ(r.Summary().warnings, 0) << past_cap;
    EXPECT_EQ(r.Summary().truncated, past_cap);
  }
}

TEST(VerifierParts, AfpRulesAreNotMerged) {
  const auto scene = testing::AfpScene(geom::MakePlane(4000, 4000));
  const process::ProcessModel model = process::MakeProcessModel(*scene, 5.0);
  trace::CellDescription cell;
  cell.max_velocities.setConstant(10.0);
  const RuleContext ctx{scene.get(), &cell, &model};
  const Eigen::Vector2d x(1, 0);
  const auto line = [&](int n, double u) {
    return testing::LayLine(n, testing::ToolAt(*scene->surface, Eigen::Vector2d(u, 0), x),
                            testing::ToolAt(*scene->surface, Eigen::Vector2d(u + 100, 0), x));
  };
  Verifier a(ctx, false), b(ctx, false), empty(ctx, false);
  a.OnLine(line(10, -200));
  b.OnLine(line(11, -100));
  EXPECT_THROW(a.SavePartial(), std::logic_error);
  EXPECT_THROW(a.ResetAccumulators(), std::logic_error);
  EXPECT_NE(a.Carry(), b.Carry());
  EXPECT_THROW(a.Absorb(b), std::logic_error);
  // A part that saw nothing merges either way.
  EXPECT_NO_THROW(a.Absorb(empty));
  Verifier c(ctx, false);
  EXPECT_NO_THROW(c.Absorb(a));
  Report merged, alone;
  c.Finish(merged);
  Verifier d(ctx, false);
  d.OnLine(line(10, -200));
  d.Finish(alone);
  EXPECT_EQ(ReportToJson(merged), ReportToJson(alone));
}

}  // namespace
}  // namespace stitchsim::verify
