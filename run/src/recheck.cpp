#include "stitchsim/run/recheck.h"

#include <memory>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/run/reports.h"
#include "stitchsim/scene/limits_file.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

// Limit changes go through a limits file, never through edited scene files: geometry and IK
// are baked into the trace.
bool TraceFitsScene(const trace::TraceFileHeader& h, const std::string& trace_file,
                    const std::string& scene_file, const scene::Scene& scene,
                    DiagnosticSink& sink) {
  if (h.scene_name != scene.name || h.head != scene.head.name) {
    ToolError(sink, "trace-scene-mismatch",
              trace_file + " was saved on scene '" + h.scene_name + "' with head '" + h.head +
                  "', but " + scene_file + " is scene '" + scene.name + "' with head '" +
                  scene.head.name + "': run `stitchsim verify` on this scene instead");
    return false;
  }
  const std::vector<trace::FileFingerprint> now = SceneFingerprints(scene);
  for (const trace::FileFingerprint& was : h.fingerprints) {
    const trace::FileFingerprint* same_role = nullptr;
    for (const auto& f : now) {
      if (f.role == was.role) same_role = &f;
    }
    if (same_role == nullptr || same_role->fnv1a != was.fnv1a) {
      ToolError(sink, "trace-stale",
                trace_file + ": the " + was.role + " (" +
                    (same_role != nullptr ? same_role->path : was.path) +
                    ") changed since the trace was saved: run `stitchsim verify --save-trace` "
                    "again (to change only limits, keep the files and pass --limits)");
      return false;
    }
  }
  return true;
}

bool SimulationLimitsUnchanged(const trace::TraceFileHeader& h, const LoadedScene& loaded,
                               const std::string& trace_file, DiagnosticSink& sink) {
  const sim::CellSetup cell = sim::MakeCellSetup(*loaded.robot, *loaded.scene);
  if (cell.ik.wrist_singularity_rad == h.ik_wrist_singularity_rad) return true;
  ToolError(sink, "trace-simulation-limit",
            "kin.singularity a5_min_deg is applied by the IK while simulating, so " + trace_file +
                " (saved with another value) cannot be rechecked with it: run `stitchsim "
                "verify` with the new limit");
  return false;
}

RecheckResult RecheckTrace(const RecheckRequest& a, DiagnosticSink& sink) {
  RecheckResult out;
  std::string error;
  const std::unique_ptr<trace::TraceFileReader> reader =
      trace::TraceFileReader::Open(a.trace, error);
  if (!reader) {
    ToolError(sink, "trace-bad-file", error);
    return out;
  }
  const trace::TraceFileHeader& h = reader->Header();
  std::optional<LoadedScene> loaded = LoadScene(a.scene, a.load, sink);
  if (!loaded || !TraceFitsScene(h, a.trace, a.scene, *loaded->scene, sink)) return out;
  if (!a.limits.empty()) {
    DiagnosticSink limits_sink;
    const bool ok = scene::ApplyLimitsFile(a.limits, *loaded->scene, limits_sink);
    if (Forward(limits_sink, sink) || !ok) return out;
  }
  if (!SimulationLimitsUnchanged(h, *loaded, a.trace, sink)) return out;
  const process::ProcessModel model = process::MakeProcessModel(*loaded->scene, h.stitch_length_mm);
  verify::RuleContext ctx{loaded->scene.get(), &h.cell, &model};
  ctx.declared_stitches = h.declared_stitches;
  verify::Verifier verifier(ctx, false);
  trace::TraceFileSummary run;
  if (!reader->Replay(verifier, run, error)) {
    ToolError(sink, "trace-bad-file", error);
    return out;
  }
  out.report = RunReport(h.program_file, a.scene, *loaded->scene, h.stitch_length_mm, run);
  verifier.Finish(out.report);
  out.status = out.report.errors == 0 ? RunStatus::kOk : RunStatus::kFindings;
  return out;
}

}  // namespace stitchsim::run
