#include "chunked_cmd.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "chunked_verify.h"
#include "commands.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/progress.h"
#include "stitchsim/common/version.h"
#include "stitchsim/program/identity.h"

namespace stitchsim::app {
namespace {

constexpr const char* kPartFormat = "stitchsim-verify-part";
constexpr int kPartVersion = 1;

// The first pass's chunks, handed to the workers (the first pass runs on its own thread).
class ChunkQueue {
 public:
  void Push(const sim::Chunk& c) {
    std::lock_guard lock(m_);
    q_.push_back(c);
    cv_.notify_all();
  }
  void Close() {
    std::lock_guard lock(m_);
    closed_ = true;
    cv_.notify_all();
  }
  std::optional<sim::Chunk> Pop() {
    std::unique_lock lock(m_);
    cv_.wait(lock, [&] { return closed_ || !q_.empty(); });
    if (q_.empty()) return std::nullopt;
    sim::Chunk c = q_.front();
    q_.pop_front();
    return c;
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<sim::Chunk> q_;
  bool closed_ = false;
};

// FNV-1a 64 of a file's bytes, streamed (0 when unreadable).
std::uint64_t FileFnv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  std::uint64_t h = 1469598103934665603ULL;
  std::vector<char> buf(1 << 20);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buf[static_cast<std::size_t>(i)]);
      h *= 1099511628211ULL;
    }
  }
  return h;
}

std::string Hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

int DefaultJobs() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

// Which shard (1..N) a chunk belongs to: by where its run starts in the file.
int ShardOf(const sim::Chunk& c, std::uint64_t file_bytes, int shards) {
  if (c.warm.programme_start || file_bytes == 0) return 1;
  const long double at = static_cast<long double>(c.warm.reader.bytes) * shards / file_bytes;
  return 1 + std::min(static_cast<int>(at), shards - 1);
}

nlohmann::json PartJson(const ChunkedInvocation& inv, const VerifySession& vs,
                        const sim::ScanResult& scan, const std::vector<int>& indices,
                        const ChunkedRun* run, std::uint64_t program_fnv) {
  nlohmann::json j;
  j["format"] = kPartFormat;
  j["version"] = kPartVersion;
  j["tool_version"] = std::string(ToolVersion());
  j["program"] = inv.program;
  j["program_bytes"] = scan.bytes;
  j["program_fnv1a"] = Hex64(program_fnv);
  j["scene"] = inv.scene;
  j["dialect"] = inv.dialect;
  nlohmann::json fp = nlohmann::json::array();
  for (const auto& f : SceneFingerprints(*vs.ls.scene)) {
    fp.push_back({{"role", f.role}, {"fnv1a", Hex64(f.fnv1a)}});
  }
  j["scene_files"] = fp;
  j["no_collision"] = inv.no_collision;
  j["allow_mismatch"] = inv.allow_mismatch;
  j["shard"] = inv.shard;
  j["shards"] = inv.shards;
  j["chunks_total"] = scan.chunks;
  j["chunk_lines"] = inv.chunk_lines;
  j["warm_lines"] = inv.warm_lines;
  j["lines"] = scan.summary.lines;
  j["moves"] = scan.summary.moves;
  j["cycle_time_s"] = scan.summary.time_s;
  j["stitch_length_mm"] = vs.stitch_length_mm;
  j["declared_stitches"] =
      vs.declared_stitches ? nlohmann::json(*vs.declared_stitches) : nlohmann::json(nullptr);
  if (indices.empty() || run == nullptr) {
    j["chunks"] = nullptr;
    return j;
  }
  j["chunks"] = {indices.front(), indices.back()};
  if (scan.chunks == 1) {
    // Not cut (fibre placement, or a programme with no safe point): this part is the whole
    // run; its reports are finished here (the afp.* rules cannot be carried in a part).
    const trace::TraceFileSummary summary{scan.summary.lines, scan.summary.moves,
                                          scan.summary.time_s, run->timed.Value()};
    verify::Report report =
        RunReport(inv.program, inv.scene, *vs.ls.scene, vs.stitch_length_mm, summary);
    run->verifier->Finish(report);
    j["complete"] = {{"text", verify::ReportToText(report)},
                     {"json", verify::ReportToJson(report)},
                     {"junit", verify::ReportToJunit(report)},
                     {"errors", report.errors}};
    return j;
  }
  j["timed_sum"] = run->timed.Hex();
  j["start"] = run->start.Hex();
  j["end"] = run->end.Hex();
  run->verifier->CloseNeedleWindow();
  j["verifier"] = run->verifier->SavePartial();
  return j;
}

}  // namespace

bool ParseShard(const std::string& text, int& shard, int& shards) {
  const std::size_t slash = text.find('/');
  try {
    if (slash != std::string::npos) {
      std::size_t used_i = 0, used_n = 0;
      shard = std::stoi(text.substr(0, slash), &used_i);
      shards = std::stoi(text.substr(slash + 1), &used_n);
      if (used_i == slash && used_n == text.size() - slash - 1 && shards >= 1 && shard >= 1 &&
          shard <= shards && shards <= 100000) {
        return true;
      }
    }
  } catch (const std::exception&) {
  }
  PrintError("cli-usage", "--shard " + text + ": expected I/N with 1 <= I <= N (e.g. 3/8)");
  return false;
}

