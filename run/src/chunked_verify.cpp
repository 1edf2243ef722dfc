// verify --jobs / --shard (chunked_verify.h): the first pass cuts the programme on its own
// thread, RunChunks runs and merges the chunks, then the whole run's verifier or the part.
#include "stitchsim/run/chunked_verify.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include "stitchsim/common/files.h"
#include "stitchsim/run/chunked.h"
#include "stitchsim/run/parts.h"

namespace stitchsim::run {
namespace {

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

// One chunked run: the first pass (its own thread) feeding the queue, the progress, and what
// the run gives at its end (the merged verifier, or a shard's part).
class ChunkedVerify {
 public:
  ChunkedVerify(const ChunkedOptions& o, const RunModel& model, const RunProgress& progress)
      : o_(o),
        model_(model),
        progress_(progress),
        sharded_(o.plan.shards > 0),
        first_pass_data_(MakeRunData(model)) {
    std::error_code ec;
    file_bytes_ = std::filesystem::file_size(o.program, ec);
  }

  /// Starts the first pass: it cuts the programme (fibre placement is never cut: its
  /// coverage rules judge a ply as a whole; one job and no shards: one chunk, the serial run)
  /// and queues this process's chunks.
  std::thread StartFirstPass(sim::ProgramInput& input, int jobs, DiagnosticSink& diagnostics) {
    const bool cut = model_.loaded.scene->head.IsStitching() && (jobs > 1 || sharded_);
    return std::thread([this, &input, &diagnostics, cut] {
      sim::ScanOptions scan_options;
      scan_options.chunk_lines = o_.plan.chunk_lines;
      scan_options.warm_lines = o_.plan.warm_lines;
      scan_ = sim::ScanProgram(model_.cell, *model_.process, input, first_pass_data_.execute,
                               scan_options, cut, diagnostics,
                               [this](const sim::Chunk& c) { Found(c); });
      if (last_first_ > 0) lines_total_ += scan_.summary.lines + 1 - last_first_;
      scanned_ = true;
      queue_.Close();
    });
  }

  /// Progress once the first pass knows how many lines this process verifies.
  void Tick() {
    if (progress_ && scanned_)
      progress_(static_cast<double>(lines_done_.load()), static_cast<double>(lines_total_.load()));
  }

  ChunkedRun Run(int jobs) {
    ChunkSetup setup;
    setup.model = &model_;
    setup.program_path = o_.program;
    setup.keep_stitch_marks = o_.stitch_marks;
    setup.chunk_poses = o_.chunk_poses;
    return RunChunks(
        setup, jobs, !sharded_ || o_.plan.shard == 1, [&] { return queue_.Pop(); }, &lines_done_,
        [this] { Tick(); });
  }

  const sim::ScanResult& Scan() const { return scan_; }

  /// A shard's end: its part written (tool errors into `sink`).
  RunStatus WritePart(const ChunkedRun& run, ChunkedOutcome& out, DiagnosticSink& sink) {
    std::sort(indices_.begin(), indices_.end());
    if (!indices_.empty() && !run.ok) {
      ToolError(sink, "internal", "chunked run: " + run.error);
      return RunStatus::kInternal;
    }
    const nlohmann::json j = PartJson(o_, model_, scan_, indices_,
                                      indices_.empty() ? nullptr : &run, FileFnv(o_.program));
    if (std::string err = WriteFileAtomically(o_.plan.part, j.dump() + "\n"); !err.empty()) {
      ToolError(sink, "io-write", "--part: " + err);
      return RunStatus::kBadInput;
    }
    out.part_chunks = indices_.size();
    return RunStatus::kOk;
  }

 private:
  // A chunk the first pass found: queued when it is this process's.
  void Found(const sim::Chunk& c) {
    if (sharded_ && ShardOf(c, file_bytes_, o_.plan.shards) != o_.plan.shard) return;
    indices_.push_back(c.index);
    queue_.Push(c);
    if (c.end_line > 0) {
      lines_total_ += c.end_line - c.first_line;
    } else {
      last_first_ = c.first_line;  // runs to the programme's end
    }
  }

  const ChunkedOptions& o_;
  const RunModel& model_;
  const RunProgress& progress_;
  const bool sharded_;
  RunData first_pass_data_;  ///< the first pass's working states (its own thread's)
  std::uint64_t file_bytes_ = 0;
  ChunkQueue queue_;
  std::vector<int> indices_;  ///< the chunks this process runs
  sim::ScanResult scan_;
  std::atomic<long> lines_done_{0}, lines_total_{0};
  std::atomic<bool> scanned_{false};
  int last_first_ = 0;
};

}  // namespace

int DefaultJobs() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

ChunkedOutcome RunChunkedVerify(const ChunkedOptions& o, const RunModel& model,
                                sim::ProgramInput& input, DiagnosticSink& diagnostics,
                                const RunProgress& progress, DiagnosticSink& sink) {
  ChunkedOutcome out;
  const int jobs = o.plan.jobs > 0 ? o.plan.jobs : DefaultJobs();
  ChunkedVerify cv(o, model, progress);
  std::thread first_pass = cv.StartFirstPass(input, jobs, diagnostics);
  ChunkedRun run = cv.Run(jobs);
  first_pass.join();
  if (Forward(diagnostics, sink) || !cv.Scan().summary.ok) return out;
  cv.Tick();
  out.chunks = cv.Scan().chunks;
  out.reruns = run.reruns;
  out.first_mismatch = run.first_mismatch;
  if (o.plan.shards > 0) {
    out.status = cv.WritePart(run, out, sink);
    return out;
  }
  if (!run.ok) {
    ToolError(sink, "internal", "chunked run: " + run.error);
    out.status = RunStatus::kInternal;
    return out;
  }
  const sim::ScanResult& scan = cv.Scan();
  out.verifier = std::move(run.verifier);
  out.poses = std::move(run.poses);
  out.summary = trace::TraceFileSummary{scan.summary.lines, scan.summary.moves, scan.summary.time_s,
                                        run.timed.Value()};
  out.status = RunStatus::kOk;
  return out;
}

}  // namespace stitchsim::run
