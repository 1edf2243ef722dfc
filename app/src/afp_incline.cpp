// `plan afp --incline auto`: every candidate judged by the real executor and verifier.
#include "afp_incline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
const char* const kJointSpeed = "kin.joint_speed";

// The verdict of a programme text with every rule, as `stitchsim verify --scene` gives it.
struct Judgement {
  verify::Report report;
  std::string error;  // the programme did not execute (never read as a verdict)
};

Judgement Judge(const LoadedScene& ls, sim::CollisionWorld& world, const std::string& text) {
  Judgement out;
  const program::Dialect& dialect = program::Dialect::Default();
  BoundedDiagnosticSink diagnostics(10);
  std::istringstream in(text);
  sim::ProgramInput input(in, dialect, "candidate.nc", diagnostics);
  const std::optional<program::ProgramIdentity> id =
      program::ReadIdentity(input.Header(), "candidate.nc", diagnostics);
  const double stitch_length = id && id->stitch_length_mm ? *id->stitch_length_mm
                                                          : ls.scene->nominal_stitch_length_mm;
  const sim::CellSetup cell = sim::MakeCellSetup(*ls.robot, *ls.scene);
  const process::ProcessModel model = process::MakeProcessModel(*ls.scene, stitch_length);
  const trace::CellDescription cell_description = sim::DescribeCell(*ls.robot, &world);
  verify::RuleContext ctx{ls.scene.get(), &cell_description, &model};
  sim::ExecuteOptions options = sim::ExecuteOptionsFor(*ls.scene);
  options.collision = &world;
  verify::Verifier verifier(ctx, false);
  const sim::ExecutionSummary run =
      sim::ExecuteProgram(cell, model, input, options, diagnostics, verifier);
  if (!run.ok || diagnostics.HasErrors()) {
    out.error = diagnostics.Diagnostics().empty()
                    ? std::string("the candidate programme did not execute")
                    : FormatDiagnostic(diagnostics.Diagnostics().front());
    return out;
  }
  out.report.lines = run.lines;
  out.report.moves = run.moves;
  verifier.Finish(out.report);
  return out;
}

// The error finding on the earliest line (rules in report order at equal lines), as
// "<rule> at line N: <message>", with how many other errors there are.
std::string FirstFailure(const verify::Report& r) {
  const verify::Finding* first = nullptr;
  long errors = 0;
  for (const auto& rule : r.rules) {
    errors += rule.errors;
    for (const auto& f : rule.findings) {
      if (f.severity != verify::FindingSeverity::kError) continue;
      if (first == nullptr || f.line < first->line) first = &f;
      break;  // findings are in line order
    }
  }
  if (first == nullptr) return "errors without findings";
  std::string out = first->rule + " at line " + std::to_string(first->line) + ": " + first->message;
  if (errors > 1) out += " (" + std::to_string(errors - 1) + " more errors)";
  return out;
}

// Programme line -> index of the course point its move ends at (moves in order = points).
std::map<int, std::size_t> PointLines(const std::string& text) {
  DiagnosticSink sink;
  std::map<int, std::size_t> out;
  std::size_t point = 0;
  for (const auto& b : program::ParseString(text, program::Dialect::Default(), "c.nc", sink)) {
    if (b.motion != program::Motion::kNone) out[b.source_line] = point++;
  }
  return out;
}

// Lowers the feed of every move kin.joint_speed flags so its worst joint lands at the target
// fraction of the limit. False (with the reason) when a flagged line is not a feed move.
bool LowerFeeds(const verify::RuleSummary& speed, const std::string& text, double target,
                planner::AfpPlan& plan, std::string& why) {
  std::map<int, double> worst_pct;  // line -> worst joint speed, % of its maximum
  for (const auto& f : speed.findings) {
    if (f.severity != verify::FindingSeverity::kError) continue;
    worst_pct[f.line] = std::max(worst_pct[f.line], f.value);
  }
  const std::map<int, std::size_t> points = PointLines(text);
  const double limit_pct = speed.error_limit.value_or(100.0);
  for (const auto& [line, pct] : worst_pct) {
    const auto at = points.find(line);
    if (at == points.end() || at->second == 0 || at->second >= plan.points.size()) {
      why = std::string(kJointSpeed) + " at line " + std::to_string(line) +
            ", which is not a feed move: its speed cannot be lowered";
      return false;
    }
    plan.points[at->second].feed_fraction *= target * limit_pct / pct;
  }
  return !worst_pct.empty();
}

