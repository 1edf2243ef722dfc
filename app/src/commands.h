#pragma once
// The stitchsim subcommands. Each Add*Command registers itself on the CLI11 app and writes
// its exit code into `exit_code` when it runs.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli_common.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {

void AddRenderCommand(CLI::App& app, int& exit_code);
void AddCheckCommand(CLI::App& app, int& exit_code);
void AddPlanCommand(CLI::App& app, int& exit_code);
/// `plan afp` under the `plan` command (plan_afp_cmd.cpp).
void AddPlanAfpCommand(CLI::App& plan, int& exit_code);
/// `plan ply` under the `plan` command (ply_cmd.cpp).
void AddPlanPlyCommand(CLI::App& plan, int& exit_code);
/// `plan laminate` under the `plan` command (laminate_cmd.cpp).
void AddPlanLaminateCommand(CLI::App& plan, int& exit_code);
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

}  // namespace stitchsim::app
