#pragma once
// What `verify`, `diff`, `recheck` and `report merge` print around a run (run/verify_run.h):
// the scene and dialect loaded, the run's progress, diagnostics and notes on stderr, the text
// report on stdout.

#include <string>

#include "stitchsim/run/verify_run.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::app {

/// Loads the scene and the dialect, runs the programme with progress on stderr (none when
/// `quiet`) and prints what the run reports; kExitOk with `out` filled (a shard: the part
/// written), or kExitBadInput / kExitInternal with the diagnostics printed.
int RunVerificationPrinted(const run::VerifyRunOptions& options, bool quiet, run::VerifyRun& out);

/// Writes the JSON and JUnit reports (those asked for; whole or not at all, as a set) and
/// prints the text report; kExitOk, or kExitBadInput (printed) when a file cannot be written.
int WriteReports(const verify::Report& report, const std::string& json, const std::string& junit);

}  // namespace stitchsim::app
