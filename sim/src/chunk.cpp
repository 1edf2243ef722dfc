// Chunked execution: the first pass and one chunk's run (chunk.h).
#include "stitchsim/sim/chunk.h"

#include <fstream>

#include "detail/executor_core.h"
#include "detail/start_branch.h"

namespace stitchsim::sim {

namespace {

// The executor options of a chunk: the first pass chose the start branch and checks the
// programme's end.
ExecuteOptions ChunkOptions(const ExecuteOptions& options) {
  ExecuteOptions o = options;
  o.choose_start_branch = false;
  o.require_program_end = false;
  return o;
}

// Cuts the programme while the first pass reads it: a warm point every chunk_lines lines, the
// cut at the first safe block boundary warm_lines after it.
class Cutter {
 public:
  Cutter(const ScanOptions& scan, bool cut, const std::function<void(const Chunk&)>& on_chunk)
      : scan_(scan), cut_(cut && scan.chunk_lines > 0), on_chunk_(on_chunk) {}

  // Before a block: a pending cut starts the next chunk here.
  void Before(const program::Block& block) {
    if (!cut_pending_) return;
    cut_pending_ = false;
    if (first_cut_line_ == 0) first_cut_line_ = block.source_line;
    if (have_open_) Emit(block.source_line);
    open_ = Chunk{};
    open_.index = next_index_++;
    open_.warm = pending_warm_;
    open_tracks_ = pending_tracks_;
    open_.first_line = block.source_line;
    have_open_ = true;
    warm_taken_ = false;
  }

  // After a block: where the state stands now may become the next warm point or a cut.
  void After(const program::Block& block, const program::ProgramReader& reader,
             const program::ModalState& state, const detail::Executor& exec, bool have_pose,
             const detail::StartBranchScan& branch) {
    if (!cut_) return;
    const int line = block.source_line;
    if (!warm_taken_ && line >= chunk_start_line_ + scan_.chunk_lines) {
      pending_warm_ = ResumePoint{};
      pending_warm_.programme_start = false;
      pending_warm_.reader = reader.Resume();
      pending_warm_.state = state.State();
      pending_warm_.previous = state.Previous();
      pending_warm_.time_s = exec.Time();
      pending_warm_.have_pose = have_pose;
      pending_tracks_ = branch.Positions();
      warm_taken_ = true;
      warm_line_ = line;
    }
    const program::MachineState& st = state.State();
    if (warm_taken_ && !cut_pending_ && line >= warm_line_ + scan_.warm_lines &&
        (!st.stitching || st.head_retracted)) {
      cut_pending_ = true;
      chunk_start_line_ = line;
    }
  }

  // At the end: every chunk in order, each seeded with the chosen start's track where it
  // stood at the chunk's warm point.
  int Finish(std::optional<JointVector> start, const detail::StartBranchScan& branch) {
    if (have_open_) Emit(0);
    Chunk first;
    first.index = 0;
    first.warm.programme_start = true;
    first.warm.joints = start;
    first.first_line = 1;
    first.end_line = first_cut_line_;
    on_chunk_(first);
    for (auto& [chunk, tracks] : cut_chunks_) {
      chunk.warm.joints = branch.At(tracks);
      on_chunk_(chunk);
    }
    return next_index_;
  }

 private:
  void Emit(int end_line) {
    open_.end_line = end_line;
    cut_chunks_.push_back({open_, open_tracks_});
  }

