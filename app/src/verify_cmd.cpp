// `stitchsim verify`: execute a programme on the cell, check every stitch and pose, report.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "chunked_cmd.h"
#include "cli_common.h"
#include "commands.h"
#include "html_report.h"
#include "snapshots.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/progress.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/sim/dynamics.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/verifier.h"
#include "verify_run.h"
#include "verify_session.h"

namespace stitchsim::app {
namespace {

struct VerifyArgs {
  std::string program;
  std::string dialect;
  std::string scene;
  std::string report_json;
  std::string junit;
  std::string snapshots;
  std::string html;
  std::string save_trace;
  bool no_collision = false;
  bool allow_mismatch = false;
  bool dynamics = false;
  bool quiet = false;
  int jobs = 0;       ///< 0: the number of cores
  std::string shard;  ///< "I/N"
  std::string part;   ///< --shard: the partial result file
  int chunk_lines = 16384;
  int warm_lines = 128;
};

// --html: the snapshots (into --snapshots' folder, or a scratch folder removed afterwards)
// read back, then the page.
int WriteHtml(const VerifyArgs& a, const VerifySession& vs, const verify::Report& report,
              const verify::Verifier& verifier, run::PoseTrack& poses) {
  namespace fs = std::filesystem;
  const bool scratch = a.snapshots.empty();
  const fs::path dir =
      scratch ? fs::temp_directory_path() / ("stitchsim-html-" + std::to_string(::getpid()))
              : fs::path(a.snapshots);
  if (scratch && WriteSnapshotFolder(vs, verifier, report, dir.string()) != kExitOk) {
    return kExitBadInput;
  }
  HtmlInputs in;
  std::vector<fs::path> pngs;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".png") pngs.push_back(e.path());
  }
  std::sort(pngs.begin(), pngs.end(), [](const fs::path& x, const fs::path& y) {
    const bool ox = x.filename() == "overview.png", oy = y.filename() == "overview.png";
    return ox != oy ? ox : x.filename() < y.filename();
  });
  for (const fs::path& png : pngs) {
    std::ifstream f(png, std::ios::binary);
    in.snapshots.emplace_back(png.filename().string(),
                              std::string(std::istreambuf_iterator<char>(f), {}));
  }
  if (scratch) fs::remove_all(dir, ec);
  poses.SetMaxPoses(HtmlLimits{}.max_poses);
  poses.Thin(run::PointedLines(verifier), INT_MAX);
  in.report = &report;
  in.verifier = &verifier;
  in.scene = &vs.ls;
  in.poses = &poses;
  return WriteHtmlReport(a.html, in);
}

