#pragma once
// A saved trace (verify --save-trace) checked again by every rule against the scene's (and a
// limits file's) limits, without simulating: the same report as the run that saved it when
// nothing changed.

#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/status.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::run {

/// What to recheck (file names as given on the command line: the report names them).
struct RecheckRequest {
  std::string trace;        ///< trace file from verify --save-trace
  std::string scene;        ///< scene YAML file the trace was saved on
  std::string limits;       ///< rule-limit overrides (YAML `limits:`); empty: none
  scene::LoadOptions load;  ///< how the scene is loaded (outside paths)
};

struct RecheckResult {
  RunStatus status = RunStatus::kBadInput;  ///< kOk / kFindings with `report` finished
  verify::Report report;                    ///< the rules' report of the saved trace
};

/// The trace was made on this scene and head, from the same files (trace-scene-mismatch,
/// trace-stale into `sink`; `trace_file` names the trace in the messages).
bool TraceFitsScene(const trace::TraceFileHeader& header, const std::string& trace_file,
                    const std::string& scene_file, const scene::Scene& scene, DiagnosticSink& sink);

/// The IK's singularity band, applied while simulating, is the one the trace was saved with
/// (trace-simulation-limit into `sink` otherwise: a limits file cannot move it).
bool SimulationLimitsUnchanged(const trace::TraceFileHeader& header, const LoadedScene& loaded,
                               const std::string& trace_file, DiagnosticSink& sink);

/// Loads the scene and the trace, checks they fit, re-runs the rules over the trace.
RecheckResult RecheckTrace(const RecheckRequest& request, DiagnosticSink& sink);

}  // namespace stitchsim::run
