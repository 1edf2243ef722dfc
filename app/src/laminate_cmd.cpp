// `stitchsim plan laminate`: every ply of a scene laminate planned in stack order into one
// programme (and one tow CSV), written whole or not at all (docs/afp.md, "Laminates").
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "plan_progress.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/laminate_planner.h"

namespace stitchsim::app {
namespace {

struct PlanLaminateArgs {
  std::string scene;
  std::string laminate;
  std::string output;
  std::string tows_csv;
  int jobs = 0;        ///< 0: the number of cores
  bool quiet = false;  ///< no progress on stderr
};

// One line per ply of the stack, then the whole laminate.
void PrintLaminate(const scene::Scene& scene, const planner::LaminatePlan& plan, double wall_s,
                   const PlanLaminateArgs& a) {
  const double speed = scene.head.afp.layup_speed_mm_s;
  for (const planner::LaminatePly& p : plan.plies) {
    const planner::PlyPlan& q = p.plan;
    std::printf(
        "  ply %zu '%s' (%g deg, %.3f mm): %zu courses, %d tow pieces (%d adds, %d cuts), "
        "lay-up %.1f mm (%.1f s at %g mm/s); stagger shift %.2f mm (same-angle ply %d); "
        "thickness below %.3f..%.3f mm; min steering radius %.1f mm; max gap %.4f mm, max "
        "overlap %.4f mm; bare %.2f %%, doubled %.2f %%\n",
        p.stack_index + 1, q.ply_name.c_str(), q.angle_rad * 180.0 / kPi, p.thickness_mm,
        q.courses.size(), q.tow_segments, q.events / 2, q.events / 2, q.laid_length_mm,
        q.laid_length_mm / speed, speed, p.stagger_shift_mm, p.same_angle_index + 1, p.below_min_mm,
        p.below_max_mm, q.min_radius_mm, q.max_gap_mm, q.max_overlap_mm, q.bare_pct, q.doubled_pct);
    PrintTowPieceFixes(q, "    ");
    for (const auto& f : q.findings)
      std::printf("error[%s]: %s (the cell cannot lay this ply as planned)\n", f.code.c_str(),
                  f.message.c_str());
  }
  std::printf(
      "%s: laminate '%s' of %zu plies on %s: %d courses, %d tow pieces (%d adds, %d cuts), "
      "lay-up %.1f mm (%.1f s at %g mm/s); thickness up to %.3f mm (cell %.2f mm); planned in "
      "%.2f s -> %s%s%s\n",
      scene.name.c_str(), plan.laminate.c_str(), plan.plies.size(), scene.head.name.c_str(),
      plan.courses, plan.tow_segments, plan.events / 2, plan.events / 2, plan.laid_length_mm,
      plan.laid_length_mm / speed, speed, plan.max_thickness_mm, plan.thickness_cell_mm, wall_s,
      a.output.c_str(), a.tows_csv.empty() ? "" : ", ", a.tows_csv.c_str());
}

int RunPlanLaminate(const PlanLaminateArgs& a) {
  if (!OutputsDistinct({{"--output", a.output}, {"--tows-csv", a.tows_csv}})) return kExitBadInput;
  DiagnosticSink sink;
  auto scene = scene::LoadScene(a.scene, sink, SceneLoadOptions());
  if (PrintDiagnostics(sink) || !scene) return kExitBadInput;
  const scene::LaminateSpec* lam = nullptr;
  std::string names;
  for (const auto& l : scene->laminates) {
    if (l.name == a.laminate) lam = &l;
    names += (names.empty() ? "" : ", ") + l.name;
  }
  if (lam == nullptr) {
    sink.Error("plan-unknown-laminate", SourceLocation{a.scene, 1, 1},
               "scene '" + scene->name + "' has no laminate '" + a.laminate + "' (laminates: " +
                   (names.empty() ? "none; add a `laminates:` list, docs/scene-format.md" : names) +
                   ")");
    PrintDiagnostics(sink);
    return kExitBadInput;
  }
  const auto t0 = std::chrono::steady_clock::now();
  PlanProgressPrinter progress("plan laminate " + lam->name, "plies", a.quiet);
  planner::LaminatePlanOptions options;
  options.jobs = a.jobs;
  options.progress = progress.Callback();
  auto plan = planner::PlanLaminate(*scene, *lam, options, sink);
  progress.Finish();
  if (PrintDiagnostics(sink) || !plan) return kExitBadInput;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int written = WriteProgramAndCsv(
      a.output, a.tows_csv,
      [&](std::ostream& out) {
        planner::WriteLaminateProgram(*plan, *scene, program::Dialect::Default(), out);
      },
      [&](std::ostream& out) { planner::WriteLaminateTowsCsv(*plan, out); });
  if (written != kExitOk) return written;
  PrintLaminate(*scene, *plan, seconds, a);
  for (const auto& p : plan->plies)
    if (!p.plan.findings.empty()) return kExitFindings;
  return kExitOk;
}

}  // namespace

void AddPlanLaminateCommand(CLI::App& plan, int& exit_code) {
  auto a = std::make_shared<PlanLaminateArgs>();
  CLI::App* cmd = plan.add_subcommand(
      "laminate",
      "A scene laminate (`laminates:`): every ply of its stack planned (as `plan ply`), "
      "same-angle plies staggered, each ply lifted onto the thickness the plies below lay, "
      "into one programme in stack order. Exit 1 (programme written) when a ply fails the "
      "head's steering limit or afp.coverage; exit 2 on bad input (docs/afp.md)");
  cmd->add_option("--scene", a->scene, "Scene YAML file (AFP head, `laminates:`)")->required();
  cmd->add_option("--laminate", a->laminate, "Laminate name (the scene's `laminates:`)")
      ->required();
  cmd->add_option("-o,--output", a->output, "Programme file to write")->required();
  cmd->add_option("--tows-csv", a->tows_csv,
                  "Per ply (stack position), course, tow and laid segment: course length and "
                  "edge points, lifted onto the plies below (docs/afp.md)");
  cmd->add_option("--jobs,-j", a->jobs,
                  "Threads planning plies (default: the number of cores); the programme is the "
                  "same for any number")
      ->check(CLI::Range(0, 256));
  AddScenePathFlag(*cmd);
  AddQuietFlag(*cmd, a->quiet);
  cmd->callback([a, &exit_code] { exit_code = RunPlanLaminate(*a); });
}

}  // namespace stitchsim::app
