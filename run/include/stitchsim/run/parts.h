#pragma once
// Part files: one shard's share of a chunked verify run (verify --shard I/N --part FILE), and
// `report merge`, the report of the whole run from every shard's part (docs/ci.md).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/run/chunked.h"
#include "stitchsim/run/chunked_verify.h"
#include "stitchsim/run/status.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/chunk.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::run {

/// An FNV-1a 64 style hash of a file's bytes, streamed (0 when unreadable); its offset
/// basis differs from trace::Fnv1a64's (parts.cpp).
std::uint64_t FileFnv(const std::string& path);

/// Which shard (1..shards) a chunk belongs to: by where its run starts in the file of
/// `file_bytes` bytes.
int ShardOf(const sim::Chunk& chunk, std::uint64_t file_bytes, int shards);

/// A part's JSON: the run's identity (programme, scene files, options, the cut) and, when
/// `run` is given, the chunks `indices` (sorted) of it: their verifier's partial state and
/// boundaries, or the finished reports when the programme is one chunk.
nlohmann::json PartJson(const ChunkedOptions& options, const RunModel& model,
                        const sim::ScanResult& scan, const std::vector<int>& indices,
                        const ChunkedRun* run, std::uint64_t program_fnv);

/// A part file read.
struct Part {
  std::string file;      ///< as given
  nlohmann::json j;      ///< its JSON
  int lo = -1, hi = -1;  ///< the chunk range it holds (-1: none)
};

/// Reads a part (part-bad, io-missing-file into `sink`; false then).
bool ReadPart(const std::string& file, Part& part, DiagnosticSink& sink);

/// Every part from the same run, together covering every chunk once (part-mismatch,
/// part-missing, part-duplicate into `sink` otherwise); reordered by chunk, parts without
/// chunks dropped.
bool PartsFit(std::vector<Part>& parts, DiagnosticSink& sink);

/// A programme run in one chunk: its part holds the finished reports, as written.
struct CompleteReports {
  std::string text, json, junit;  ///< verify's text, JSON and JUnit reports
  long errors = 0;                ///< error findings (the exit code)
};

/// The report of the run whose parts are `files`.
struct MergedReport {
  RunStatus status = RunStatus::kBadInput;  ///< kOk / kFindings when merged
  verify::Report report;                    ///< merged and finished (unless `complete`)
  std::optional<CompleteReports> complete;  ///< a one-chunk run: its part's reports
};

/// Reads, checks and merges the parts (scene loaded with `load`); problems into `sink`.
MergedReport MergeParts(const std::vector<std::string>& files, const scene::LoadOptions& load,
                        DiagnosticSink& sink);

}  // namespace stitchsim::run
