// `stitchsim plan afp`: writes the programme of one fibre-placement course (docs/afp.md),
// at a given inclination or the first one whose programme verifies (`--incline auto`).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "cli_common.h"
#include "cli_options.h"
#include "commands.h"
#include "plan_progress.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/incline_judge.h"

namespace stitchsim::app {
namespace {

struct PlanAfpArgs {
  std::string scene;
  std::string path;
  double lay_angle_deg = std::nan("");  ///< NaN: not given
  std::string incline = "0";            ///< degrees, or "auto"
  double incline_max_deg = 30.0;
  double incline_step_deg = 1.0;
  double point_spacing_mm = 5.0;
  std::string output;
  std::string csv;
  bool quiet = false;  ///< no progress on stderr
};

std::string Deg(double rad) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3f", rad / kDeg);
  return buf;
}

/// Writes the programme (and the CSV), prints the summary and the over-travel findings.
int WriteAfpOutputs(const scene::Scene& scene, const planner::AfpPlan& plan, const PlanAfpArgs& a) {
  const int written = WriteProgramAndCsv(
      a.output, a.csv,
      [&](std::ostream& out) {
        planner::WriteAfpProgram(plan, scene, program::Dialect::Default(), out);
      },
      [&](std::ostream& out) { planner::WriteAfpCsv(plan, out); });
  if (written != kExitOk) return written;
  const auto& l = plan.limits;
  std::printf(
      "%s: AFP course '%s' on %s, incline %s deg: %zu points over %.3f mm; "
      "B %s..%s deg (travel %s deg, limits %s..%s), C %s..%s deg (travel %s deg, limits "
      "%s..%s), largest C step %s deg -> %s%s%s\n",
      scene.name.c_str(), plan.course_name.c_str(), scene.head.name.c_str(),
      Deg(plan.incline_rad).c_str(), plan.points.size(), plan.length_mm,
      Deg(plan.b_min_rad).c_str(), Deg(plan.b_max_rad).c_str(),
      Deg(plan.b_max_rad - plan.b_min_rad).c_str(), Deg(l.b_min_rad).c_str(),
      Deg(l.b_max_rad).c_str(), Deg(plan.c_min_rad).c_str(), Deg(plan.c_max_rad).c_str(),
      Deg(plan.c_max_rad - plan.c_min_rad).c_str(), Deg(l.c_min_rad).c_str(),
      Deg(l.c_max_rad).c_str(), Deg(plan.c_max_step_rad).c_str(), a.output.c_str(),
      a.csv.empty() ? "" : ", ", a.csv.c_str());
  for (const auto& f : plan.over_travel)
    std::printf("error[%s]: %s (the cell cannot run this course)\n", f.code.c_str(),
                f.message.c_str());
  return plan.over_travel.empty() ? kExitOk : kExitFindings;
}

int RunPlanAfpAuto(const PlanAfpArgs& a, const scene::PathSpec* path,
                   const planner::AfpPlanOptions& options) {
  planner::InclineSearchOptions search;
  search.max_deg = a.incline_max_deg;
  search.step_deg = a.incline_step_deg;
  // Progress: candidates judged, of all there are (the search stops at the first that passes).
  PlanProgressPrinter progress("plan afp", "inclinations", a.quiet);
  const double candidates = static_cast<double>(planner::InclineCandidates(search).size());
  int judged = 0;
  DiagnosticSink sink;
  const run::AutoInclineRun r = run::PlanAfpAutoIncline(
      a.scene, SceneLoadOptions(),
      path != nullptr ? std::optional<std::string>(path->name) : std::nullopt, options, search,
      [&](const planner::InclineCandidate& c) {
        progress.Update(++judged, candidates);
        if (c.pass) return;
        std::printf("incline %s deg: rejected: %s\n", Deg(c.incline_rad).c_str(),
                    c.failure.c_str());
        std::fflush(stdout);
      },
      sink);
  progress.Finish();
  PrintDiagnostics(sink);
  if (r.status != run::RunStatus::kOk) return kExitBadInput;
  if (!r.search.plan) {
    std::printf(
        "error[plan-afp-no-clear-incline]: no inclination within +-%.3f deg gives a programme "
        "that verifies with every rule (%zu tried; first failure: %s)\n",
        a.incline_max_deg, r.search.candidates.size(),
        run::FailuresByRule(r.search.candidates).c_str());
    return kExitFindings;
  }
  const planner::AfpPlan& plan = *r.search.plan;
  const planner::InclineCandidate& won = r.search.candidates.back();
  std::string feeds = "feed as planned";
  if (won.slowed_moves > 0) {
    char buf[128];
    std::snprintf(buf, sizeof(buf),
                  "feed lowered on %d moves, to %.1f %% of the layup speed at least",
                  won.slowed_moves, 100.0 * won.slowest_feed_fraction);
    feeds = buf;
  }
  std::printf(
      "incline auto: %s deg is the first inclination whose programme verifies with every rule "
      "(B travel %s deg, C travel %s deg; %s)\n",
      Deg(plan.incline_rad).c_str(), Deg(plan.b_max_rad - plan.b_min_rad).c_str(),
      Deg(plan.c_max_rad - plan.c_min_rad).c_str(), feeds.c_str());
  return WriteAfpOutputs(*r.loaded->scene, plan, a);
}

int RunPlanAfp(const PlanAfpArgs& a) {
  if (!OutputsDistinct({{"--output", a.output}, {"--csv", a.csv}})) return kExitBadInput;
  DiagnosticSink sink;
  auto scene = scene::LoadScene(a.scene, sink, SceneLoadOptions());
  if (PrintDiagnostics(sink) || !scene) return kExitBadInput;
  const bool by_lay_angle = !std::isnan(a.lay_angle_deg);
  const scene::PathSpec* path = nullptr;
  if (!by_lay_angle) {
    path = PathOrReport(*scene, a.scene, a.path);
    if (path == nullptr) return kExitBadInput;
  }
  planner::AfpPlanOptions options;
  if (by_lay_angle) options.lay_angle_rad = a.lay_angle_deg * kDeg;
  options.point_spacing_mm = a.point_spacing_mm;
  if (a.incline == "auto") return RunPlanAfpAuto(a, path, options);
  char* end = nullptr;
  const double incline_deg = std::strtod(a.incline.c_str(), &end);
  if (a.incline.empty() || end != a.incline.c_str() + a.incline.size() ||
      !std::isfinite(incline_deg)) {
    PrintError("plan-bad-incline",
               "--incline must be a number of degrees or 'auto', got '" + a.incline + "'");
    return kExitBadInput;
  }
  options.incline_rad = incline_deg * kDeg;
  auto plan = planner::PlanAfpCourse(*scene, path, options, sink);
  if (PrintDiagnostics(sink) || !plan) return kExitBadInput;
  return WriteAfpOutputs(*scene, *plan, a);
}

}  // namespace

