// `stitchsim plan ply`: fills one ply of a scene with AFP courses and writes the programme
// (and the tow CSV) whole or not at all (docs/afp.md, "Plies, courses and tows").
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "plan_progress.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/laminate_planner.h"
#include "stitchsim/planner/ply_planner.h"

namespace stitchsim::app {
namespace {

struct PlanPlyArgs {
  std::string scene;
  std::vector<std::string> plies;
  std::string output;
  std::string tows_csv;
  bool quiet = false;  ///< no progress on stderr
};

// Prints one planned ply's summary line and its findings.
void PrintPly(const scene::Scene& scene, const planner::PlyPlan& plan, double wall_s,
              const PlanPlyArgs& a) {
  int laid_tows = 0;
  for (const auto& c : plan.courses)
    for (const auto& t : c.tows) laid_tows += t.laid.empty() ? 0 : 1;
  std::printf(
      "%s: ply '%s' (%g deg, coverage %g %%, %d tows of %.3f mm: head tows %d..%d) on %s: %zu "
      "courses, %d tows laid in %d segments, %d cut/add events, lay-up %.1f mm (%.1f s at %g "
      "mm/s); min steering radius %.1f mm (head limit %.1f mm); max gap %.4f mm, max overlap "
      "%.4f mm between courses; bare %.2f %%, doubled %.2f %%, laid outside %.2f %% of the ply; "
      "planned in %.2f s -> %s%s%s\n",
      scene.name.c_str(), plan.ply_name.c_str(), plan.angle_rad * 180.0 / kPi,
      plan.coverage * 100.0, plan.band.count, plan.layout.width_mm, plan.band.first,
      plan.band.Last(), scene.head.name.c_str(), plan.courses.size(), laid_tows, plan.tow_segments,
      plan.events, plan.laid_length_mm, plan.laid_length_mm / scene.head.afp.layup_speed_mm_s,
      scene.head.afp.layup_speed_mm_s, plan.min_radius_mm, scene.head.afp.min_steering_radius_mm,
      plan.max_gap_mm, plan.max_overlap_mm, plan.bare_pct, plan.doubled_pct, plan.laid_outside_pct,
      wall_s, a.output.c_str(), a.tows_csv.empty() ? "" : ", ", a.tows_csv.c_str());
  PrintTowPieceFixes(plan, "  ");
  for (const auto& f : plan.findings)
    std::printf("error[%s]: %s (the cell cannot lay this ply as planned)\n", f.code.c_str(),
                f.message.c_str());
}

int RunPlanPly(const PlanPlyArgs& a) {
  if (!OutputsDistinct({{"--output", a.output}, {"--tows-csv", a.tows_csv}})) return kExitBadInput;
  if (a.plies.size() > 1 && !a.tows_csv.empty()) {
    PrintError("plan-csv-one-ply", "--tows-csv takes one --ply (its rows are per course)");
    return kExitBadInput;
  }
  DiagnosticSink sink;
  auto scene = scene::LoadScene(a.scene, sink, SceneLoadOptions());
  if (PrintDiagnostics(sink) || !scene) return kExitBadInput;
  std::vector<const scene::PlySpec*> specs;
  for (const std::string& name : a.plies) {
    const scene::PlySpec* ply = scene->FindPly(name);
    if (ply == nullptr) {
      std::string names;
      for (const auto& p : scene->plies) names += (names.empty() ? "" : ", ") + p.name;
      sink.Error("plan-unknown-ply", SourceLocation{a.scene, 1, 1},
                 "scene '" + scene->name + "' has no ply '" + name +
                     "' (plies: " + (names.empty() ? "none" : names) + ")");
      PrintDiagnostics(sink);
      return kExitBadInput;
    }
    specs.push_back(ply);
  }
  std::vector<planner::PlyPlan> plans;
  std::vector<double> seconds;
  plans.reserve(specs.size());
  for (const scene::PlySpec* ply : specs) {
    const auto t0 = std::chrono::steady_clock::now();
    PlanProgressPrinter progress("plan ply " + ply->name, "courses", a.quiet);
    planner::PlyPlanOptions options;
    options.progress = progress.Callback();
    auto plan = planner::PlanPly(*scene, *ply, options, sink);
    progress.Finish();
    if (PrintDiagnostics(sink) || !plan) return kExitBadInput;
    plans.push_back(std::move(*plan));
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  // Several plies in one programme: each laid on the ones before it (as plan laminate).
  std::vector<planner::PlyPlan*> stack;
  std::vector<double> thickness;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    stack.push_back(&plans[i]);
    thickness.push_back(specs[i]->thickness_mm);
  }
  if (plans.size() > 1) planner::StackPlies(*scene->surface, stack, thickness, 2.0);
  std::vector<const planner::PlyPlan*> ptrs;
  for (const auto& p : plans) ptrs.push_back(&p);
  const int written = WriteProgramAndCsv(
      a.output, a.tows_csv,
      [&](std::ostream& out) {
        planner::WritePlyProgram(ptrs, *scene, program::Dialect::Default(), out);
      },
      [&](std::ostream& out) { planner::WritePlyTowsCsv(plans.front(), out); });
  if (written != kExitOk) return written;
  bool findings = false;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    PrintPly(*scene, plans[i], seconds[i], a);
    findings = findings || !plans[i].findings.empty();
  }
  return findings ? kExitFindings : kExitOk;
}

}  // namespace

void AddPlanPlyCommand(CLI::App& plan, int& exit_code) {
  auto a = std::make_shared<PlanPlyArgs>();
  CLI::App* cmd = plan.add_subcommand(
      "ply",
      "A fibre-placement ply (seed 002): courses offset across the ply, tows cut at its "
      "boundary. Exit 1 (programme written) when the plan fails the head's steering limit or "
      "afp.coverage; exit 2 when courses the ply needs would leave the surface (docs/afp.md)");
  cmd->add_option("--scene", a->scene, "Scene YAML file (AFP head, `plies:`)")->required();
  cmd->add_option("--ply", a->plies,
                  "Ply name (the scene's `plies:`); repeat it to write several plies into one "
                  "programme, laid in the order given")
      ->required();
  cmd->add_option("-o,--output", a->output, "Programme file to write")->required();
  cmd->add_option("--tows-csv", a->tows_csv,
                  "Per course, tow and laid segment: course length and edge points (docs/afp.md)");
  AddScenePathFlag(*cmd);
  AddQuietFlag(*cmd, a->quiet);
  cmd->callback([a, &exit_code] { exit_code = RunPlanPly(*a); });
}

}  // namespace stitchsim::app