int RunVerify(const VerifyArgs& a) {
  if (!OutputsDistinct({{"--report", a.report_json},
                        {"--junit", a.junit},
                        {"--save-trace", a.save_trace},
                        {"--html", a.html},
                        {"--part", a.part}})) {
    return kExitBadInput;
  }
  int shard = 0, shards = 0;
  if (!a.shard.empty() && !ParseShard(a.shard, shard, shards)) return kExitBadInput;
  if (a.shard.empty() != a.part.empty()) {
    PrintError("cli-usage", "--shard I/N and --part FILE go together");
    return kExitBadInput;
  }
  if (!a.shard.empty() && (a.dynamics || !a.save_trace.empty() || !a.report_json.empty() ||
                           !a.junit.empty() || !a.snapshots.empty() || !a.html.empty())) {
    PrintError("cli-usage",
               "--shard writes a partial result (--part) only: reports come from `stitchsim "
               "report merge`; --dynamics and --save-trace run in one process");
    return kExitBadInput;
  }
  VerifyRunOptions run_options;
  run_options.program = a.program;
  run_options.dialect = a.dialect;
  run_options.scene = a.scene;
  run_options.save_trace = a.save_trace;
  run_options.no_collision = a.no_collision;
  run_options.allow_mismatch = a.allow_mismatch;
  run_options.dynamics = a.dynamics;
  run_options.quiet = a.quiet;
  run_options.keep_stitch_marks = !a.snapshots.empty() || !a.html.empty();
  run_options.record_poses = !a.html.empty();
  run_options.jobs = a.jobs;
  run_options.shard = a.shard;
  run_options.part = a.part;
  run_options.chunk_lines = a.chunk_lines;
  run_options.warm_lines = a.warm_lines;
  VerifyRun run;
  const int rc = RunVerification(run_options, run);
  if (rc != kExitOk || !a.shard.empty()) return rc;
  if (WriteReports(run.report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  if (!a.snapshots.empty() &&
      WriteSnapshotFolder(*run.session, *run.verifier, run.report, a.snapshots) != kExitOk) {
    return kExitBadInput;
  }
  if (!a.html.empty() &&
      WriteHtml(a, *run.session, run.report, *run.verifier, run.poses) != kExitOk) {
    return kExitBadInput;
  }
  return run.report.errors == 0 ? kExitOk : kExitFindings;
}

}  // namespace

void AddVerifyCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<VerifyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "verify", "Execute a programme on the cell and check every stitch and pose");
  cmd->add_option("program", args->program, "Programme file (G-code)")->required();
  cmd->add_option("--scene", args->scene, "Scene YAML file")->required();
  cmd->add_option("--report", args->report_json, "Write the JSON report here");
  cmd->add_option("--junit", args->junit, "Write a JUnit XML report here");
  cmd->add_option("--dialect", args->dialect,
                  "Dialect YAML file (default: the built-in dialect, models/dialect/default.yaml)");
  cmd->add_option("--save-trace", args->save_trace,
                  "Write the trace the rules read here, to check again with `stitchsim recheck`");
  cmd->add_option("--snapshots", args->snapshots,
                  "Write overview.png and <rule>.png close-ups into this folder");
  cmd->add_option("--html", args->html,
                  "Write one self-contained HTML report here: findings, snapshots, a 3D view of "
                  "the cell posed at any line, plots of every rule along the programme");
  AddScenePathFlag(*cmd);
  cmd->add_flag("--no-collision", args->no_collision,
                "Skip the FCL collision checks (collision.* rules)");
  cmd->add_flag("--dynamics", args->dynamics,
                "Step MuJoCo's physics with the joint servos tracking the timed trajectory: the "
                "needle rules see the arm's lag, dyn.tracking reports it");
  cmd->add_option("--jobs,-j", args->jobs,
                  "Worker threads (default: the number of cores); reports are the same for any "
                  "number")
      ->check(CLI::Range(0, 256));
  cmd->add_option("--shard", args->shard,
                  "I/N: verify the I-th of N shares of the programme (I = 1..N) into --part; "
                  "`stitchsim report merge` makes the report (docs/ci.md)");
  cmd->add_option("--part", args->part, "--shard: write the partial result here");
  cmd->add_option("--chunk-lines", args->chunk_lines,
                  "--jobs/--shard: cut the programme at the first safe point after every this "
                  "many lines (reports do not depend on it; shards of one run must agree)")
      ->check(CLI::Range(1, 1 << 30));
  cmd->add_option("--warm-lines", args->warm_lines,
                  "--jobs/--shard: lines each chunk runs before its own to rebuild the state a "
                  "serial run carries there (a chunk that rebuilt it wrong runs again)")
      ->check(CLI::Range(0, 1 << 30));
  cmd->add_flag("--quiet,-q", args->quiet, "No progress on stderr");
  cmd->add_flag("--allow-mismatch", args->allow_mismatch,
                "Verify a programme whose header names another scene or head, or that mounts "
                "another head (T.. M6), on this scene's cell anyway");
  cmd->callback([args, &exit_code] { exit_code = RunVerify(*args); });
}

}  // namespace stitchsim::app
