// Programme text throughput on a 1-million-stitch decoupled programme (a start line, then a
// translation line and a rotation line per stitch: about 2 million lines, every axis with 6
// decimals). Run the Release build:
//   build/bench/program_bench --benchmark_counters_tabular=true
// Parse reports bytes/s (target >= 50 MB/s) and lines/s; Write the same for the writer;
// StreamingMemory parses a generated stream that never exists whole in memory and reports
// how much the resident set grew (it must not depend on the programme's length).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "bench_support.h"
#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {
namespace {

using stitchsim::bench::CountingSink;

constexpr int kStitches = 1'000'000;
constexpr double kStitchLengthMm = 5.0;
constexpr double kRadiusMm = 101.6;  // the 8 in circle
constexpr int kRing = 8192;          // distinct poses, reused cyclically by the generator

double Round6(double v) { return std::round(v * 1e6) / 1e6; }

// Poses of a decoupled stitch path around a slightly wavy circle, with cumulative U and V.
class StitchGenerator {
 public:
  StitchGenerator() {
    for (int i = 0; i < kRing; ++i) {
      const double theta = i * kStitchLengthMm / kRadiusMm + 0.0123456;
      Pose& p = ring_.emplace_back();
      p.x = Round6(kRadiusMm * std::sin(theta));
      p.y = Round6(kRadiusMm * std::cos(theta));
      p.z = Round6(0.25 * std::sin(i * 0.0137) + 0.1234567);
      p.a = Round6(0.5 * std::sin(i * 0.011) + 0.0000013);
      p.b = Round6(0.25 * std::cos(i * 0.017) - 0.0000021);
      p.c = Round6(std::remainder(-theta * 180.0 / kPi, 360.0) - 0.0000017);
    }
  }

  // Line `line` of the programme body: 0 = start, then translation/rotation per stitch.
  void Fill(long long line, Block& b) const {
    b.Clear();
    b.motion = Motion::kFeed;
    const long long stitch = line == 0 ? 0 : (line + 1) / 2;
    const bool rotation = line > 0 && line % 2 == 0;
    const Pose& at = ring_[static_cast<std::size_t>(stitch % kRing)];
    const Pose& angles = rotation ? ring_[static_cast<std::size_t>((stitch + 1) % kRing)] : at;
    b[Axis::kX] = at.x;
    b[Axis::kY] = at.y;
    b[Axis::kZ] = at.z;
    b[Axis::kA] = angles.a;
    b[Axis::kB] = angles.b;
    b[Axis::kC] = angles.c;
    b[Axis::kDrive] = static_cast<double>(stitch) * kStitchLengthMm + 0.000001 * (stitch % 7);
    b[Axis::kPathLength] = *b[Axis::kDrive];
    if (line == 0) {
      b.units = LengthUnit::kMillimetre;
      b.absolute = true;
      b.feed = 3000.0;
    }
  }

  static constexpr long long kBodyLines = 1 + 2LL * kStitches;

 private:
  struct Pose {
    double x, y, z, a, b, c;
  };
  std::vector<Pose> ring_;
};

ProgramHeader BenchHeader() {
  ProgramHeader header;
  header.entries = {{"scene", "circle_8in"},
                    {"head", "rs535"},
                    {"stitch_length_mm", "5.000000"},
                    {"mode", "decoupled"}};
  return header;
}

const std::string& ProgrammeText() {
  static const std::string text = [] {
    std::ostringstream out;
    {
      ProgramWriter writer(out, Dialect::Default());
      writer.WriteMark();
      writer.WriteHeader(BenchHeader());
      const StitchGenerator generator;
      Block block;
      for (long long line = 0; line < StitchGenerator::kBodyLines; ++line) {
        generator.Fill(line, block);
        writer.Write(block);
      }
      block.Clear();
      block.m_codes = {30};
      writer.Write(block);
      writer.WriteMark();
    }
    return out.str();
  }();
  return text;
}

// Reads a string in place (no copy into a stringstream).
class MemoryBuffer : public std::streambuf {
 public:
  explicit MemoryBuffer(const std::string& text) {
    char* begin = const_cast<char*>(text.data());
    setg(begin, begin, begin + text.size());
  }
};

// Generates the programme text on demand, a few thousand lines at a time.
class GeneratedProgramme : public std::streambuf {
 public:
  explicit GeneratedProgramme(long long body_lines) : body_lines_(body_lines) {}

 protected:
  int_type underflow() override {
    if (done_) return traits_type::eof();
    std::ostringstream out;
    {
      ProgramWriter writer(out, Dialect::Default());
      Block block;
      if (next_ == 0) writer.WriteMark();
      for (int k = 0; k < 4096 && next_ < body_lines_; ++k, ++next_) {
        generator_.Fill(next_, block);
        writer.Write(block);
      }
      if (next_ == body_lines_) {
        block.Clear();
        block.m_codes = {30};
        writer.Write(block);
        writer.WriteMark();
        done_ = true;
      }
    }
    chunk_ = out.str();
    setg(chunk_.data(), chunk_.data(), chunk_.data() + chunk_.size());
    return traits_type::to_int_type(chunk_[0]);
  }

