#pragma once
// The run behind `stitchsim verify` and `stitchsim diff`: a programme executed on the scene's
// cell and checked by every rule, into a finished verify::Report (serially, or in chunks on
// worker threads, or one shard of the chunks into a part file).

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/chunked_verify.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/run/run_model.h"
#include "stitchsim/run/status.h"
#include "stitchsim/sim/dynamics.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

/// What to run and how (verify's options other than its outputs).
struct VerifyRunOptions {
  std::string program;     ///< programme file, or a pipe (run serially)
  std::string scene;       ///< scene YAML file name, as given (the report names it)
  std::string dialect;     ///< dialect YAML file name, as given ("" built-in; parts record it)
  std::string save_trace;  ///< write the trace here (a serial run); empty: no trace
  RunOptions run;          ///< collision, mismatch, dynamics (a serial run)
  bool keep_stitch_marks = false;  ///< every stitch's verdict kept (the overview snapshot)
  bool record_poses = false;       ///< line-end poses kept (--html's slider)
  std::size_t max_poses = 0;       ///< record_poses: at most this many poses kept (serial run)
  ChunkPlan chunks;                ///< the chunked run's cut and share (a serial run: not used)
};

/// A finished run: the report (rules, counts, verdict filled) and what the snapshots read.
struct VerifyRun {
  RunStatus status = RunStatus::kBadInput;     ///< kOk when run (findings are in `report`)
  std::unique_ptr<RunModel> model;             ///< owned; null when it could not be made
  std::unique_ptr<verify::Verifier> verifier;  ///< finished into `report`
  verify::Report report;                       ///< finished (empty with a shard)
  PoseTrack poses{0};  ///< VerifyRunOptions::record_poses: the line-end poses, in line order
  /// A dynamic run: the physics' figures, and the wall time from the start of execution, s.
  std::optional<sim::DynamicsFigures> dynamics;
  double dynamics_wall_s = 0.0;
  /// A chunked run: the chunks, re-runs, and a shard's part (ChunkedOutcome's fields).
  int chunks = 0, reruns = 0;
  std::string first_mismatch;
  std::size_t part_chunks = 0;
};

/// Runs the programme on `loaded` (moved in) with `dialect`. Problems into `sink` (the
/// programme's with file:line) and status kBadInput or kInternal; with a shard, the part
/// written and `report` left empty. `progress` (may be null) sees the lines verified.
VerifyRun RunVerification(const VerifyRunOptions& options, LoadedScene loaded,
                          const program::Dialect& dialect, const RunProgress& progress,
                          DiagnosticSink& sink);

}  // namespace stitchsim::run