void AddPlanAfpCommand(CLI::App& plan, int& exit_code) {
  auto afp = std::make_shared<PlanAfpArgs>();
  CLI::App* afp_cmd = plan.add_subcommand(
      "afp", "A fibre-placement course (seed 003): normal or inclined pressure, B/C per point");
  afp_cmd->add_option("--scene", afp->scene, "Scene YAML file (AFP head)")->required();
  auto* path_opt = afp_cmd->add_option(
      "--path", afp->path, "Course = this scene path (default: the first; not with --lay-angle)");
  afp_cmd
      ->add_option("--lay-angle", afp->lay_angle_deg,
                   "Course = straight (u, v) line at this angle to the u axis through the "
                   "domain centre, degrees (cylinder: helix, 0 = axial, 90 = hoop)")
      ->excludes(path_opt);
  afp_cmd->add_option("--incline", afp->incline,
                      "Head lean along the course, degrees (0 = normal pressure), or 'auto'");
  afp_cmd->add_option("--incline-max", afp->incline_max_deg, "auto: largest lean tried, degrees")
      ->check(CLI::Range(0.0, 89.0));
  afp_cmd->add_option("--incline-step", afp->incline_step_deg, "auto: lean step, degrees")
      ->check(CLI::PositiveNumber);
  AddLengthOption(
      afp_cmd, "--spacing", [afp](double mm) { afp->point_spacing_mm = mm; },
      LengthUnit::kMillimetre, LengthRange::kPositive, "Point spacing along the course", "5mm");
  afp_cmd->add_option("-o,--output", afp->output, "Programme file to write")->required();
  afp_cmd->add_option("--csv", afp->csv, "Per-point CSV (alpha, tangent, inclination, B, C)");
  AddScenePathFlag(*afp_cmd);
  AddQuietFlag(*afp_cmd, afp->quiet);
  afp_cmd->callback([afp, &exit_code] { exit_code = RunPlanAfp(*afp); });
}

}  // namespace stitchsim::app