 private:
  StitchGenerator generator_;
  long long body_lines_;
  long long next_ = 0;
  bool done_ = false;
  std::string chunk_;
};

double ResidentMiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kib = 0;
      status >> kib;
      return kib / 1024.0;
    }
    status.ignore(1 << 12, '\n');
  }
  return 0.0;
}

void SetRates(benchmark::State& state, std::uint64_t bytes, std::uint64_t lines) {
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes) * state.iterations());
  state.counters["lines_per_s"] =
      benchmark::Counter(static_cast<double>(lines) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
  state.counters["lines"] = static_cast<double>(lines);
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
}

void BM_Parse(benchmark::State& state) {
  const std::string& text = ProgrammeText();
  std::uint64_t lines = 0;
  for (auto _ : state) {
    MemoryBuffer buffer(text);
    std::istream in(&buffer);
    DiagnosticSink sink;
    ProgramReader reader(in, Dialect::Default(), "bench.nc", sink);
    Block block;
    std::uint64_t blocks = 0;
    while (reader.Next(block)) ++blocks;
    benchmark::DoNotOptimize(blocks);
    if (sink.HasErrors()) state.SkipWithError("unexpected diagnostics");
    lines = static_cast<std::uint64_t>(reader.LineCount());
  }
  SetRates(state, text.size(), lines);
}
BENCHMARK(BM_Parse)->Unit(benchmark::kMillisecond)->UseRealTime();

// What `stitchsim check` does: reader and modal state over every block.
void BM_ParseAndTrack(benchmark::State& state) {
  const std::string& text = ProgrammeText();
  std::uint64_t lines = 0;
  for (auto _ : state) {
    MemoryBuffer buffer(text);
    std::istream in(&buffer);
    DiagnosticSink sink;
    const CheckSummary summary = CheckProgram(in, Dialect::Default(), "bench.nc", sink);
    if (!summary.ok) state.SkipWithError("unexpected diagnostics");
    lines = static_cast<std::uint64_t>(summary.lines);
  }
  SetRates(state, text.size(), lines);
}
BENCHMARK(BM_ParseAndTrack)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Write(benchmark::State& state) {
  const StitchGenerator generator;
  // Blocks are prepared outside the timed loop so that only formatting is measured.
  std::vector<Block> ring(2 * kRing);
  for (std::size_t k = 0; k < ring.size(); ++k) generator.Fill(static_cast<long long>(k), ring[k]);
  std::uint64_t bytes = 0;
  std::uint64_t lines = 0;
  for (auto _ : state) {
    CountingSink sink;
    std::ostream out(&sink);
    {
      ProgramWriter writer(out, Dialect::Default());
      for (long long line = 0; line < StitchGenerator::kBodyLines; ++line) {
        writer.Write(ring[static_cast<std::size_t>(line % (2 * kRing))]);
      }
      lines = writer.LinesWritten();
    }
    bytes = sink.bytes;
  }
  SetRates(state, bytes, lines);
}
BENCHMARK(BM_Write)->Unit(benchmark::kMillisecond)->UseRealTime();

// Parses a generated stream of `state.range(0)` stitches; reports the growth of the
// resident set while parsing (sampled), which must stay flat as the programme grows.
void BM_StreamingMemory(benchmark::State& state) {
  const long long stitches = state.range(0);
  double growth_mib = 0.0;
  std::uint64_t bytes = 0;
  std::uint64_t lines = 0;
  for (auto _ : state) {
    GeneratedProgramme source(1 + 2 * stitches);
    std::istream in(&source);
    DiagnosticSink sink;
    const double before = ResidentMiB();
    double peak = before;
    {
      ProgramReader reader(in, Dialect::Default(), "stream.nc", sink);
      ModalState modal(Dialect::Default(), "stream.nc", sink);
      Block block;
      std::uint64_t blocks = 0;
      while (reader.Next(block)) {
        modal.Update(block);
        if ((++blocks & 0xFFFF) == 0) peak = std::max(peak, ResidentMiB());
      }
      peak = std::max(peak, ResidentMiB());
      bytes = reader.BytesRead();
      lines = static_cast<std::uint64_t>(reader.LineCount());
    }
    if (sink.HasErrors()) state.SkipWithError("unexpected diagnostics");
    growth_mib = peak - before;
  }
  SetRates(state, bytes, lines);
  state.counters["rss_growth_MiB"] = growth_mib;
}
BENCHMARK(BM_StreamingMemory)
    ->Arg(kStitches / 4)
    ->Arg(kStitches)
    ->Arg(4 * kStitches)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace stitchsim::program

BENCHMARK_MAIN();