namespace {

// What every chunk's run is made from.
ChunkSetup MakeChunkSetup(const ChunkedInvocation& inv, VerifySession& vs) {
  ChunkSetup setup;
  setup.dialect = &vs.dialect;
  setup.program_path = inv.program;
  setup.cell = &vs.cell;
  setup.robot = vs.ls.robot.get();
  setup.process = vs.model.get();
  setup.collision = vs.collision.get();
  setup.mujoco = vs.mj.kinematics.get();
  setup.execute = vs.execute;
  setup.timing = vs.timing;
  setup.rules = vs.Rules();
  setup.keep_stitch_marks = inv.stitch_marks;
  setup.chunk_poses = inv.chunk_poses;
  return setup;
}

}  // namespace

int RunChunkedVerify(const ChunkedInvocation& inv, VerifySession& vs, sim::ProgramInput& input,
                     BoundedDiagnosticSink& diagnostics, ChunkedOutcome& out) {
  const int jobs = inv.jobs > 0 ? inv.jobs : DefaultJobs();
  const bool sharded = inv.shards > 0;
  std::error_code ec;
  const std::uint64_t file_bytes = std::filesystem::file_size(inv.program, ec);
  // Fibre placement is never cut (its coverage rules judge a ply as a whole); one job and no
  // shards: one chunk, the serial run.
  const bool cut = vs.ls.scene->head.IsStitching() && (jobs > 1 || sharded);
  sim::ScanOptions scan_options;
  scan_options.chunk_lines = inv.chunk_lines;
  scan_options.warm_lines = inv.warm_lines;
  ChunkQueue queue;
  std::vector<int> indices;  // the chunks this process runs
  sim::ScanResult scan;
  // Progress starts once the first pass knows how many lines this process verifies.
  std::unique_ptr<Progress> progress;
  std::atomic<long> lines_done{0}, lines_total{0};
  std::atomic<bool> scanned{false};
  long lines_reported = 0;
  int last_first = 0;
  std::thread scanner([&] {
    scan = sim::ScanProgram(vs.cell, *vs.model, input, vs.execute, scan_options, cut, diagnostics,
                            [&](const sim::Chunk& c) {
                              if (!sharded || ShardOf(c, file_bytes, inv.shards) == inv.shard) {
                                indices.push_back(c.index);
                                queue.Push(c);
                                if (c.end_line > 0) {
                                  lines_total += c.end_line - c.first_line;
                                } else {
                                  last_first = c.first_line;  // runs to the programme's end
                                }
                              }
                            });
    if (last_first > 0) lines_total += scan.summary.lines + 1 - last_first;
    scanned = true;
    queue.Close();
  });
  const ChunkSetup setup = MakeChunkSetup(inv, vs);
  const auto tick = [&] {
    if (!progress && scanned) {
      Progress::Options po;
      po.enabled = !inv.quiet;
      po.plain_min_run_s = 1.0;  // a short run writes no progress into a log
      progress = std::make_unique<Progress>("verify", "lines",
                                            static_cast<double>(lines_total.load()), po);
    }
    if (!progress) return;
    const long now = lines_done.load();
    if (now > lines_reported) progress->Add(static_cast<double>(now - lines_reported));
    lines_reported = now;
    progress->Tick();
  };
  ChunkedRun run = RunChunks(
      setup, jobs, !sharded || inv.shard == 1, [&] { return queue.Pop(); }, &lines_done, tick);
  scanner.join();
  if (PrintDiagnostics(diagnostics) || !scan.summary.ok) return kExitBadInput;
  tick();
  if (progress) progress->Finish();
  if (!inv.quiet && run.reruns > 0) {
    std::fprintf(stderr,
                 "verify: %d of %d chunks ran again (their warm-up did not rebuild the state "
                 "the chunk before ended with; first: %s)\n",
                 run.reruns, scan.chunks, run.first_mismatch.c_str());
  }
  if (sharded) {
    std::sort(indices.begin(), indices.end());
    if (!indices.empty() && !run.ok) {
      PrintError("internal", "chunked run: " + run.error);
      return kExitInternal;
    }
    const nlohmann::json j =
        PartJson(inv, vs, scan, indices, indices.empty() ? nullptr : &run, FileFnv(inv.program));
    if (std::string err = WriteFileAtomically(inv.part, j.dump() + "\n"); !err.empty()) {
      PrintError("io-write", "--part: " + err);
      return kExitBadInput;
    }
    std::fprintf(stderr, "verify: shard %d/%d: %zu of %d chunks, part written to %s\n", inv.shard,
                 inv.shards, indices.size(), scan.chunks, inv.part.c_str());
    return kExitOk;
  }
  if (!run.ok) {
    PrintError("internal", "chunked run: " + run.error);
    return kExitInternal;
  }
  out.verifier = std::move(run.verifier);
  out.poses = std::move(run.poses);
  out.summary = trace::TraceFileSummary{scan.summary.lines, scan.summary.moves, scan.summary.time_s,
                                        run.timed.Value()};
  return kExitOk;
}

}  // namespace stitchsim::app