bool OnlyJointSpeedFails(const verify::Report& r) {
  for (const auto& rule : r.rules) {
    if (rule.errors > 0 && rule.id != kJointSpeed) return false;
  }
  return true;
}

const verify::RuleSummary* RuleOf(const verify::Report& r, const std::string& id) {
  for (const auto& rule : r.rules) {
    if (rule.id == id) return &rule;
  }
  return nullptr;
}

// Judges one planned candidate, lowering feeds where only the joint speed fails. Fills the
// verdict; returns false when the programme could not be judged (`error`).
bool JudgeCandidate(const LoadedScene& ls, sim::CollisionWorld& world,
                    const InclineSearchOptions& search, planner::AfpPlan& plan, InclineCandidate& c,
                    std::string& error) {
  if (!plan.over_travel.empty()) {
    c.failure = plan.over_travel.front().code + ": " + plan.over_travel.front().message;
    return true;
  }
  for (int round = 0; round <= search.max_feed_rounds; ++round) {
    std::ostringstream text;
    planner::WriteAfpProgram(plan, *ls.scene, program::Dialect::Default(), text);
    const Judgement j = Judge(ls, world, text.str());
    if (!j.error.empty()) {
      error = j.error;
      return false;
    }
    c.slowed_moves = 0;
    c.slowest_feed_fraction = 1.0;
    for (const auto& p : plan.points) {
      if (p.feed_fraction < 1.0) ++c.slowed_moves;
      c.slowest_feed_fraction = std::min(c.slowest_feed_fraction, p.feed_fraction);
    }
    if (j.report.errors == 0) {
      c.pass = true;
      c.failure.clear();
      return true;
    }
    c.failure = FirstFailure(j.report);
    if (!OnlyJointSpeedFails(j.report)) return true;
    if (round == search.max_feed_rounds) {
      c.failure += " (still, after lowering the feed " + std::to_string(round) + " times)";
      return true;
    }
    std::string why;
    if (!LowerFeeds(*RuleOf(j.report, kJointSpeed), text.str(), search.feed_target_fraction, plan,
                    why)) {
      if (!why.empty()) c.failure = why;
      return true;
    }
  }
  return true;
}

}  // namespace

std::vector<double> InclineCandidates(const InclineSearchOptions& search) {
  const int steps = static_cast<int>(std::floor(search.max_deg / search.step_deg + 1e-9));
  std::vector<double> out{0.0};
  for (int k = 1; k <= steps; ++k) {
    out.push_back(k * search.step_deg * kDegToRad);
    out.push_back(-k * search.step_deg * kDegToRad);
  }
  return out;
}

InclineSearchResult SearchAfpIncline(
    const LoadedScene& ls, sim::CollisionWorld& world, const scene::PathSpec* path,
    planner::AfpPlanOptions options, const InclineSearchOptions& search, DiagnosticSink& sink,
    const std::function<void(const InclineCandidate&)>& on_candidate) {
  InclineSearchResult out;
  for (double incline_rad : InclineCandidates(search)) {
    options.incline_rad = incline_rad;
    auto plan = planner::PlanAfpCourse(*ls.scene, path, options, sink);
    if (!plan || sink.HasErrors()) {
      out.error = "the course could not be planned";
      return out;
    }
    InclineCandidate c;
    c.incline_rad = incline_rad;
    std::string error;
    if (!JudgeCandidate(ls, world, search, *plan, c, error)) {
      char deg[32];
      std::snprintf(deg, sizeof(deg), "%.3f", incline_rad / kDegToRad);
      out.error = std::string("incline ") + deg + " deg: " + error;
      return out;
    }
    out.candidates.push_back(c);
    if (on_candidate) on_candidate(c);
    if (c.pass) {
      out.plan = std::move(plan);
      return out;
    }
  }
  return out;
}

}  // namespace stitchsim::app
