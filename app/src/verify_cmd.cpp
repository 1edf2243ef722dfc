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
#include "pose_track.h"
#include "snapshots.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/progress.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/sim/dynamics.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/verifier.h"
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

// The programme's header against the scene it is verified on: a programme written for
// another scene or head is bad input (both names given), unless overridden on purpose.
bool HeaderFitsScene(const program::ProgramIdentity& id, const program::ProgramHeader& header,
                     const std::string& program_file, const scene::Scene& scene,
                     const std::string& scene_file, DiagnosticSink& sink) {
  bool ok = true;
  if (id.scene && *id.scene != scene.name) {
    sink.Error("program-scene-mismatch", {program_file, header.LineOf("scene"), 1},
               "the programme was written for scene '" + *id.scene + "' but " + scene_file +
                   " is scene '" + scene.name + "'; --allow-mismatch verifies it anyway");
    ok = false;
  }
  if (id.head && *id.head != scene.head.name) {
    sink.Error("program-head-mismatch", {program_file, header.LineOf("head"), 1},
               "the programme was written for head '" + *id.head + "' but scene '" + scene.name +
                   "' mounts '" + scene.head.name + "'; --allow-mismatch verifies it anyway");
    ok = false;
  }
  return ok;
}

// Passes the trace on and shows its progress (common/progress.h).
class ProgressSink : public sim::TraceSink {
 public:
  /// The serial run has no first pass: the total is unknown (counts and rate only).
  ProgressSink(sim::TraceSink& next, bool quiet)
      : next_(next), progress_("verify", "lines", 0.0, [&] {
          Progress::Options o;
          o.enabled = !quiet;
          o.plain_min_run_s = 1.0;  // a short run writes no progress into a log
          return o;
        }()) {}
  void OnLine(const sim::LineRecord& line) override {
    next_.OnLine(line);
    if (line.source_line > passed_) {
      progress_.Add(line.source_line - passed_);
      passed_ = line.source_line;
    }
  }
  void OnSample(const sim::TraceSample& s) override { next_.OnSample(s); }
  void Done() { progress_.Finish(); }

 private:
  sim::TraceSink& next_;
  Progress progress_;
  int passed_ = 0;  ///< programme lines passed
};

// Sends the trace to the verifier and, with --save-trace, to the trace file.
class TeeSink : public trace::TraceSink {
 public:
  TeeSink(trace::TraceSink& first, trace::TraceSink* second) : first_(first), second_(second) {}
  void OnLine(const trace::LineRecord& line) override {
    first_.OnLine(line);
    if (second_ != nullptr) second_->OnLine(line);
  }
  void OnSample(const trace::TraceSample& s) override {
    first_.OnSample(s);
    if (second_ != nullptr) second_->OnSample(s);
  }

 private:
  trace::TraceSink& first_;
  trace::TraceSink* second_;
};

// The --save-trace file, its header written: what was run and on what.
std::unique_ptr<trace::TraceFileWriter> OpenTrace(const VerifyArgs& a, const LoadedScene& ls,
                                                  const sim::CellSetup& cell,
                                                  const trace::CellDescription& description,
                                                  const program::ProgramIdentity& id,
                                                  double stitch_length) {
  trace::TraceFileHeader h;
  h.program_file = a.program;
  h.scene_name = ls.scene->name;
  h.head = ls.scene->head.name;
  h.stitch_length_mm = stitch_length;
  h.declared_stitches = id.stitches;
  h.ik_wrist_singularity_rad = cell.ik.wrist_singularity_rad;
  h.cell = description;
  h.fingerprints = SceneFingerprints(*ls.scene);
  std::string error;
  auto writer = trace::TraceFileWriter::Open(a.save_trace, h, error);
  if (!writer) PrintError("io-write", "--save-trace: " + error);
  return writer;
}

