#pragma once
// verify's chunked run (--jobs, --shard) and `stitchsim report merge` (docs/ci.md).

#include <memory>
#include <string>

#include "cli_common.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/verifier.h"
#include "verify_session.h"

namespace stitchsim::app {

/// A verify invocation as its partial result records it (report merge rebuilds the run).
struct ChunkedInvocation {
  std::string program, scene, dialect;
  bool no_collision = false, allow_mismatch = false, quiet = false;
  bool stitch_marks = false;    ///< keep every stitch's verdict (--snapshots' overview)
  std::size_t chunk_poses = 0;  ///< --html: line-end poses kept per chunk (0: none)
  int jobs = 0;                 ///< 0: the number of cores
  int shard = 0, shards = 0;    ///< --shard I/N (0: the whole programme)
  std::string part;             ///< --shard: the partial result file
  int chunk_lines = 16384;      ///< cut at the first safe point after this many lines
  int warm_lines = 128;         ///< each chunk's warm-up, lines
};

struct ChunkedOutcome {
  std::unique_ptr<verify::Verifier> verifier;  ///< merged, not finished
  trace::TraceFileSummary summary;
  run::PoseTrack poses{0};  ///< ChunkedInvocation::chunk_poses > 0: every chunk's, in order
};

/// "I/N" with 1 <= I <= N (printed error otherwise).
bool ParseShard(const std::string& text, int& shard, int& shards);

/// Runs the programme (or its shard) chunked; kExitOk with `out` filled (whole programme) or the
/// part written (--shard); kExitBadInput (printed) on bad input.
int RunChunkedVerify(const ChunkedInvocation& inv, VerifySession& vs, sim::ProgramInput& input,
                     BoundedDiagnosticSink& diagnostics, ChunkedOutcome& out);

}  // namespace stitchsim::app
