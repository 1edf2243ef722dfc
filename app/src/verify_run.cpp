// The run behind `stitchsim verify` and `stitchsim diff` (verify_run.h): scene, programme
// header, session, then the serial or the chunked run, into a finished report.

#include "verify_run.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "chunked_cmd.h"
#include "cli_common.h"
#include "commands.h"
#include "html_report.h"
#include "stitchsim/common/progress.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/sim/dynamics.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/trace/trace_file.h"

namespace stitchsim::app {
namespace {

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
std::unique_ptr<trace::TraceFileWriter> OpenTrace(const VerifyRunOptions& a, const LoadedScene& ls,
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

// The serial run (--dynamics, --save-trace, a programme read from a pipe): executor ->
// progress -> timing (time law, inverse dynamics) [-> physics] -> verifier, trace file.
int RunSerial(const VerifyRunOptions& a, VerifySession& vs, sim::ProgramInput& input,
              const program::ProgramIdentity& id, BoundedDiagnosticSink& diagnostics,
              VerifyRun& out) {
  auto verifier = std::make_unique<verify::Verifier>(vs.Rules(), a.keep_stitch_marks);
  out.poses = run::PoseTrack(HtmlLimits{}.max_poses);
  run::PoseRecorder recorder(out.poses, verifier.get());
  TeeSink rules(*verifier, a.record_poses ? &recorder : nullptr);
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
  out.report = RunReport(a.program, a.scene, *vs.ls.scene, vs.stitch_length_mm, summary);
  verifier->Finish(out.report);
  out.verifier = std::move(verifier);
  return kExitOk;
}

// The chunked run (sim/chunk.h, chunked_verify.h): the first pass on its own thread cuts the
// programme, `jobs` workers run the chunks, this thread merges them; or, with --shard, this
// process's share of the chunks into a partial result file.
int RunChunked(const VerifyRunOptions& a, VerifySession& vs, sim::ProgramInput& input,
               BoundedDiagnosticSink& diagnostics, VerifyRun& out) {
  ChunkedInvocation inv;
  inv.program = a.program;
  inv.scene = a.scene;
  inv.dialect = a.dialect;
  inv.no_collision = a.no_collision;
  inv.allow_mismatch = a.allow_mismatch;
  inv.quiet = a.quiet;
  inv.stitch_marks = a.keep_stitch_marks;
  inv.chunk_poses = a.record_poses ? 1024 : 0;
  inv.jobs = a.jobs;
  if (!a.shard.empty() && !ParseShard(a.shard, inv.shard, inv.shards)) return kExitBadInput;
  inv.part = a.part;
  inv.chunk_lines = a.chunk_lines;
  inv.warm_lines = a.warm_lines;
  ChunkedOutcome chunked;
  const int rc = RunChunkedVerify(inv, vs, input, diagnostics, chunked);
  if (rc != kExitOk || !a.shard.empty()) return rc;
  out.report = RunReport(a.program, a.scene, *vs.ls.scene, vs.stitch_length_mm, chunked.summary);
  chunked.verifier->Finish(out.report);
  out.verifier = std::move(chunked.verifier);
  out.poses = std::move(chunked.poses);
  return kExitOk;
}

}  // namespace

int RunVerification(const VerifyRunOptions& a, VerifyRun& out) {
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
  const int rc = serial ? RunSerial(a, *vs, input, *id, diagnostics, out)
                        : RunChunked(a, *vs, input, diagnostics, out);
  out.session = std::move(vs);
  return rc;
}

}  // namespace stitchsim::app