// The dynamic run's figures on stderr: physics time, wall time, real-time factor, worst lag.
void PrintDynamicsFigures(const sim::DynamicsFigures& f,
                          std::chrono::steady_clock::time_point started) {
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::fprintf(stderr,
               "dynamics: %.2f s of motion simulated in %.2f s (%.1fx real time), %ld samples "
               "tracked, largest tool lag %.4f mm on line %d\n",
               f.simulated_s, wall, wall > 0.0 ? f.simulated_s / wall : 0.0, f.samples,
               f.max_error_mm, f.max_error_line);
}

// The snapshots: the overview, a close-up per rule with errors, the AFP coverage maps.
int WriteSnapshots(const VerifySession& vs, const verify::Verifier& verifier,
                   const verify::Report& report, const std::string& dir) {
  return WriteSnapshotFolder(vs, verifier, report, dir);
}

// --html: the snapshots (into --snapshots' folder, or a scratch folder removed afterwards)
// read back, then the page.
int WriteHtml(const VerifyArgs& a, const VerifySession& vs, const verify::Report& report,
              const verify::Verifier& verifier, PoseTrack& poses) {
  namespace fs = std::filesystem;
  const bool scratch = a.snapshots.empty();
  const fs::path dir =
      scratch ? fs::temp_directory_path() / ("stitchsim-html-" + std::to_string(::getpid()))
              : fs::path(a.snapshots);
  if (scratch && WriteSnapshots(vs, verifier, report, dir.string()) != kExitOk) {
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
  poses.Thin(PointedLines(verifier), INT_MAX);
  in.report = &report;
  in.verifier = &verifier;
  in.scene = &vs.ls;
  in.poses = &poses;
  return WriteHtmlReport(a.html, in);
}

// The serial run (--dynamics, --save-trace, a programme read from a pipe): executor ->
// progress -> timing (time law, inverse dynamics) [-> physics] -> verifier, trace file.
int RunSerial(const VerifyArgs& a, VerifySession& vs, sim::ProgramInput& input,
              const program::ProgramIdentity& id, BoundedDiagnosticSink& diagnostics) {
  verify::Verifier verifier(vs.Rules(), !a.snapshots.empty() || !a.html.empty());
  PoseTrack poses(HtmlLimits{}.max_poses);
  PoseRecorder recorder(poses, &verifier);
  TeeSink rules(verifier, a.html.empty() ? nullptr : &recorder);
  std::unique_ptr<trace::TraceFileWriter> saved;
  if (!a.save_trace.empty()) {
    saved = OpenTrace(a, vs.ls, vs.cell, vs.description, id, vs.stitch_length_mm);
    if (!saved) return kExitBadInput;
  }
  TeeSink tee(rules, saved.get());
  std::optional<sim::DynamicsSink> physics;
  if (a.dynamics) physics.emplace(*vs.mj.physics, *vs.mj.physics_poses, tee);
  sim::TimingSink timing(*vs.mj.timing, *vs.ls.robot, vs.timing,
                         physics ? static_cast<trace::TraceSink&>(*physics) : tee);
  ProgressSink progress(timing, a.quiet);
  const auto started = std::chrono::steady_clock::now();
  const sim::ExecutionSummary run =
      sim::ExecuteProgram(vs.cell, *vs.model, input, vs.execute, diagnostics, progress);
  progress.Done();
  if (PrintDiagnostics(diagnostics) || !run.ok) return kExitBadInput;
  timing.Finish();
  if (physics) PrintDynamicsFigures(physics->Figures(), started);
  const trace::TraceFileSummary summary{run.lines, run.moves, run.time_s, timing.CycleTime()};
  if (saved) {
    if (std::string err = saved->Commit(summary); !err.empty()) {
      PrintError("io-write", "--save-trace: " + err);
      return kExitBadInput;
    }
  }
  verify::Report report = RunReport(a.program, a.scene, *vs.ls.scene, vs.stitch_length_mm, summary);
  verifier.Finish(report);
  if (WriteReports(report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  if (!a.snapshots.empty() && WriteSnapshots(vs, verifier, report, a.snapshots) != kExitOk) {
    return kExitBadInput;
  }
  if (!a.html.empty() && WriteHtml(a, vs, report, verifier, poses) != kExitOk) return kExitBadInput;
  return report.errors == 0 ? kExitOk : kExitFindings;
}

// The chunked run (sim/chunk.h, chunked_verify.h): the first pass on its own thread cuts the
// programme, `jobs` workers run the chunks, this thread merges them; or, with --shard, this
// process's share of the chunks into a partial result file.
int RunChunked(const VerifyArgs& a, VerifySession& vs, sim::ProgramInput& input,
               BoundedDiagnosticSink& diagnostics) {
  ChunkedInvocation inv;
  inv.program = a.program;
  inv.scene = a.scene;
  inv.dialect = a.dialect;
  inv.no_collision = a.no_collision;
  inv.allow_mismatch = a.allow_mismatch;
  inv.quiet = a.quiet;
  inv.stitch_marks = !a.snapshots.empty() || !a.html.empty();
  inv.chunk_poses = a.html.empty() ? 0 : 1024;
  inv.jobs = a.jobs;
  if (!a.shard.empty() && !ParseShard(a.shard, inv.shard, inv.shards)) return kExitBadInput;
  inv.part = a.part;
  inv.chunk_lines = a.chunk_lines;
  inv.warm_lines = a.warm_lines;
  ChunkedOutcome out;
  const int rc = RunChunkedVerify(inv, vs, input, diagnostics, out);
  if (rc != kExitOk || !a.shard.empty()) return rc;
  verify::Report report =
      RunReport(a.program, a.scene, *vs.ls.scene, vs.stitch_length_mm, out.summary);
  out.verifier->Finish(report);
  if (WriteReports(report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  if (!a.snapshots.empty() && WriteSnapshots(vs, *out.verifier, report, a.snapshots) != kExitOk) {
    return kExitBadInput;
  }
  if (!a.html.empty() && WriteHtml(a, vs, report, *out.verifier, out.poses) != kExitOk) {
    return kExitBadInput;
  }
  return report.errors == 0 ? kExitOk : kExitFindings;
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
  auto ls = LoadSceneAndRobot(a.scene);
  if (!ls) return kExitBadInput;
  const std::optional<program::Dialect> dialect = DialectOption(a.dialect);
  if (!dialect) return kExitBadInput;
  // The programme is read once, front to back (a pipe works): the header first, then the run.
  if (!ProgramInputOk(a.program)) return kExitBadInput;
  std::ifstream in(a.program, std::ios::binary);
  if (!in) {
    PrintError("io-missing-file", "cannot open programme " + a.program);
    return kExitBadInput;
  }
  BoundedDiagnosticSink diagnostics(100);
  sim::ProgramInput input(in, *dialect, a.program, diagnostics);
  const program::ProgramHeader& header = input.Header();
  const std::optional<program::ProgramIdentity> id =
      program::ReadIdentity(header, a.program, diagnostics);
  if (!id || (!a.allow_mismatch &&
              !HeaderFitsScene(*id, header, a.program, *ls->scene, a.scene, diagnostics))) {
    PrintDiagnostics(diagnostics);
    return kExitBadInput;
  }
  const double stitch_length = id->stitch_length_mm.value_or(ls->scene->nominal_stitch_length_mm);
  SessionOptions so;
  so.no_collision = a.no_collision;
  so.allow_mismatch = a.allow_mismatch;
  so.dynamics = a.dynamics;
  std::unique_ptr<VerifySession> vs =
      MakeSession(std::move(*ls), *dialect, stitch_length, id->stitches, so);
  if (!vs) return kExitBadInput;
  // Chunks reopen the programme by name: a regular file only.
  const bool serial =
      a.dynamics || !a.save_trace.empty() || !std::filesystem::is_regular_file(a.program);
  if (serial && !a.shard.empty()) {
    PrintError("cli-usage", "--shard needs the programme as a regular file");
    return kExitBadInput;
  }
  return serial ? RunSerial(a, *vs, input, *id, diagnostics)
                : RunChunked(a, *vs, input, diagnostics);
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
