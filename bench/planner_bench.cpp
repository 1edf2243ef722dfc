// Stitch planner throughput: stitches per second for a 1-million-stitch straight row (a 5 km
// line on a 5.2 km plane) and a ~125,000-stitch circle (100 m radius), in each mode, with
// the programme written to a discarding stream (PlanAndWrite) and without writing
// (PlanOnly: StitchPathPlanner::Next alone). Planner creation (arc-length table) is timed
// too. Run the Release build:
//   build/bench/planner_bench --benchmark_counters_tabular=true
// Target: >= 1 million stitches/s. Rates are per CPU second of this process (the default
// timer), so a busy machine slows them less than it slows the wall clock.

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <streambuf>
#include <string>

#include "bench_support.h"
#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {
namespace {

using stitchsim::bench::CountingSink;

namespace fs = std::filesystem;

// Scenes written once to a temporary folder, loaded once, shared by every benchmark.
constexpr const char* kLineScene = R"(stitchsim_scene: 1
name: bench_line_5km
units: mm
head: rs535
part:
  mount: table
  position: [0, 0, 50]
surface:
  type: plane
  size: [5200000, 1000]
preform:
  thickness: 12
stitch:
  nominal_length: 5
paths:
  - name: row
    type: line
    from: [-2500000, 0]
    to: [2500000, 0]
)";

constexpr const char* kCircleScene = R"(stitchsim_scene: 1
name: bench_circle_100m
units: mm
head: rs535
part:
  mount: table
  position: [0, 0, 50]
surface:
  type: plane
  size: [210000, 210000]
preform:
  thickness: 12
stitch:
  nominal_length: 5
paths:
  - name: circle
    type: circle
    center: [0, 0]
    radius: 100000
    start_deg: -90
    direction: ccw
)";

class BenchScenes {
 public:
  static BenchScenes& Get() {
    static BenchScenes scenes;
    return scenes;
  }
  const scene::Scene& Line() const { return *line_; }
  const scene::Scene& Circle() const { return *circle_; }

 private:
  BenchScenes() {
    const fs::path dir =
        fs::temp_directory_path() / ("stitchsim_planner_bench_" + std::to_string(getpid()));
    fs::create_directories(dir);
    line_ = Load(dir / "line.yaml", kLineScene);
    circle_ = Load(dir / "circle.yaml", kCircleScene);
    std::error_code ec;
    fs::remove_all(dir, ec);
  }

  static std::unique_ptr<scene::Scene> Load(const fs::path& file, const char* text) {
    std::ofstream(file) << text;
    DiagnosticSink sink;
    auto s = scene::LoadScene(file, sink);
    if (!s) {
      for (const auto& d : sink.Diagnostics())
        std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
      std::abort();
    }
    return s;
  }

  std::unique_ptr<scene::Scene> line_;
  std::unique_ptr<scene::Scene> circle_;
};

const scene::Scene& SceneOf(int which) {
  return which == 0 ? BenchScenes::Get().Line() : BenchScenes::Get().Circle();
}

StitchPathPlanner MakePlanner(const scene::Scene& s, Mode mode) {
  DiagnosticSink sink;
  StitchPlanOptions options;
  options.mode = mode;
  auto planner = StitchPathPlanner::Create(s, s.paths.front(), options, sink);
  if (!planner) std::abort();
  return std::move(*planner);
}

void SetLabel(benchmark::State& state, int which, Mode mode) {
  state.SetLabel(std::string(which == 0 ? "line_5km/" : "circle_100m/") +
                 std::string(ToString(mode)));
}

// args: scene (0 line, 1 circle), mode (0 coupled, 1 decoupled, 2 auto)
void BM_PlanAndWrite(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const Mode mode = static_cast<Mode>(state.range(1));
  const scene::Scene& s = SceneOf(which);
  std::uint64_t stitches = 0, bytes = 0, decoupled = 0;
  for (auto _ : state) {
    StitchPathPlanner planner = MakePlanner(s, mode);
    CountingSink sink;
    std::ostream out(&sink);
    const ProgramSummary summary =
        WriteStitchProgram(planner, s, s.paths.front().name, program::Dialect::Default(), out);
    stitches += static_cast<std::uint64_t>(summary.stitches);
    decoupled += static_cast<std::uint64_t>(summary.decoupled);
    bytes += sink.bytes;
  }
  SetLabel(state, which, mode);
  state.counters["stitches/s"] =
      benchmark::Counter(static_cast<double>(stitches), benchmark::Counter::kIsRate);
  state.counters["stitches"] = static_cast<double>(stitches / state.iterations());
  state.counters["decoupled"] = static_cast<double>(decoupled / state.iterations());
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
BENCHMARK(BM_PlanAndWrite)->ArgsProduct({{0, 1}, {0, 1, 2}})->Unit(benchmark::kMillisecond);

void BM_PlanOnly(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const Mode mode = static_cast<Mode>(state.range(1));
  const scene::Scene& s = SceneOf(which);
  std::uint64_t stitches = 0;
  PlannedStitch stitch;
  for (auto _ : state) {
    StitchPathPlanner planner = MakePlanner(s, mode);
    while (planner.Next(stitch)) {
      benchmark::DoNotOptimize(stitch.end);
      ++stitches;
    }
  }
  SetLabel(state, which, mode);
  state.counters["stitches/s"] =
      benchmark::Counter(static_cast<double>(stitches), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PlanOnly)->ArgsProduct({{0, 1}, {0, 1, 2}})->Unit(benchmark::kMillisecond);

// Creating the planner alone: the arc-length table and the first two path points.
void BM_CreatePlanner(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const scene::Scene& s = SceneOf(which);
  for (auto _ : state) {
    StitchPathPlanner planner = MakePlanner(s, Mode::kAuto);
    benchmark::DoNotOptimize(planner.StitchCount());
  }
  state.SetLabel(which == 0 ? "line_5km" : "circle_100m");
}
BENCHMARK(BM_CreatePlanner)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace stitchsim::planner

BENCHMARK_MAIN();
