#pragma once
// A run's report header, the fingerprints of the files a run depends on, and writing the
// machine-readable reports (JSON, JUnit) as a set.

#include <string>
#include <vector>

#include "stitchsim/scene/scene.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::run {

/// Fingerprints of the files a run on `scene` depends on (scene, head spec, cell and head
/// models), in a fixed order; an unreadable file fingerprints as 0. A saved trace and a part
/// file carry them: recheck and report merge refuse one whose files changed.
std::vector<trace::FileFingerprint> SceneFingerprints(const scene::Scene& scene);

/// A report's header (rules not yet finished into it) for a run of `program_file` on `scene`,
/// read from `scene_file` (both names as given on the command line).
verify::Report RunReport(const std::string& program_file, const std::string& scene_file,
                         const scene::Scene& scene, double stitch_length_mm,
                         const trace::TraceFileSummary& run);

/// Writes the JSON and the JUnit reports of `report` to the paths given (empty: not asked
/// for), whole or not at all, as a set; "" or what failed.
std::string WriteReportFiles(const verify::Report& report, const std::string& json_path,
                             const std::string& junit_path);

}  // namespace stitchsim::run
