#pragma once
// Chunked execution (verify --jobs, --shard; docs/ci.md): a cheap first pass reads the whole
// programme (parser, modal state, the executor's line clock, the start-branch look-ahead) and
// cuts it into chunks at safe points; each chunk then runs on its own (any thread, any
// process) from a warm-up that rebuilds the state a serial run carries there. What a chunk
// carries across its boundaries is compared as bytes (Carry): equal bytes at a boundary mean
// the chunk after it saw exactly what a serial run sees.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/executor.h"

namespace stitchsim::sim {

/// Where the execution of a programme can resume: between two blocks.
struct ResumePoint {
  bool programme_start = true;  ///< the very beginning (the rest is unused)
  program::ReaderResume reader;
  program::MachineState state;     ///< modal state after the last block read
  program::MachineState previous;  ///< ... and before it
  double time_s = 0.0;             ///< the executor's clock there (programmed speeds), s
  bool have_pose = false;          ///< a move came before
  /// Seeds the executor's joint continuity: at the programme start the start branch (exact);
  /// elsewhere the chosen start's look-ahead track there (the line ends only: a guess of the
  /// branch the warm-up refines).
  std::optional<JointVector> joints;
};

/// One chunk: the run starts at `warm` and counts from the block on `first_line` up to (not
/// including) the block on `end_line`; what comes before first_line is the warm-up.
struct Chunk {
  int index = 0;
  ResumePoint warm;
  int first_line = 1;  ///< source line of the chunk's first block (a safe point)
  int end_line = 0;    ///< the next chunk's first_line; 0: the programme's end
};

struct ScanOptions {
  /// Cut at the first safe point after every this many lines (0: do not cut).
  int chunk_lines = 16384;
  /// Each chunk's warm-up: at least this many lines before its first line.
  int warm_lines = 128;
};

struct ScanResult {
  ExecutionSummary summary;  ///< lines, moves, time_s (the executor's clock), header, ok
  int chunks = 0;
  std::uint64_t bytes = 0;        ///< programme size read
  std::uint64_t fingerprint = 0;  ///< FNV-1a 64 of the programme's bytes
};

/// The first pass over `input` (its header read already), with every check ExecuteProgram
/// makes on the blocks (errors to `diagnostics`). Calls `on_chunk` for every chunk, in order,
/// once the whole programme is read (each chunk's warm-up is seeded with the arm's branch the
/// start-branch look-ahead chose, where it stood at that point). `progress(bytes)`, if set,
/// is called now and then. A safe point is a block boundary where the stitch head cannot be in
/// the preform: stitching off or the head retracted before it; fibre placement is never cut
/// (its coverage rules judge a ply as a whole).
ScanResult ScanProgram(const CellSetup& cell, const process::ProcessModel& process,
                       ProgramInput& input, const ExecuteOptions& options, const ScanOptions& scan,
                       bool cut, DiagnosticSink& diagnostics,
                       const std::function<void(const Chunk&)>& on_chunk,
                       const std::function<void(std::uint64_t)>& progress = nullptr);

/// The carries of one boundary of a chunk, as bytes (compared, never read back).
struct ChunkCarry {
  std::string executor;  ///< captured before the executor takes the line on
  std::string timing;    ///< the timing sink's input side, at the same moment
  bool operator==(const ChunkCarry& o) const = default;
};

/// Hooks a chunk run calls; `stop` is polled after each block (true: the chunk has what it
/// needs, stop reading).
struct ChunkHooks {
  /// Before the block on `line` (first_line or end_line) is executed.
  std::function<void(int line, ChunkCarry carry)> at_boundary;
  std::function<std::string()> timing_carry;  ///< the timing sink's input-side carry
  std::function<bool()> stop;
};

/// Runs one chunk of the programme file `path` (opened anew) from `chunk.warm`: every line
/// and sample goes to `sink` (warm-up included: the caller gates it). Runs to the programme's
/// end unless hooks.stop says so. Input errors go to `diagnostics` (the first pass has seen
/// them already: a chunk reports none of its own).
ExecutionSummary ExecuteChunk(const CellSetup& cell, const process::ProcessModel& process,
                              const program::Dialect& dialect, const std::string& path,
                              const Chunk& chunk, const ExecuteOptions& options,
                              DiagnosticSink& diagnostics, TraceSink& sink,
                              const ChunkHooks& hooks);

}  // namespace stitchsim::sim
