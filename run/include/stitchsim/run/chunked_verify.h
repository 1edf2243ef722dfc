#pragma once
// verify's chunked run (--jobs, --shard): a first pass on its own thread cuts the programme
// into chunks (sim/chunk.h), worker threads run them (chunked.h), this thread merges them;
// with a shard, this process's share of the chunks into a part file (docs/ci.md).

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/run/run_model.h"
#include "stitchsim/run/status.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

/// Lines verified so far of the total (0 while unknown), in programme lines; called on the
/// run's thread, `done` only grows. Null: never called.
using RunProgress = std::function<void(double done, double total)>;

/// How a programme is cut and shared out (verify --jobs, --shard, --part, --chunk-lines,
/// --warm-lines).
struct ChunkPlan {
  int jobs = 0;               ///< worker threads; 0: the number of cores
  int shard = 0, shards = 0;  ///< --shard I/N, 1 <= I <= N (0: the whole programme)
  std::string part;           ///< --shard: the part file written
  int chunk_lines = 16384;    ///< cut at the first safe point after this many lines
  int warm_lines = 128;       ///< each chunk's warm-up, lines
};

/// A chunked verify run as its part file records it (report merge rebuilds the run from it).
struct ChunkedOptions {
  std::string program;          ///< programme file (a regular file: chunks reopen it)
  std::string scene, dialect;   ///< file names as given (a part records them); dialect "" built-in
  bool no_collision = false;    ///< as the model was made (a part records it)
  bool allow_mismatch = false;  ///< as the model was made (a part records it)
  bool stitch_marks = false;    ///< keep every stitch's verdict (--snapshots' overview)
  std::size_t chunk_poses = 0;  ///< --html: line-end poses kept per chunk (0: none)
  ChunkPlan plan;               ///< the cut and the share
};

/// What the chunked run gives (whole programme) or wrote (a shard).
struct ChunkedOutcome {
  RunStatus status = RunStatus::kBadInput;     ///< kOk, kBadInput or kInternal (sink says why)
  std::unique_ptr<verify::Verifier> verifier;  ///< whole programme: merged, not finished
  trace::TraceFileSummary summary;             ///< whole programme: lines, moves, times (s)
  PoseTrack poses{0};           ///< ChunkedOptions::chunk_poses > 0: every chunk's, in line order
  int chunks = 0;               ///< chunks the first pass cut the whole programme into
  int reruns = 0;               ///< chunks run again (their warm-up rebuilt another state)
  std::string first_mismatch;   ///< what differed at the first chunk run again
  std::size_t part_chunks = 0;  ///< a shard: the chunks its part holds
};

/// The number of worker threads when none is asked for: the number of cores (at least 1).
int DefaultJobs();

/// Runs the programme (or its shard) chunked on `model`; `input` is the programme already
/// opened with its header read, `diagnostics` the programme's sink (forwarded by the caller).
/// Tool errors (io-write, internal) into `sink`.
ChunkedOutcome RunChunkedVerify(const ChunkedOptions& options, const RunModel& model,
                                sim::ProgramInput& input, DiagnosticSink& diagnostics,
                                const RunProgress& progress, DiagnosticSink& sink);

}  // namespace stitchsim::run
