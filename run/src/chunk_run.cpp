#include <climits>
#include <cstdio>
#include <cstring>

#include "stitchsim/run/chunked.h"

namespace stitchsim::run {
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
  RunData data = MakeRunData(*setup.model);
  const RunModel& model = *setup.model;
  result.verifier = std::make_unique<verify::Verifier>(model.Rules(), setup.keep_stitch_marks);
  Gate gate(*result.verifier, result.chunk, lines_done);
  sim::TimingSink timing(*data.timing, *model.loaded.robot, model.timing, gate);
  gate.SetTiming(&timing);
  std::optional<PoseRecorder> recorder;
  if (setup.chunk_poses > 0) {
    result.poses = std::make_unique<PoseTrack>(setup.chunk_poses);
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
      sim::ExecuteChunk(model.cell, *model.process, model.dialect, setup.program_path, chunk,
                        data.execute, diagnostics, timing, hooks);
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
  if (result.poses) result.poses->Thin(PointedLines(*result.verifier), INT_MAX);
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

}  // namespace stitchsim::run
