#include "chunked_verify.h"

#include <chrono>
#include <climits>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <thread>

namespace stitchsim::app {
namespace {

// Between the timing sink and a chunk's verifier: the warm-up's lines rebuild the verifier's
// carried state and are then forgotten (ResetAccumulators); the chunk's own lines are counted;
// from end_line on nothing passes (the next chunk counts it) and the run may stop.
class Gate final : public trace::TraceSink {
 public:
  Gate(verify::Verifier& verifier, const sim::Chunk& chunk, std::atomic<long>* lines_done)
      : verifier_(verifier),
        chunk_(chunk),
        lines_done_(lines_done),
        passed_(chunk.first_line - 1) {}
  void SetTiming(const sim::TimingSink* timing) { timing_ = timing; }
  /// Also gives the chunk's own samples (not the warm-up's) to `recorder`.
  void SetRecorder(trace::TraceSink* recorder) { recorder_ = recorder; }

  void OnLine(const trace::LineRecord& line) override {
    if (phase_ == Phase::kWarm && line.source_line >= chunk_.first_line) {
      start_ = Output();
      verifier_.ResetAccumulators();
      phase_ = Phase::kCounting;
    }
    if (phase_ == Phase::kCounting && chunk_.end_line > 0 && line.source_line >= chunk_.end_line) {
      end_ = Output();
      phase_ = Phase::kDone;
    }
    if (phase_ == Phase::kDone) return;
    verifier_.OnLine(line);
    if (phase_ == Phase::kCounting) {
      timed_.Add(line.timed_duration_s);
      ++lines_;
      Advance(line.source_line - 1);
    }
  }
  void OnSample(const trace::TraceSample& s) override {
    if (phase_ == Phase::kDone) return;
    verifier_.OnSample(s);
    if (recorder_ != nullptr && phase_ == Phase::kCounting) recorder_->OnSample(s);
  }
  bool Done() const { return phase_ == Phase::kDone; }
  // The programme ended before the chunk's first motion line: the chunk counts nothing.
  // (Its boundary carries nothing then, as the chunk before it saw no line at its end.)
  void End() {
    if (phase_ != Phase::kWarm) return;
    verifier_.ResetAccumulators();
    phase_ = Phase::kCounting;
  }
  // Progress: the programme lines passed (blocks without motion included).
  void Advance(int through_line) {
    if (through_line <= passed_) return;
    unreported_ += through_line - passed_;
    passed_ = through_line;
    if (lines_done_ != nullptr && unreported_ >= 1024) {
      lines_done_->fetch_add(unreported_);
      unreported_ = 0;
    }
  }
  void Flush(int last_line) {
    Advance(last_line);
    if (lines_done_ != nullptr) lines_done_->fetch_add(unreported_);
    unreported_ = 0;
  }

  std::string start_, end_;
  ExactSum timed_;
  long lines_ = 0;

