#pragma once
// Trace files (`stitchsim verify --save-trace`, `stitchsim recheck`): everything the verifier
// consumed, so a run can be checked again, with other limits, without simulating. Binary and
// streamed: a header (what was run, the cell description, fingerprints of the files the run
// depended on), every LineRecord and TraceSample in order, then a summary. Format:
// docs/report-format.md, "Trace files".

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/trace/trace.h"

namespace stitchsim::trace {

/// Version of the format this build writes and reads.
inline constexpr std::uint32_t kTraceFormatVersion = 3;

/// FNV-1a (64 bit) of `bytes`: a file's fingerprint.
std::uint64_t Fnv1a64(std::string_view bytes);

/// A file the run depended on (scene, head spec, cell models), by its fingerprint.
struct FileFingerprint {
  std::string role;  ///< "scene", "head spec", "cell URDF", "cell MJCF", "head MJCF"
  std::string path;  ///< where the producer read it (for messages)
  std::uint64_t fnv1a = 0;
};

/// What was run: written before the first record.
struct TraceFileHeader {
  std::string program_file;  ///< the programme as given to `verify`
  std::string scene_name;    ///< the scene it ran on
  std::string head;          ///< the head mounted
  double stitch_length_mm = 0.0;
  std::optional<long> declared_stitches;  ///< the header's `stitches=N`, if any
  /// The wrist-singularity band the IK used (rad, from the kin.singularity limit a5_min_deg):
  /// the IK statuses in the trace depend on it, so a recheck cannot change it.
  double ik_wrist_singularity_rad = 0.0;
  CellDescription cell;  ///< joint limits, speeds, names, collision bodies
  std::vector<FileFingerprint> fingerprints;
};

/// How the run ended: written after the last record.
struct TraceFileSummary {
  long lines = 0;  ///< programme lines read
  long moves = 0;  ///< motion lines executed
  double cycle_time_s = 0.0;        ///< at the programmed speeds (the simple estimate)
  double cycle_time_timed_s = 0.0;  ///< on the controller's time law; 0 when not timed
};

/// Streams a trace into a file, written whole or not at all (common OutputFile): nothing
/// appears at `path` unless Commit succeeds. Memory does not grow with the trace.
class TraceFileWriter final : public TraceSink {
 public:
  /// Opens the output and writes the header; nullptr and `error` set when it cannot.
  static std::unique_ptr<TraceFileWriter> Open(const std::filesystem::path& path,
                                               const TraceFileHeader& header, std::string& error);
  ~TraceFileWriter() override;
  void OnLine(const LineRecord& line) override;
  void OnSample(const TraceSample& sample) override;
  /// Writes the summary and moves the file into place; an error message, or empty.
  std::string Commit(const TraceFileSummary& summary);

 private:
  TraceFileWriter();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads a trace file front to back. Every problem (missing file, a directory, not a trace,
/// another format version, a truncated or corrupt record) is an error naming the file and the
/// byte offset, never a crash or a hang.
class TraceFileReader {
 public:
  /// Opens `path` and reads the header; nullptr and `error` set on failure.
  static std::unique_ptr<TraceFileReader> Open(const std::filesystem::path& path,
                                               std::string& error);
  ~TraceFileReader();
  const TraceFileHeader& Header() const;
  /// Sends every record to `sink` in order and reads the summary; false and `error` set on a
  /// bad record (the sink may have seen the records before it).
  bool Replay(TraceSink& sink, TraceFileSummary& summary, std::string& error);

 private:
  TraceFileReader();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stitchsim::trace
