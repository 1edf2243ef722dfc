// `stitchsim plan stitch`: writes the stitching programme of one path of a scene.
// `stitchsim plan raster`: constraint-aware raster of a large preform (docs/raster.md).
// `plan afp` (plan_afp_cmd.cpp), `plan ply` (ply_cmd.cpp) and `plan laminate`
// (laminate_cmd.cpp) register under `plan` here.
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
#include "stitchsim/planner/plan_status.h"
#include "stitchsim/planner/raster_planner.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/dialect.h"

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

  AddPlanAfpCommand(*plan, exit_code);

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
  AddPlanLaminateCommand(*plan, exit_code);
}

}  // namespace stitchsim::app
