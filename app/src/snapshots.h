#pragma once
// `verify --snapshots DIR`: the overview (always), a close-up per rule with errors chosen by
// the rule's family (snapshot_families.h), the AFP coverage maps, each picture with a title
// bar and a colour legend burned in, and snapshots.json saying what each picture shows
// (docs/report-format.md, "Snapshots").

#include <array>
#include <string>

#include "stitchsim/run/run_model.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {

/// Writes the snapshot folder for a finished run; kExitOk, or kExitBadInput (printed) when a
/// file cannot be written, a font is missing (io-missing-file) or the scene cannot be drawn.
/// The colour of what a rule draws (verify::DrawnPoints label), on the overview and in the
/// HTML report: laid tows blue, gaps red, overlaps magenta.
std::array<float, 4> DrawnColour(const std::string& label);

int WriteSnapshotFolder(const run::RunModel& vs, const verify::Verifier& verifier,
                        const verify::Report& report, const std::string& dir);

}  // namespace stitchsim::app
