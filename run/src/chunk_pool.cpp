// RunChunks (chunked.h): worker threads run the chunks, the calling thread merges them in
// index order and queues a re-run for a chunk whose start differs.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <thread>

#include "stitchsim/run/chunked.h"

namespace stitchsim::run {
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

// The merging thread's side of RunChunks: the workers' results taken in index order.
class MergeLoop {
 public:
  MergeLoop(WorkPool& pool, bool starts_at_zero, const std::function<void()>& tick)
      : pool_(pool), tick_(tick), first_(starts_at_zero ? 0 : -1) {}

  /// Merges every chunk (re-running those whose start differs), then stops the workers;
  /// out.ok, or out.error on the first failure.
  void Run(ChunkedRun& out) {
    std::unique_lock lock(pool_.m);
    for (;;) {
      std::optional<ChunkResult> r = NextResult(lock);
      if (!r) {
        if (!AllMerged()) continue;
        out.ok = merger_.Taken() > 0;
        if (!out.ok) out.error = "no chunk to run";
        break;
      }
      if (!r->ok) {
        out.error = r->error;
        break;
      }
      if (!Merge(std::move(*r), lock, out)) break;
    }
    pool_.stop = true;
    pool_.cv.notify_all();
  }
  ChunkMerger& Merger() { return merger_; }

 private:
  int Next() const { return first_ + merger_.Taken(); }
  // Every chunk the first pass found (for this process) is merged.
  bool AllMerged() const {
    return pool_.exhausted && pool_.pending.empty() && pool_.source_busy == 0;
  }

  // Waits (half a second at most; progress ticked) for the next chunk's result; nullopt when
  // it has not come yet.
  std::optional<ChunkResult> NextResult(std::unique_lock<std::mutex>& lock) {
    if (first_ < 0 && !pool_.pending.empty()) first_ = pool_.pending.begin()->first;
    const int next = Next();
    pool_.cv.wait_for(lock, std::chrono::milliseconds(500), [&] {
      return (first_ >= 0 && pool_.done.count(next) > 0) ||
             (pool_.exhausted && pool_.pending.empty());
    });
    if (tick_) {
      lock.unlock();
      tick_();
      lock.lock();
    }
    if (first_ < 0) return std::nullopt;
    auto it = pool_.done.find(next);
    if (it == pool_.done.end()) return std::nullopt;
    ChunkResult r = std::move(it->second);
    pool_.done.erase(it);
    return r;
  }

  // Takes `r` (the next chunk) into the merger, or queues its re-run from the chunk before's
  // start; false (out.error set) when it cannot be merged.
  bool Merge(ChunkResult r, std::unique_lock<std::mutex>& lock, ChunkedRun& out) {
    const int next = Next();
    const sim::Chunk as_planned = pool_.pending.count(next) ? pool_.pending[next] : r.chunk;
    const bool warm_as_planned = as_planned.warm.programme_start == r.chunk.warm.programme_start &&
                                 as_planned.warm.reader.bytes == r.chunk.warm.reader.bytes;
    lock.unlock();
    ChunkMerger::Outcome outcome = ChunkMerger::Outcome::kTaken;
    std::string merge_error;
    try {
      outcome = merger_.Add(std::move(r));
    } catch (const std::exception& e) {  // a bug (e.g. a part ending with the needles in)
      merge_error = e.what();
    }
    lock.lock();
    if (!merge_error.empty()) {
      out.error = merge_error;
      return false;
    }
    if (outcome == ChunkMerger::Outcome::kRerun) {
      if (!warm_as_planned) {
        // A run from the chunk before's own start differs from that chunk's: not
        // deterministic (a bug); never take it.
        out.error = "chunk " + std::to_string(next) + " is not reproducible from line " +
                    std::to_string(as_planned.first_line);
        return false;
      }
      ++out.reruns;
      pool_.reruns.push_front(merger_.Rerun(as_planned));
      pool_.cv.notify_all();
      return true;
    }
    pool_.pending.erase(next);
    return true;
  }

  WorkPool& pool_;
  const std::function<void()>& tick_;
  ChunkMerger merger_;
  int first_;  ///< the first chunk index to merge (-1 until the first pass gives one)
};

}  // namespace

ChunkedRun RunChunks(const ChunkSetup& setup, int jobs, bool starts_at_zero,
                     const std::function<std::optional<sim::Chunk>()>& next_chunk,
                     std::atomic<long>* lines_done, const std::function<void()>& tick) {
  WorkPool pool(setup, next_chunk, lines_done);
  std::vector<std::thread> threads;
  for (int i = 0; i < std::max(1, jobs); ++i) threads.emplace_back([&pool] { pool.Work(); });
  ChunkedRun out;
  MergeLoop loop(pool, starts_at_zero, tick);
  loop.Run(out);
  for (auto& t : threads) t.join();
  if (!out.ok) return out;
  ChunkMerger& merger = loop.Merger();
  out.first_mismatch = merger.FirstMismatch();
  out.verifier = merger.TakeVerifier();
  out.timed = merger.Timed();
  out.poses = std::move(merger.Poses());
  out.start = merger.FirstStart();
  out.end = merger.Last()->end;
  return out;
}

}  // namespace stitchsim::run
