// stitchsim: plan, execute and verify composite stitching / fiber placement programmes on an
// ISAAC-like cell. Exit codes: 0 success / pass, 1 findings, 2 bad input, 3 internal error.
// A bare `stitchsim` (or `stitchsim plan`) prints its help and exits 0.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "stitchsim/common/version.h"

int main(int argc, char** argv) {
  CLI::App app{
      "stitchsim: kinematic simulator and verification harness for composite-manufacturing "
      "robots (stitching and fiber-placement heads on a rail-mounted 6-axis arm)",
      "stitchsim"};
  // Every option's default value shows in --help (subcommands inherit this).
  app.option_defaults()->always_capture_default();
  app.require_subcommand(1);
  app.set_version_flag("--version", "stitchsim " + std::string(stitchsim::ToolVersion()));
  int exit_code = stitchsim::app::kExitOk;
  stitchsim::app::AddRenderCommand(app, exit_code);
  stitchsim::app::AddPlanCommand(app, exit_code);
  stitchsim::app::AddCheckCommand(app, exit_code);
  stitchsim::app::AddKinematicsCommands(app, exit_code);
  stitchsim::app::AddVerifyCommand(app, exit_code);
  stitchsim::app::AddReportCommand(app, exit_code);
  stitchsim::app::AddRecheckCommand(app, exit_code);
  stitchsim::app::AddExportStepCommand(app, exit_code);
  stitchsim::app::AddSequenceCommand(app, exit_code);
  stitchsim::app::AddDiffCommand(app, exit_code);
  // The subcommands run inside parse(). Bad input is a diagnostic and exit 2 there; an
  // exception reaching this far is a bug, reported as one (exit 3), never a crash or a verdict.
  try {
    const std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
    if (const auto early = stitchsim::app::PreDispatch(app, args)) return *early;
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : stitchsim::app::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "stitchsim: internal error: " << e.what() << '\n';
    return stitchsim::app::kExitInternal;
  } catch (...) {
    std::cerr << "stitchsim: internal error: unknown exception\n";
    return stitchsim::app::kExitInternal;
  }
  return exit_code;
}
