// `stitchsim recheck`: a saved trace (`verify --save-trace`) checked again against the scene's
// (and --limits') limits, without simulating. The same reports as `verify`, byte for byte when
// nothing changed.
#include <CLI/CLI.hpp>

#include "cli_common.h"
#include "commands.h"
#include "stitchsim/run/recheck.h"
#include "verify_cli.h"

namespace stitchsim::app {
namespace {

struct RecheckArgs {
  std::string trace;
  std::string scene;
  std::string limits;
  std::string report_json;
  std::string junit;
};

int RunRecheck(const RecheckArgs& a) {
  if (!OutputsDistinct({{"--report", a.report_json}, {"--junit", a.junit}})) return kExitBadInput;
  run::RecheckRequest request{a.trace, a.scene, a.limits, SceneLoadOptions()};
  DiagnosticSink sink;
  const run::RecheckResult r = run::RecheckTrace(request, sink);
  PrintDiagnostics(sink);
  if (r.status == run::RunStatus::kBadInput) return kExitBadInput;
  if (WriteReports(r.report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  return static_cast<int>(r.status);
}

}  // namespace

void AddRecheckCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RecheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "recheck",
      "Check a saved trace (verify --save-trace) again with the scene's or new limits, without "
      "simulating");
  cmd->add_option("trace", args->trace, "Trace file written by verify --save-trace")->required();
  cmd->add_option("--scene", args->scene, "Scene YAML file the trace was saved on")->required();
  cmd->add_option("--limits", args->limits,
                  "Rule-limit overrides (a YAML file with a `limits:` map, docs/scene-format.md)");
  cmd->add_option("--report", args->report_json, "Write the JSON report here");
  cmd->add_option("--junit", args->junit, "Write a JUnit XML report here");
  AddScenePathFlag(*cmd);
  cmd->callback([args, &exit_code] { exit_code = RunRecheck(*args); });
}

}  // namespace stitchsim::app
