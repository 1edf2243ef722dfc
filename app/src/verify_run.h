#pragma once
// The run behind `stitchsim verify` and `stitchsim diff`: a programme executed on the scene's
// cell and checked by every rule, into a finished verify::Report (serial or in chunks).

#include <memory>
#include <string>

#include "stitchsim/run/pose_track.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"
#include "verify_session.h"

namespace stitchsim::app {

/// What to run and how (verify's options other than its outputs).
struct VerifyRunOptions {
  std::string program;     ///< programme file, or a pipe (run serially)
  std::string dialect;     ///< dialect YAML; empty: the built-in dialect
  std::string scene;       ///< scene YAML file
  std::string save_trace;  ///< write the trace here (a serial run); empty: no trace
  bool no_collision = false;
  bool allow_mismatch = false;
  bool dynamics = false;           ///< step MuJoCo's physics (a serial run)
  bool quiet = false;              ///< no progress on stderr
  bool keep_stitch_marks = false;  ///< every stitch's verdict kept (the overview snapshot)
  bool record_poses = false;       ///< line-end poses kept (--html's slider)
  int jobs = 0;                    ///< 0: the number of cores
  std::string shard;               ///< "I/N": this process's share into `part`; empty: all
  std::string part;                ///< --shard: the partial result file
  int chunk_lines = 16384;         ///< chunked run: cut after this many lines
  int warm_lines = 128;            ///< chunked run: each chunk's warm-up, lines
};

/// A finished run: the report (rules, counts, verdict filled) and what the snapshots read.
struct VerifyRun {
  std::unique_ptr<VerifySession> session;
  std::unique_ptr<verify::Verifier> verifier;  ///< finished into `report`
  verify::Report report;
  run::PoseTrack poses{0};  ///< VerifyRunOptions::record_poses: the line-end poses, in line order
};

/// Runs the programme: kExitOk with `out` filled (with a shard: the part written, `out` empty),
/// or kExitBadInput with the diagnostics printed (file:line for the programme).
int RunVerification(const VerifyRunOptions& options, VerifyRun& out);

}  // namespace stitchsim::app
