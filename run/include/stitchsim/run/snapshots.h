#pragma once
// `verify --snapshots DIR`: the overview (always), a close-up per rule with errors chosen by
// the rule's close-up family (close_up.h), the AFP coverage maps, each picture with a title
// bar and a colour legend burned in, and snapshots.json saying what each picture shows
// (docs/report-format.md, "Snapshots").

#include <array>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/status.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

/// What the pictures of a finished run read.
struct SnapshotInputs {
  const LoadedScene* scene = nullptr;              ///< not owned; the scene and its robot
  const process::ProcessModel* process = nullptr;  ///< not owned; the needles (stitching)
  const trace::CellDescription* cell = nullptr;    ///< not owned; collision body names
  const verify::Verifier* verifier = nullptr;      ///< not owned; finished, with stitch marks
  const verify::Report* report = nullptr;          ///< not owned; the run's report (titles)
};

/// Writes the snapshot folder `dir` (created if missing). The scene model's diagnostics go
/// into `sink` (Status::InSink on an error); a folder or file that cannot be written
/// (io-write), a missing font (io-missing-file, before any picture), a joint the model lacks
/// (model-missing-joint) or a renderer that cannot be made (render-context) come back as the
/// Status's code and message.
Status WriteSnapshotFolder(const SnapshotInputs& in, const std::string& dir, DiagnosticSink& sink);

/// Writes coverage_ply<n>.png into `dir` for each ply afp.coverage measured (AfpCoveragePictures,
/// afp_coverage_picture.h; `scene`: the run's); io-write when a file cannot be written,
/// io-missing-file without the fonts.
Status WriteAfpCoverageSnapshots(const verify::Verifier& verifier, const scene::Scene& scene,
                                 const std::string& dir);

/// Writes laminate_thickness.png and laminate_fiber_angle.png into `dir`: the stack thickness
/// and the worst fibre-angle deviation the programme's plies laid, over (u, v) (verify::
/// LaminateMaps); nothing when nothing was laid; io-write / io-missing-file on failure.
Status WriteAfpLaminateSnapshots(const verify::Verifier& verifier, const std::string& dir);

/// The colour (RGBA in [0, 1]) of what a rule draws (verify::DrawnPoints label), on the
/// overview and in the HTML report: laid tows blue, gaps red, overlaps magenta.
std::array<float, 4> DrawnColour(const std::string& label);

}  // namespace stitchsim::run
