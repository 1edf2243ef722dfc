// `plan afp --incline auto` (incline_judge.h): every candidate judged by the real executor and
// verifier.
#include "stitchsim/run/incline_judge.h"

#include <algorithm>
#include <map>
#include <sstream>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {
namespace {

const char* const kJointSpeed = "kin.joint_speed";

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

// The verdict of a verified report, as the search reads it.
planner::InclineVerdict VerdictOf(const verify::Report& r) {
  planner::InclineVerdict v;
  v.pass = r.errors == 0;
  if (v.pass) return v;
  v.first_failure = FirstFailure(r);
  v.joint_speed_rule = kJointSpeed;
  v.only_joint_speed_fails = true;
  for (const auto& rule : r.rules) {
    if (rule.errors > 0 && rule.id != kJointSpeed) v.only_joint_speed_fails = false;
    if (rule.id != kJointSpeed) continue;
    v.joint_speed_limit_pct = rule.error_limit.value_or(100.0);
    for (const auto& f : rule.findings) {
      if (f.severity != verify::FindingSeverity::kError) continue;
      v.joint_speed_pct[f.line] = std::max(v.joint_speed_pct[f.line], f.value);
    }
  }
  return v;
}

// The verdict of a programme text with every rule, as `stitchsim verify --scene` gives it.
planner::InclineVerdict Judge(const LoadedScene& ls, sim::CollisionWorld& world,
                              const std::string& text) {
  planner::InclineVerdict out;
  const program::Dialect& dialect = program::Dialect::Default();
  BoundedDiagnosticSink diagnostics(10);
  auto failed = [&] {
    out.error = diagnostics.Diagnostics().empty()
                    ? std::string("the candidate programme did not execute")
                    : FormatDiagnostic(diagnostics.Diagnostics().front());
    return out;
  };
  std::istringstream in(text);
  sim::ProgramInput input(in, dialect, "candidate.nc", diagnostics);
  const std::optional<program::ProgramIdentity> id =
      program::ReadIdentity(input.Header(), "candidate.nc", diagnostics);
  if (!id) return failed();
  const double stitch_length = ls.scene->StitchLengthMm(id->stitch_length_mm);
  const sim::CellSetup cell = sim::MakeCellSetup(*ls.robot, *ls.scene);
  const process::ProcessModel model = process::MakeProcessModel(*ls.scene, stitch_length);
  const trace::CellDescription cell_description = sim::DescribeCell(*ls.robot, &world);
  verify::RuleContext ctx{ls.scene.get(), &cell_description, &model};
  sim::ExecuteOptions options = sim::ExecuteOptionsFor(*ls.scene);
  options.collision = &world;
  verify::Verifier verifier(ctx, false);
  const sim::ExecutionSummary run =
      sim::ExecuteProgram(cell, model, input, options, diagnostics, verifier);
  if (!run.ok || diagnostics.HasErrors()) return failed();
  verify::Report report;
  report.lines = run.lines;
  report.moves = run.moves;
  verifier.Finish(report);
  return VerdictOf(report);
}

}  // namespace

planner::InclineJudge VerifyJudge(const LoadedScene& loaded, sim::CollisionWorld& world) {
  return [&loaded, &world](const std::string& text) { return Judge(loaded, world, text); };
}

AutoInclineRun PlanAfpAutoIncline(
    const std::string& scene_file, const scene::LoadOptions& load,
    const std::optional<std::string>& path_name, const planner::AfpPlanOptions& options,
    const planner::InclineSearchOptions& search,
    const std::function<void(const planner::InclineCandidate&)>& on_candidate,
    DiagnosticSink& sink) {
  AutoInclineRun out;
  out.loaded = LoadScene(scene_file, load, sink);
  if (!out.loaded) return out;
  const scene::Scene& scene = *out.loaded->scene;
  DiagnosticSink world_sink;
  auto world = sim::CollisionWorld::Create(scene, *out.loaded->robot, world_sink);
  if (Forward(world_sink, sink) || !world) return out;
  const scene::PathSpec* path = path_name ? scene.FindPath(*path_name) : nullptr;
  DiagnosticSink search_sink;
  out.search = planner::SearchAfpIncline(
      scene, path, options, search, VerifyJudge(*out.loaded, *world), search_sink, on_candidate);
  if (Forward(search_sink, sink)) return out;
  if (!out.search.error.empty()) {
    ToolError(sink, "plan-incline-check", "--incline auto: " + out.search.error);
    return out;
  }
  out.status = RunStatus::kOk;
  return out;
}

std::string FailuresByRule(const std::vector<planner::InclineCandidate>& candidates) {
  std::map<std::string, int> by_rule;  // first failing rule -> candidates
  for (const auto& c : candidates) {
    std::string rule = c.failure.substr(0, c.failure.find(' '));
    if (!rule.empty() && rule.back() == ':') rule.pop_back();
    ++by_rule[rule];
  }
  std::string why;
  for (const auto& [rule, n] : by_rule) {
    why += (why.empty() ? "" : ", ") + rule + " on " + std::to_string(n);
  }
  return why;
}

}  // namespace stitchsim::run