 private:
  enum class Phase { kWarm, kCounting, kDone };
  std::string Output() const {
    std::string out = timing_ != nullptr ? timing_->OutputCarry() : std::string();
    out += verifier_.Carry();
    return out;
  }
  verify::Verifier& verifier_;
  const sim::Chunk& chunk_;
  std::atomic<long>* lines_done_;
  const sim::TimingSink* timing_ = nullptr;
  trace::TraceSink* recorder_ = nullptr;
  Phase phase_ = Phase::kWarm;
  int passed_ = 0;  ///< programme lines passed so far (before first_line: none counted)
  long unreported_ = 0;
};

constexpr char kHexDigits[] = "0123456789abcdef";

void AppendHex(std::string& out, const std::string& bytes) {
  out += std::to_string(bytes.size()) + ":";
  for (unsigned char c : bytes) {
    out += kHexDigits[c >> 4];
    out += kHexDigits[c & 0xF];
  }
  out += ";";
}

bool ReadHex(const std::string& text, std::size_t& at, std::string& bytes) {
  const std::size_t colon = text.find(':', at);
  if (colon == std::string::npos) return false;
  std::size_t n = 0;
  for (std::size_t i = at; i < colon; ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
    n = n * 10 + static_cast<std::size_t>(text[i] - '0');
  }
  if (colon + 1 + 2 * n + 1 > text.size() || text[colon + 1 + 2 * n] != ';') return false;
  bytes.assign(n, '\0');
  for (std::size_t i = 0; i < n; ++i) {
    int v = 0;
    for (int k = 0; k < 2; ++k) {
      const char c = text[colon + 1 + 2 * i + static_cast<std::size_t>(k)];
      const int d = c >= '0' && c <= '9' ? c - '0' : (c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1);
      if (d < 0) return false;
      v = v * 16 + d;
    }
    bytes[i] = static_cast<char>(v);
  }
  at = colon + 1 + 2 * n + 1;
  return true;
}

}  // namespace

std::string BoundaryState::Hex() const {
  std::string out;
  AppendHex(out, input.executor);
  AppendHex(out, input.timing);
  AppendHex(out, output);
  return out;
}

std::optional<BoundaryState> BoundaryState::FromHex(const std::string& text) {
  BoundaryState b;
  std::size_t at = 0;
  if (!ReadHex(text, at, b.input.executor) || !ReadHex(text, at, b.input.timing) ||
      !ReadHex(text, at, b.output) || at != text.size()) {
    return std::nullopt;
  }
  return b;
}

ChunkResult RunChunk(const ChunkSetup& setup, const sim::Chunk& chunk,
                     std::atomic<long>* lines_done) {
  ChunkResult result;
  result.chunk = chunk;
  // Fresh per-run state: a run's answers depend on where it started only.
  std::unique_ptr<sim::MujocoCell> kinematics = setup.mujoco->Share();
  std::unique_ptr<sim::MujocoCell> timing_cell = setup.mujoco->Share();
  std::unique_ptr<sim::CollisionWorld> collision;
  if (setup.collision != nullptr) {
    collision = setup.collision->Share();
    collision->UseKinematics(kinematics.get());
  }
  sim::ExecuteOptions options = setup.execute;
  options.collision = collision.get();
  options.mujoco = kinematics.get();
  result.verifier = std::make_unique<verify::Verifier>(setup.rules, setup.keep_stitch_marks);
  Gate gate(*result.verifier, result.chunk, lines_done);
  sim::TimingSink timing(*timing_cell, *setup.robot, setup.timing, gate);
  gate.SetTiming(&timing);
  std::optional<run::PoseRecorder> recorder;
  if (setup.chunk_poses > 0) {
    result.poses = std::make_unique<run::PoseTrack>(setup.chunk_poses);
    recorder.emplace(*result.poses, nullptr);
    gate.SetRecorder(&*recorder);
  }
  sim::ChunkHooks hooks;
  hooks.at_boundary = [&](int line, sim::ChunkCarry carry) {
    (line == chunk.first_line ? result.start : result.end).input = std::move(carry);
  };
  hooks.timing_carry = [&] { return timing.InputCarry(); };
  hooks.stop = [&] { return gate.Done(); };
  BoundedDiagnosticSink diagnostics(8);
  const sim::ExecutionSummary run =
      sim::ExecuteChunk(*setup.cell, *setup.process, *setup.dialect, setup.program_path, chunk,
                        options, diagnostics, timing, hooks);
  if (!run.ok) {
    result.error = diagnostics.Diagnostics().empty() ? "chunk run failed"
                                                     : diagnostics.Diagnostics().front().message;
    return result;
  }
  if (!gate.Done()) timing.Finish();  // the programme's end: the last lines, ending at rest
  gate.End();
  gate.Flush(chunk.end_line > 0 ? chunk.end_line - 1 : run.lines);
  result.start.output = std::move(gate.start_);
  result.end.output = std::move(gate.end_);
  result.timed = gate.timed_;
  result.lines = gate.lines_;
  if (result.poses) result.poses->Thin(run::PointedLines(*result.verifier), INT_MAX);
  result.ok = true;
  return result;
}

std::string BoundaryState::Difference(const BoundaryState& o) const {
  std::string d;
  const auto first_diff = [](const std::string& a, const std::string& b) {
    std::size_t i = 0;
    while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
    return " (" + std::to_string(a.size()) + " vs " + std::to_string(b.size()) +
           " bytes, first difference at byte " + std::to_string(i) + ")";
  };
  if (input.executor != o.input.executor) {
    d += "the executor's joints" + first_diff(input.executor, o.input.executor);
    if (input.executor.size() >= 64 && o.input.executor.size() >= 64) {
      for (std::size_t j = 0; j < 8; ++j) {
        double a = 0.0, b = 0.0;
        std::memcpy(&a, input.executor.data() + 8 * j, 8);
        std::memcpy(&b, o.input.executor.data() + 8 * j, 8);
        if (a != b) {
          char buf[96];
          std::snprintf(buf, sizeof buf, " joint %zu: %.17g vs %.17g", j, a, b);
          d += buf;
        }
      }
    }
    d += "; ";
  }
  if (input.timing != o.input.timing) {
    d += "the timing sink's last joints" + first_diff(input.timing, o.input.timing) + "; ";
  }
  if (output != o.output) {
    d += "the controller's speed or the verifier's state" + first_diff(output, o.output) + "; ";
  }
  return d;
}

ChunkMerger::Outcome ChunkMerger::Add(ChunkResult result) {
  if (taken_ > 0 && !(result.start == last_->end)) {
    if (first_mismatch_.empty()) {
      first_mismatch_ = "chunk " + std::to_string(result.chunk.index) + " at line " +
                        std::to_string(result.chunk.first_line) + ": " +
                        result.start.Difference(last_->end);
    }
    return Outcome::kRerun;
  }
  if (taken_ == 0) {
    verifier_ = std::move(result.verifier);
    first_start_ = result.start;
  } else {
    verifier_->Absorb(*result.verifier);
    result.verifier.reset();
  }
  timed_.Add(result.timed);
  if (result.poses) {
    poses_.Append(*result.poses);
    result.poses.reset();
  }
  last_ = std::move(result);
  ++taken_;
  return Outcome::kTaken;
}

sim::Chunk ChunkMerger::Rerun(const sim::Chunk& next) const {
  sim::Chunk c = next;
  c.warm = last_->chunk.warm;
  return c;
}

namespace {

// The workers' side of RunChunks: chunks to run (new ones from the source, re-runs first),
// results by chunk index.
struct WorkPool {
  WorkPool(const ChunkSetup& s, const std::function<std::optional<sim::Chunk>()>& source,
           std::atomic<long>* done_lines)
      : setup(s), next_chunk(source), lines_done(done_lines) {}
  const ChunkSetup& setup;
  const std::function<std::optional<sim::Chunk>()>& next_chunk;
  std::atomic<long>* lines_done;
  std::mutex m;
  std::condition_variable cv;
  std::map<int, ChunkResult> done;
  std::map<int, sim::Chunk> pending;  // chunks known but not yet merged (for re-runs)
  std::deque<sim::Chunk> reruns;
  bool exhausted = false, stop = false;
  int source_busy = 0;  // workers inside next_chunk

