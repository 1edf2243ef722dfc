#include "verify_cli.h"

#include <cstdio>
#include <iostream>

#include "cli_common.h"
#include "plan_progress.h"
#include "stitchsim/run/reports.h"

namespace stitchsim::app {
namespace {

// The dynamic run's figures on stderr: physics time, wall time, real-time factor, worst lag.
void PrintDynamicsFigures(const sim::DynamicsFigures& f, double wall) {
  std::fprintf(stderr,
               "dynamics: %.2f s of motion simulated in %.2f s (%.1fx real time), %ld samples "
               "tracked, largest tool lag %.4f mm on line %d\n",
               f.simulated_s, wall, wall > 0.0 ? f.simulated_s / wall : 0.0, f.samples,
               f.max_error_mm, f.max_error_line);
}

}  // namespace

int RunVerificationPrinted(const run::VerifyRunOptions& o, bool quiet, run::VerifyRun& out) {
  auto loaded = LoadSceneAndRobot(o.scene);
  if (!loaded) return kExitBadInput;
  const std::optional<program::Dialect> dialect = DialectOption(o.dialect);
  if (!dialect) return kExitBadInput;
  PlanProgressPrinter progress("verify", "lines", quiet);
  DiagnosticSink sink;
  out = run::RunVerification(o, std::move(*loaded), *dialect, progress.Callback(), sink);
  progress.Finish();
  PrintDiagnostics(sink);
  if (out.dynamics) PrintDynamicsFigures(*out.dynamics, out.dynamics_wall_s);
  if (!quiet && out.reruns > 0) {
    std::fprintf(stderr,
                 "verify: %d of %d chunks ran again (their warm-up did not rebuild the state "
                 "the chunk before ended with; first: %s)\n",
                 out.reruns, out.chunks, out.first_mismatch.c_str());
  }
  if (out.status == run::RunStatus::kOk && o.chunks.shards > 0) {
    std::fprintf(stderr, "verify: shard %d/%d: %zu of %d chunks, part written to %s\n",
                 o.chunks.shard, o.chunks.shards, out.part_chunks, out.chunks,
                 o.chunks.part.c_str());
  }
  return static_cast<int>(out.status);
}

int WriteReports(const verify::Report& report, const std::string& json, const std::string& junit) {
  if (std::string err = run::WriteReportFiles(report, json, junit); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  std::cout << verify::ReportToText(report);
  return kExitOk;
}

}  // namespace stitchsim::app
