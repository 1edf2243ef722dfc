#pragma once
// `verify --snapshots DIR` (run/snapshots.h) from a run model: the pictures' inputs
// taken from it, the outcome printed.

#include <string>

#include "stitchsim/run/run_model.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {

/// Writes the snapshot folder for a finished run; kExitOk, or kExitBadInput (printed) when a
/// file cannot be written, a font is missing (io-missing-file) or the scene cannot be drawn.
int WriteSnapshotFolder(const run::RunModel& vs, const verify::Verifier& verifier,
                        const verify::Report& report, const std::string& dir);

}  // namespace stitchsim::app
