// The run behind `stitchsim verify` and `stitchsim diff` (verify_run.h): programme header,
// run model, then the serial or the chunked run, into a finished report.
#include "stitchsim/run/verify_run.h"

#include <chrono>
#include <filesystem>
#include <fstream>

#include "stitchsim/common/files.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/run/reports.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/trace/trace_file.h"

namespace stitchsim::run {
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

// Passes the trace on and counts the programme lines passed for the progress (the serial
// run has no first pass: the total is unknown), told every kProgressLines lines and at the end.
class ProgressSink : public sim::TraceSink {
 public:
  static constexpr int kProgressLines = 256;
  ProgressSink(sim::TraceSink& next, const RunProgress& progress)
      : next_(next), progress_(progress) {}
  void OnLine(const sim::LineRecord& line) override {
    next_.OnLine(line);
    if (line.source_line > passed_) {
      passed_ = line.source_line;
      if (passed_ - told_ >= kProgressLines) Tell();
    }
  }
  void OnSample(const sim::TraceSample& s) override { next_.OnSample(s); }
  void Tell() {
    if (progress_ && passed_ > told_) progress_(passed_, 0.0);
    told_ = passed_;
  }

 private:
  sim::TraceSink& next_;
  const RunProgress& progress_;
  int passed_ = 0;  ///< programme lines passed
  int told_ = 0;    ///< lines passed when the progress was last told
};

// Sends the trace to the verifier and, with a saved trace, to the trace file.
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

// The saved trace's file, its header written: what was run and on what.
std::unique_ptr<trace::TraceFileWriter> OpenTrace(const VerifyRunOptions& a, const RunModel& m,
                                                  const program::ProgramIdentity& id,
                                                  DiagnosticSink& sink) {
  trace::TraceFileHeader h;
  h.program_file = a.program;
  h.scene_name = m.loaded.scene->name;
  h.head = m.loaded.scene->head.name;
  h.stitch_length_mm = m.stitch_length_mm;
  h.declared_stitches = id.stitches;
  h.ik_wrist_singularity_rad = m.cell.ik.wrist_singularity_rad;
  h.cell = m.description;
  h.fingerprints = SceneFingerprints(*m.loaded.scene);
  std::string error;
  auto writer = trace::TraceFileWriter::Open(a.save_trace, h, error);
  if (!writer) ToolError(sink, "io-write", "--save-trace: " + error);
  return writer;
}

// The serial run (dynamics, a saved trace, a programme read from a pipe): executor ->
// progress -> timing (time law, inverse dynamics) [-> physics] -> verifier, trace file.
RunStatus RunSerial(const VerifyRunOptions& a, const RunModel& m, sim::ProgramInput& input,
                    const program::ProgramIdentity& id, DiagnosticSink& diagnostics,
                    const RunProgress& progress, DiagnosticSink& sink, VerifyRun& out) {
  RunData data = MakeRunData(m);
  auto verifier = std::make_unique<verify::Verifier>(m.Rules(), a.keep_stitch_marks);
  out.poses = PoseTrack(a.max_poses);
  PoseRecorder recorder(out.poses, verifier.get());
  TeeSink rules(*verifier, a.record_poses ? &recorder : nullptr);
  std::unique_ptr<trace::TraceFileWriter> saved;
  if (!a.save_trace.empty()) {
    saved = OpenTrace(a, m, id, sink);
    if (!saved) return RunStatus::kBadInput;
  }
  TeeSink tee(rules, saved.get());
  std::optional<sim::DynamicsSink> physics;
  if (a.run.dynamics) physics.emplace(*data.physics, *data.physics_poses, tee);
  sim::TimingSink timing(*data.timing, *m.loaded.robot, m.timing,
                         physics ? static_cast<trace::TraceSink&>(*physics) : tee);
  ProgressSink progress_sink(timing, progress);
  const auto started = std::chrono::steady_clock::now();
  const sim::ExecutionSummary run =
      sim::ExecuteProgram(m.cell, *m.process, input, data.execute, diagnostics, progress_sink);
  progress_sink.Tell();
  if (Forward(diagnostics, sink) || !run.ok) return RunStatus::kBadInput;
  timing.Finish();
  if (physics) {
    out.dynamics = physics->Figures();
    out.dynamics_wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  const trace::TraceFileSummary summary{run.lines, run.moves, run.time_s, timing.CycleTime()};
  if (saved) {
    if (std::string err = saved->Commit(summary); !err.empty()) {
      ToolError(sink, "io-write", "--save-trace: " + err);
      return RunStatus::kBadInput;
    }
  }
  out.report = RunReport(a.program, a.scene, *m.loaded.scene, m.stitch_length_mm, summary);
  verifier->Finish(out.report);
  out.verifier = std::move(verifier);
  return RunStatus::kOk;
}

// The chunked run (chunked_verify.h): the whole programme's merged verifier finished into the
// report; or, with a shard, this process's part written.
RunStatus RunChunked(const VerifyRunOptions& a, const RunModel& m, sim::ProgramInput& input,
                     DiagnosticSink& diagnostics, const RunProgress& progress, DiagnosticSink& sink,
                     VerifyRun& out) {
  ChunkedOptions o;
  o.program = a.program;
  o.scene = a.scene;
  o.dialect = a.dialect;
  o.no_collision = a.run.no_collision;
  o.allow_mismatch = a.run.allow_mismatch;
  o.stitch_marks = a.keep_stitch_marks;
  o.chunk_poses = a.record_poses ? 1024 : 0;
  o.plan = a.chunks;
  ChunkedOutcome chunked = RunChunkedVerify(o, m, input, diagnostics, progress, sink);
  out.chunks = chunked.chunks;
  out.reruns = chunked.reruns;
  out.first_mismatch = chunked.first_mismatch;
  out.part_chunks = chunked.part_chunks;
  if (chunked.status != RunStatus::kOk || a.chunks.shards > 0) return chunked.status;
  out.report = RunReport(a.program, a.scene, *m.loaded.scene, m.stitch_length_mm, chunked.summary);
  chunked.verifier->Finish(out.report);
  out.verifier = std::move(chunked.verifier);
  out.poses = std::move(chunked.poses);
  return RunStatus::kOk;
}

}  // namespace

VerifyRun RunVerification(const VerifyRunOptions& a, LoadedScene loaded,
                          const program::Dialect& dialect, const RunProgress& progress,
                          DiagnosticSink& sink) {
  VerifyRun out;
  // The programme is read once, front to back (a pipe works): the header first, then the run.
  if (std::string err = CheckStreamInput(a.program); !err.empty()) {
    ToolError(sink, "io-missing-file", err);
    return out;
  }
  std::ifstream in(a.program, std::ios::binary);
  if (!in) {
    ToolError(sink, "io-missing-file", "cannot open programme " + a.program);
    return out;
  }
  BoundedDiagnosticSink diagnostics(100);
  sim::ProgramInput input(in, dialect, a.program, diagnostics);
  const program::ProgramHeader& header = input.Header();
  const std::optional<program::ProgramIdentity> id =
      program::ReadIdentity(header, a.program, diagnostics);
  if (!id || (!a.run.allow_mismatch &&
              !HeaderFitsScene(*id, header, a.program, *loaded.scene, a.scene, diagnostics))) {
    Forward(diagnostics, sink);
    return out;
  }
  const double stitch_length = loaded.scene->StitchLengthMm(id->stitch_length_mm);
  out.model = MakeRunModel(std::move(loaded), dialect, stitch_length, id->stitches, a.run, sink);
  if (!out.model) return out;
  // Chunks reopen the programme by name: a regular file only.
  const bool serial =
      a.run.dynamics || !a.save_trace.empty() || !std::filesystem::is_regular_file(a.program);
  if (serial && a.chunks.shards > 0) {
    ToolError(sink, "cli-usage", "--shard needs the programme as a regular file");
    return out;
  }
  out.status = serial ? RunSerial(a, *out.model, input, *id, diagnostics, progress, sink, out)
                      : RunChunked(a, *out.model, input, diagnostics, progress, sink, out);
  return out;
}

}  // namespace stitchsim::run