  void Work() {
    std::unique_lock lock(m);
    for (;;) {
      cv.wait(lock, [&] { return stop || !reruns.empty() || (!exhausted && source_busy == 0); });
      if (stop) return;
      sim::Chunk c;
      if (!reruns.empty()) {
        c = reruns.front();
        reruns.pop_front();
      } else {
        ++source_busy;
        lock.unlock();
        std::optional<sim::Chunk> next = next_chunk();
        lock.lock();
        --source_busy;
        if (!next) {
          exhausted = true;
          cv.notify_all();
          continue;
        }
        c = *next;
        pending[c.index] = c;
        cv.notify_all();
      }
      lock.unlock();
      ChunkResult r;
      try {
        r = RunChunk(setup, c, lines_done);
      } catch (const std::exception& e) {  // a bug: reported by the merging thread, exit 3
        r.chunk = c;
        r.ok = false;
        r.error = e.what();
      }
      lock.lock();
      done[c.index] = std::move(r);
      cv.notify_all();
    }
  }
};

}  // namespace

ChunkedRun RunChunks(const ChunkSetup& setup, int jobs, bool starts_at_zero,
                     const std::function<std::optional<sim::Chunk>()>& next_chunk,
                     std::atomic<long>* lines_done, const std::function<void()>& tick) {
  WorkPool pool(setup, next_chunk, lines_done);
  std::mutex& m = pool.m;
  std::condition_variable& cv = pool.cv;
  std::map<int, ChunkResult>& done = pool.done;
  std::map<int, sim::Chunk>& pending = pool.pending;
  std::deque<sim::Chunk>& reruns = pool.reruns;
  std::vector<std::thread> threads;
  for (int i = 0; i < std::max(1, jobs); ++i) threads.emplace_back([&pool] { pool.Work(); });
  ChunkedRun out;
  ChunkMerger merger;
  {
    std::unique_lock lock(m);
    int first = starts_at_zero ? 0 : -1;  // the first chunk to merge
    for (;;) {
      if (first < 0 && !pending.empty()) first = pending.begin()->first;
      const int next = first + merger.Taken();
      cv.wait_for(lock, std::chrono::milliseconds(500), [&] {
        return (first >= 0 && done.count(next) > 0) || (pool.exhausted && pending.empty());
      });
      if (tick) {
        lock.unlock();
        tick();
        lock.lock();
      }
      if (first < 0 && !pending.empty()) continue;
      auto it = first >= 0 ? done.find(next) : done.end();
      if (it == done.end()) {
        // Every chunk the first pass found (for this process) is merged.
        if (pool.exhausted && pending.empty() && pool.source_busy == 0) {
          out.ok = merger.Taken() > 0;
          if (!out.ok) out.error = "no chunk to run";
          break;
        }
        continue;
      }
      ChunkResult r = std::move(it->second);
      done.erase(it);
      if (!r.ok) {
        out.error = r.error;
        break;
      }
      const sim::Chunk as_planned = pending.count(next) ? pending[next] : r.chunk;
      const bool r_warm_start = r.chunk.warm.programme_start;
      const std::uint64_t r_warm_bytes = r.chunk.warm.reader.bytes;
      lock.unlock();
      ChunkMerger::Outcome outcome = ChunkMerger::Outcome::kTaken;
      std::string merge_error;
      try {
        outcome = merger.Add(std::move(r));
      } catch (const std::exception& e) {  // a bug (e.g. a part ending with the needles in)
        merge_error = e.what();
      }
      lock.lock();
      if (!merge_error.empty()) {
        out.error = merge_error;
        break;
      }
      if (outcome == ChunkMerger::Outcome::kRerun) {
        if (!(as_planned.warm.programme_start == r_warm_start &&
              as_planned.warm.reader.bytes == r_warm_bytes)) {
          // A run from the chunk before's own start differs from that chunk's: not
          // deterministic (a bug); never take it.
          out.error = "chunk " + std::to_string(next) + " is not reproducible from line " +
                      std::to_string(as_planned.first_line);
          break;
        }
        ++out.reruns;
        reruns.push_front(merger.Rerun(as_planned));
        cv.notify_all();
        continue;
      }
      pending.erase(next);
    }
    pool.stop = true;
    cv.notify_all();
  }
  for (auto& t : threads) t.join();
  if (!out.ok) return out;
  out.first_mismatch = merger.FirstMismatch();
  out.verifier = merger.TakeVerifier();
  out.timed = merger.Timed();
  out.poses = std::move(merger.Poses());
  out.start = merger.FirstStart();
  out.end = merger.Last()->end;
  return out;
}

}  // namespace stitchsim::app
