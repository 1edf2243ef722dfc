#pragma once
// The stitchsim subcommands. Each Add*Command registers itself on the CLI11 app and writes
// its exit code into `exit_code` when it runs.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli_common.h"
#include "stitchsim/run/status.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {

void AddRenderCommand(CLI::App& app, int& exit_code);
void AddCheckCommand(CLI::App& app, int& exit_code);
void AddPlanCommand(CLI::App& app, int& exit_code);
/// `plan ply` under the `plan` command (ply_cmd.cpp).
void AddPlanPlyCommand(CLI::App& plan, int& exit_code);
void AddVerifyCommand(CLI::App& app, int& exit_code);
/// `report merge` (report_merge_cmd.cpp): the report of a run from its shards' parts.
void AddReportCommand(CLI::App& app, int& exit_code);
void AddKinematicsCommands(CLI::App& app, int& exit_code);
void AddRecheckCommand(CLI::App& app, int& exit_code);
void AddExportStepCommand(CLI::App& app, int& exit_code);
/// `sequence` (sequence_cmd.cpp): off-part course ordering of an AFP programme.
void AddSequenceCommand(CLI::App& app, int& exit_code);
/// `diff` (diff_cmd.cpp): two programmes verified and their reports compared.
void AddDiffCommand(CLI::App& app, int& exit_code);

/// Fingerprints of the files a run on `scene` depends on (scene, head spec, cell and head
/// models), for a saved trace: a recheck refuses a trace whose files changed.
std::vector<trace::FileFingerprint> SceneFingerprints(const scene::Scene& scene);
/// A report's header for a run of `program_file` on `scene` (read from `scene_file`).
verify::Report RunReport(const std::string& program_file, const std::string& scene_file,
                         const scene::Scene& scene, double stitch_length_mm,
                         const trace::TraceFileSummary& run);
/// Writes the JSON and JUnit reports (those asked for; whole or not at all, as a set) and
/// prints the text report; kExitOk, or kExitBadInput (printed) when a file cannot be written.
int WriteReports(const verify::Report& report, const std::string& json, const std::string& junit);
/// Prints a run function's diagnostics, then its error as PrintError does; the exit code:
/// kExitOk, kExitInternal for an "internal" error, else kExitBadInput.
int PrintRunOutcome(const DiagnosticSink& sink, const run::Status& status);

}  // namespace stitchsim::app
