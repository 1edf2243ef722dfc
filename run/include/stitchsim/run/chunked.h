#pragma once
// verify --jobs / --shard: a programme's chunks (sim/chunk.h) run on worker threads, each
// through its own executor, timing sink and verifier, and are merged in programme order into
// the one verifier a serial run would have. A chunk is taken only when the state it rebuilt
// in its warm-up equals, byte for byte, the state the chunk before it ended with; otherwise
// it runs again from that chunk's own start (docs/ci.md, "How a programme is cut").

#include <atomic>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/exact_sum.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/run/run_model.h"
#include "stitchsim/sim/chunk.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

/// What every chunk's run is made from (read-only while workers run: each chunk makes its own
/// RunData from the model).
struct ChunkSetup {
  const RunModel* model = nullptr;  ///< not owned; outlives the run
  std::string program_path;         ///< the programme, reopened by each chunk
  bool keep_stitch_marks = false;   ///< every stitch's verdict kept (the overview snapshot)
  /// Record line-end poses (verify --html): at most this many per chunk beside the lines its
  /// findings point at; 0 = none.
  std::size_t chunk_poses = 0;
};

/// A chunk's state at one boundary: the executor's and the timing sink's input side when the
/// executor takes the boundary line on, the timing sink's output side and the verifier's when
/// the verifier takes it on.
struct BoundaryState {
  sim::ChunkCarry input;  ///< the executor's and the timing sink's input side, as bytes
  std::string output;     ///< the timing sink's output side then the verifier's, as bytes
  bool operator==(const BoundaryState&) const = default;
  std::string Hex() const;  ///< for partial files
  /// What differs from `other`, for people ("" when equal).
  std::string Difference(const BoundaryState& other) const;
  static std::optional<BoundaryState> FromHex(const std::string& text);
};

/// One chunk as run.
struct ChunkResult {
  sim::Chunk chunk;          ///< its warm start may be an earlier chunk's (a re-run)
  BoundaryState start, end;  ///< at chunk.first_line and chunk.end_line
  std::unique_ptr<verify::Verifier> verifier;  ///< owned; the chunk's lines only
  ExactSum timed;                              ///< timed durations of the chunk's lines, s
  long lines = 0;                              ///< motion lines counted
  std::unique_ptr<PoseTrack> poses;            ///< owned; ChunkSetup::chunk_poses > 0: the chunk's
  bool ok = false;                             ///< ran to its end line (or the programme's)
  std::string error;                           ///< when !ok: the first diagnostic or exception
};

/// Runs one chunk (any thread). `lines_done` (if set) counts the lines it has verified.
ChunkResult RunChunk(const ChunkSetup& setup, const sim::Chunk& chunk,
                     std::atomic<long>* lines_done);

/// Merges chunk results in order (Add), checking each boundary; a chunk whose start differs
/// from where the chunk before it ended is to be run again from that chunk's warm start.
class ChunkMerger {
 public:
  enum class Outcome { kTaken, kRerun };
  /// `result` must be the chunk after the last one taken.
  Outcome Add(ChunkResult result);
  /// The chunk to run again after kRerun: the next chunk, from the last taken chunk's start.
  sim::Chunk Rerun(const sim::Chunk& next) const;
  int Taken() const { return taken_; }
  std::unique_ptr<verify::Verifier> TakeVerifier() { return std::move(verifier_); }
  const ExactSum& Timed() const { return timed_; }
  /// The taken chunks' poses, in order (empty without ChunkSetup::chunk_poses).
  PoseTrack& Poses() { return poses_; }
  const ChunkResult* Last() const { return last_ ? &*last_ : nullptr; }
  const BoundaryState& FirstStart() const { return first_start_; }
  /// The first boundary that did not match, and what differed (empty: none).
  const std::string& FirstMismatch() const { return first_mismatch_; }

 private:
  std::unique_ptr<verify::Verifier> verifier_;
  ExactSum timed_;
  PoseTrack poses_{std::numeric_limits<std::size_t>::max()};
  int taken_ = 0;
  std::optional<ChunkResult> last_;  ///< without its verifier (absorbed)
  BoundaryState first_start_;
  std::string first_mismatch_;
};

/// Every chunk run and merged in order (RunChunks).
struct ChunkedRun {
  bool ok = false;                             ///< every chunk merged
  std::string error;                           ///< when !ok: what failed (a bug or bad input)
  std::unique_ptr<verify::Verifier> verifier;  ///< owned; the merged verifier, not finished
  ExactSum timed;                              ///< timed durations of every chunk's lines, s
  PoseTrack poses{std::numeric_limits<std::size_t>::max()};  ///< every chunk's, in order
  int reruns = 0;                                            ///< chunks run again
  std::string first_mismatch;  ///< what differed at the first chunk run again
  BoundaryState start, end;    ///< of the first and the last chunk run
};

/// Runs chunks on `jobs` threads and merges them in index order: `next_chunk` (called from the
/// workers, one at a time) blocks until the next chunk is known and returns nullopt when there
/// are no more; they are consecutive, from index 0 when `starts_at_zero` (chunk 0 may come
/// last), else from the first one given. `tick` is called about twice a second.
ChunkedRun RunChunks(const ChunkSetup& setup, int jobs, bool starts_at_zero,
                     const std::function<std::optional<sim::Chunk>()>& next_chunk,
                     std::atomic<long>* lines_done, const std::function<void()>& tick);

}  // namespace stitchsim::run
