// `stitchsim plan stitch`: writes the stitching programme of one path of a scene.
// `stitchsim plan afp`: writes the programme of one fibre-placement course (docs/afp.md).
// `stitchsim plan raster`: constraint-aware raster of a large preform (docs/raster.md).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli_common.h"
#include "cli_options.h"
#include "commands.h"
#include "plan_progress.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/planner/plan_status.h"
#include "stitchsim/planner/raster_planner.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/incline_judge.h"

namespace stitchsim::app {
namespace {

struct PlanStitchArgs {
  std::string scene;
  std::string dialect;
  std::string path;
  std::string mode = "auto";
  std::optional<double> stitch_length_mm;  ///< unset: the scene's nominal
  std::string output;
  bool quiet = false;  ///< no progress on stderr
};

// A scene whose head stitches (diagnostics printed); nullptr otherwise.
std::unique_ptr<scene::Scene> LoadStitchingScene(const std::string& file) {
  DiagnosticSink sink;
  auto scene = scene::LoadScene(file, sink, SceneLoadOptions());
  if (PrintDiagnostics(sink) || !scene) return nullptr;
  if (const planner::PlanStatus s = planner::StitchingHeadStatus(*scene); !s.Ok()) {
    PrintError(s.code, file + ": " + s.message);
    return nullptr;
  }
  return scene;
}

// The scene's path named `name` (the first path when empty); reported (plan-unknown-path,
// with the names there are) and nullptr when there is none of that name.
const scene::PathSpec* PathOrReport(const scene::Scene& scene, const std::string& file,
                                    const std::string& name) {
  const planner::PathChoice choice = planner::ChoosePath(scene, name);
  if (!choice.status.Ok()) PrintError(choice.status.code, file + ": " + choice.status.message);
  return choice.path;
}

int RunPlanStitch(const PlanStitchArgs& a) {
  const std::optional<program::Dialect> dialect = DialectOption(a.dialect);
  if (!dialect) return kExitBadInput;
  DiagnosticSink sink;
  auto scene = LoadStitchingScene(a.scene);
  if (!scene) return kExitBadInput;
  const scene::PathSpec* path = PathOrReport(*scene, a.scene, a.path);
  if (path == nullptr) return kExitBadInput;
  planner::StitchPlanOptions options;
  options.mode = *planner::ParseMode(a.mode);
  if (a.stitch_length_mm) options.nominal_stitch_length_mm = *a.stitch_length_mm;
  PlanProgressPrinter progress("plan stitch", "stitches", a.quiet);
  options.progress = progress.Callback();
  auto planner = planner::StitchPathPlanner::Create(*scene, *path, options, sink);
  if (PrintDiagnostics(sink) || !planner) return kExitBadInput;
  // Streamed to a temporary file beside the output, renamed when complete: memory does not
  // grow with the programme, and a failed or interrupted run leaves nothing behind.
  std::string err;
  auto out = OutputFile::Open(a.output, err);
  if (!out) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  const planner::ProgramSummary s =
      planner::WriteStitchProgram(*planner, *scene, path->name, *dialect, out->Stream());
  progress.Finish();
  if (err = out->Commit(); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::printf(
      "%s: path '%s' on %s, %s mode: %d stitches of %.4f mm (nominal %.4f mm) over %.3f mm; "
      "%d decoupled, %d coupled; %ld motion lines; estimated cycle time %.1f s "
      "(stitching %.1f s, rotation and settle %.1f s) -> %s\n",
      scene->name.c_str(), path->name.c_str(), scene->head.name.c_str(),
      std::string(planner::ToString(s.mode)).c_str(), s.stitches, s.stitch_length_mm,
      s.nominal_stitch_length_mm, s.path_length_mm, s.decoupled, s.stitches - s.decoupled,
      s.motion_lines, s.time.Total(), s.time.stitching_s, s.time.rotation_s, a.output.c_str());
  return kExitOk;
}

// ---- plan afp ------------------------------------------------------------------------------

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

// ---- plan raster ---------------------------------------------------------------------------

struct PlanRasterArgs {
  std::string scene;
  std::string dialect;
  std::string strategy = "jump";
  int heads = 1;
  std::vector<int> out_of_service;
  std::string library;
  // Unset: the scene's `raster:` value, else the built-in default.
  std::optional<double> pitch_mm, row_spacing_mm, margin_mm;
  std::vector<double> region_mm;  // u_min v_min u_max v_max, mm
  std::string output;
  bool quiet = false;  ///< no progress on stderr
};

int RunPlanRaster(const PlanRasterArgs& a) {
  const std::optional<program::Dialect> dialect = DialectOption(a.dialect);
  if (!dialect) return kExitBadInput;
  DiagnosticSink sink;
  auto scene = LoadStitchingScene(a.scene);
  if (!scene) return kExitBadInput;
  planner::RasterOptions o = planner::RasterOptionsFor(*scene);
  o.strategy = *planner::ParseRasterStrategy(a.strategy);
  if (a.pitch_mm) o.pitch_mm = *a.pitch_mm;
  if (a.row_spacing_mm) o.row_spacing_mm = *a.row_spacing_mm;
  if (a.margin_mm) o.margin_mm = *a.margin_mm;
  o.heads = a.heads;
  o.out_of_service = a.out_of_service;
  if (a.region_mm.size() == 4) {
    o.region = Eigen::AlignedBox2d(Eigen::Vector2d(a.region_mm[0], a.region_mm[1]),
                                   Eigen::Vector2d(a.region_mm[2], a.region_mm[3]));
  }
  if (!a.library.empty()) {
    auto lib = planner::LoadUserCodeLibrary(a.library, *dialect, sink);
    if (PrintDiagnostics(sink) || !lib) return kExitBadInput;
    o.library = std::move(*lib);
  }
  // Streamed straight to a unique temporary file beside the output (OutputFile), renamed
  // when complete: memory does not grow with the programme, and a failed or interrupted run
  // leaves nothing behind.
  std::string err;
  auto out = OutputFile::Open(a.output, err);
  if (!out) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  PlanProgressPrinter progress("plan raster", "rows", a.quiet);
  o.progress = progress.Callback();
  const std::optional<planner::RasterSummary> s =
      planner::WriteRasterProgram(*scene, o, *dialect, out->Stream(), sink);
  progress.Finish();
  if (PrintDiagnostics(sink) || !s) return kExitBadInput;  // the temporary goes with `out`
  if (err = out->Commit(); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::string heads;
  for (std::size_t h = 0; h < s->head_stitches.size(); ++h) {
    heads += (h == 0 ? "" : ", ") + std::string("head ") + std::to_string(h + 1) + " " +
             std::to_string(s->head_stitches[h]);
  }
  std::printf(
      "%s: raster %s, pitch %.4f in, rows %.4f in apart: %ld stitches, %ld rows, %ld jumps, "
      "%ld regions, %ld user blocks; per head: %s; estimated time %.1f s (stitching %.1f s, "
      "traverse %.1f s) -> %s\n",
      scene->name.c_str(), a.strategy.c_str(), o.pitch_mm / kMmPerInch,
      o.row_spacing_mm / kMmPerInch, s->stitches, s->rows, s->jumps, s->bays, s->user_blocks,
      heads.c_str(), s->TotalS(), s->stitching_s, s->traverse_s, a.output.c_str());
  return kExitOk;
}

}  // namespace

void AddPlanCommand(CLI::App& app, int& exit_code) {
  CLI::App* plan = app.add_subcommand("plan", "Write robot programmes from a scene");
  plan->require_subcommand(1);
  auto args = std::make_shared<PlanStitchArgs>();
  CLI::App* cmd = plan->add_subcommand(
      "stitch", "A 3D stitch path (seed 000): coupled, decoupled or auto per stitch");
  cmd->add_option("--scene", args->scene, "Scene YAML file")->required();
  cmd->add_option("--path", args->path, "Path name (default: the scene's first path)");
  cmd->add_option("--mode", args->mode, "coupled | decoupled | auto")
      ->check(CLI::IsMember({"coupled", "decoupled", "auto"}));
  AddLengthOption(
      cmd, "--stitch-length", [args](double mm) { args->stitch_length_mm = mm; },
      LengthUnit::kMillimetre, LengthRange::kPositive, "Nominal stitch length",
      "the scene's stitch.nominal_length");
  cmd->add_option("-o,--output", args->output, "Programme file to write")->required();
  cmd->add_option("--dialect", args->dialect,
                  "Dialect YAML file (default: the built-in dialect, models/dialect/default.yaml)");
  AddScenePathFlag(*cmd);
  AddQuietFlag(*cmd, args->quiet);
  cmd->callback([args, &exit_code] { exit_code = RunPlanStitch(*args); });

  auto afp = std::make_shared<PlanAfpArgs>();
  CLI::App* afp_cmd = plan->add_subcommand(
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

  auto ras = std::make_shared<PlanRasterArgs>();
  CLI::App* ras_cmd = plan->add_subcommand(
      "raster", "A constraint-aware raster of a large preform (seed 001): jump or serpentine");
  ras_cmd->add_option("--scene", ras->scene, "Scene YAML file")->required();
  ras_cmd->add_option("--strategy", ras->strategy, "jump | serpentine")
      ->check(CLI::IsMember({"jump", "serpentine"}));
  ras_cmd->add_option("--heads", ras->heads, "Heads the regions are split among")
      ->check(CLI::PositiveNumber);
  ras_cmd
      ->add_option("--out-of-service", ras->out_of_service,
                   "Heads (1-based) that get nothing, comma separated")
      ->delimiter(',');
  ras_cmd->add_option("--library", ras->library, "User code library YAML (docs/raster.md)");
  // Raster lengths default to inches, the units of seed 001 and docs/raster.md.
  AddLengthOption(
      ras_cmd, "--pitch", [ras](double mm) { ras->pitch_mm = mm; }, LengthUnit::kInch,
      LengthRange::kPositive, "Stitch pitch along a row", "the scene's raster.pitch, else 0.1in");
  AddLengthOption(
      ras_cmd, "--row-spacing", [ras](double mm) { ras->row_spacing_mm = mm; }, LengthUnit::kInch,
      LengthRange::kPositive, "Row spacing", "the scene's raster.row_spacing, else 0.2in");
  AddLengthOption(
      ras_cmd, "--margin", [ras](double mm) { ras->margin_mm = mm; }, LengthUnit::kInch,
      LengthRange::kNonNegative, "Clearance around constraints beyond the head's keep-out",
      "the scene's raster.margin, else 0.5in");
  AddLengthListOption(ras_cmd, "--region", 4, ras->region_mm, LengthUnit::kInch,
                      "Stitch only u_min,v_min,u_max,v_max (part frame)");
  ras_cmd->add_option("-o,--output", ras->output, "Programme file to write")->required();
  ras_cmd->add_option("--dialect", ras->dialect, "Dialect YAML file (default: built-in)");
  AddScenePathFlag(*ras_cmd);
  AddQuietFlag(*ras_cmd, ras->quiet);
  ras_cmd->callback([ras, &exit_code] { exit_code = RunPlanRaster(*ras); });
  AddPlanPlyCommand(*plan, exit_code);
}

}  // namespace stitchsim::app
