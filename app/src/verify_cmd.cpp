// `stitchsim verify`: execute a programme on the cell, check every stitch and pose, report.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <climits>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_common.h"
#include "commands.h"
#include "html_report.h"
#include "snapshots.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/run/verify_run.h"
#include "stitchsim/verify/verifier.h"
#include "verify_cli.h"

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

// "I/N" with 1 <= I <= N (printed error otherwise).
bool ParseShard(const std::string& text, int& shard, int& shards) {
  const std::size_t slash = text.find('/');
  try {
    if (slash != std::string::npos) {
      std::size_t used_i = 0, used_n = 0;
      shard = std::stoi(text.substr(0, slash), &used_i);
      shards = std::stoi(text.substr(slash + 1), &used_n);
      if (used_i == slash && used_n == text.size() - slash - 1 && shards >= 1 && shard >= 1 &&
          shard <= shards && shards <= 100000) {
        return true;
      }
    }
  } catch (const std::exception&) {
  }
  PrintError("cli-usage", "--shard " + text + ": expected I/N with 1 <= I <= N (e.g. 3/8)");
  return false;
}

// --html: the snapshots (into --snapshots' folder, or a scratch folder removed afterwards)
// read back, then the page.
int WriteHtml(const VerifyArgs& a, const run::RunModel& vs, const verify::Report& report,
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
  in.scene = &vs.loaded;
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
  run::VerifyRunOptions o;
  o.program = a.program;
  o.dialect = a.dialect;
  o.scene = a.scene;
  o.save_trace = a.save_trace;
  o.run.no_collision = a.no_collision;
  o.run.allow_mismatch = a.allow_mismatch;
  o.run.dynamics = a.dynamics;
  o.keep_stitch_marks = !a.snapshots.empty() || !a.html.empty();
  o.record_poses = !a.html.empty();
  o.max_poses = HtmlLimits{}.max_poses;
  o.chunks = {a.jobs, shard, shards, a.part, a.chunk_lines, a.warm_lines};
  run::VerifyRun run;
  const int rc = RunVerificationPrinted(o, a.quiet, run);
  if (rc != kExitOk || !a.shard.empty()) return rc;
  if (WriteReports(run.report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  if (!a.snapshots.empty() &&
      WriteSnapshotFolder(*run.model, *run.verifier, run.report, a.snapshots) != kExitOk) {
    return kExitBadInput;
  }
  if (!a.html.empty() &&
      WriteHtml(a, *run.model, run.report, *run.verifier, run.poses) != kExitOk) {
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