  const ScanOptions& scan_;
  bool cut_;
  const std::function<void(const Chunk&)>& on_chunk_;
  int chunk_start_line_ = 0;  ///< where the open chunk was cut (0: the programme start)
  bool warm_taken_ = false;
  int warm_line_ = 0;
  ResumePoint pending_warm_;
  std::vector<ArmJointVector> pending_tracks_, open_tracks_;  ///< the look-ahead's tracks
  std::vector<std::pair<Chunk, std::vector<ArmJointVector>>> cut_chunks_;
  bool cut_pending_ = false;
  Chunk open_;
  bool have_open_ = false;
  int next_index_ = 1;
  int first_cut_line_ = 0;  ///< chunk 1's first line (0: no cut)
};

// Discards everything (the first pass sends nothing anyway).
class NullSink final : public TraceSink {
 public:
  void OnLine(const LineRecord&) override {}
  void OnSample(const TraceSample&) override {}
};

}  // namespace

ScanResult ScanProgram(const CellSetup& cell, const process::ProcessModel& process,
                       ProgramInput& input, const ExecuteOptions& options, const ScanOptions& scan,
                       bool cut, DiagnosticSink& diagnostics,
                       const std::function<void(const Chunk&)>& on_chunk,
                       const std::function<void(std::uint64_t)>& progress) {
  const program::Dialect& dialect = input.dialect_;
  const std::string& file_name = input.file_name_;
  program::ProgramReader& reader = input.reader_;
  ScanResult result;
  NullSink null;
  program::ModalState state(dialect, file_name, diagnostics);
  detail::Executor exec(cell, process, dialect, options, null);
  detail::StartBranchScan branch(cell, program::EulerOrderOf(dialect));
  Cutter cutter(scan, cut, on_chunk);
  bool have_pose = false;
  long blocks = 0;
  detail::BlockHooks hooks;
  hooks.dry = true;
  hooks.before = [&](const program::Block& block) {
    cutter.Before(block);
    return true;
  };
  hooks.after = [&](const program::Block& block, const program::Step& step) {
    if (step.is_move) {
      have_pose = true;
      if (options.choose_start_branch) branch.Visit(state.State());
    }
    cutter.After(block, reader, state, exec, have_pose, branch);
    if (progress && ++blocks % 8192 == 0) progress(reader.BytesRead());
  };
  const std::size_t errors_before = diagnostics.ErrorCount();
  detail::RunBlocks(reader, state, exec, dialect, file_name, options, diagnostics, result.summary,
                    hooks);
  program::Block block;
  while (diagnostics.ErrorCount() == errors_before && reader.Next(block)) state.Update(block);
  if (diagnostics.ErrorCount() == errors_before && options.require_program_end &&
      !state.State().program_ended) {
    diagnostics.Error("exec-missing-program-end", {file_name, reader.LineCount(), 1},
                      "the programme stops here without its end (M" +
                          std::to_string(dialect.m.program_end) + "): cut short?");
  }
  ExecutionSummary& summary = result.summary;
  summary.lines = reader.LineCount();
  summary.header = reader.Header();
  summary.time_s = exec.Time();
  summary.ok = diagnostics.ErrorCount() == errors_before;
  result.bytes = reader.BytesRead();
  if (!summary.ok) return result;
  std::optional<JointVector> start;
  if (options.choose_start_branch) start = branch.Finish();
  result.chunks = cutter.Finish(start, branch);
  return result;
}

ExecutionSummary ExecuteChunk(const CellSetup& cell, const process::ProcessModel& process,
                              const program::Dialect& dialect, const std::string& path,
                              const Chunk& chunk, const ExecuteOptions& options,
                              DiagnosticSink& diagnostics, TraceSink& sink,
                              const ChunkHooks& hooks) {
  ExecutionSummary summary;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diagnostics.Error("io-missing-file", {path, 0, 0}, "cannot open programme " + path);
    return summary;
  }
  const ExecuteOptions o = ChunkOptions(options);
  const ResumePoint& warm = chunk.warm;
  std::optional<program::ProgramReader> reader;
  if (warm.programme_start) {
    reader.emplace(in, dialect, path, diagnostics);
    reader->ReadHeader();
  } else {
    in.seekg(static_cast<std::streamoff>(warm.reader.bytes));
    reader.emplace(in, dialect, path, diagnostics, warm.reader);
  }
  program::ModalState state(dialect, path, diagnostics);
  detail::Executor exec(cell, process, dialect, o, sink);
  if (!warm.programme_start) {
    state.Restore(warm.state, warm.previous);
    exec.Resume(warm.time_s, warm.state, warm.have_pose);
  }
  if (warm.joints) exec.SeedJoints(*warm.joints);
  bool at_first = false, at_end = false;
  const auto boundary = [&](int line) {
    if (!hooks.at_boundary) return;
    ChunkCarry carry;
    exec.AppendCarry(carry.executor);
    if (hooks.timing_carry) carry.timing = hooks.timing_carry();
    hooks.at_boundary(line, std::move(carry));
  };
  detail::BlockHooks run;
  run.before = [&](const program::Block& block) {
    if (!at_first && block.source_line >= chunk.first_line) {
      at_first = true;
      boundary(chunk.first_line);
    }
    if (chunk.end_line > 0 && !at_end && block.source_line >= chunk.end_line) {
      at_end = true;
      boundary(chunk.end_line);
    }
    return !(hooks.stop && hooks.stop());
  };
  const std::size_t errors_before = diagnostics.ErrorCount();
  detail::RunBlocks(*reader, state, exec, dialect, path, o, diagnostics, summary, run);
  summary.lines = reader->LineCount();
  summary.time_s = exec.Time();
  summary.ok = diagnostics.ErrorCount() == errors_before;
  return summary;
}

}  // namespace stitchsim::sim
