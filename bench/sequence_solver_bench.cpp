// Ordering one precedence set (issue 13, S9; seed 004): the whole solver call on a plate of
// parallel courses laid in a bad (random) order, bidirectional, L1 over 8 machine axes.
// 250 and 1,000 courses: 25 / 40 bands across the plate, courses 25 mm apart in each band.
// Run the Release build:
//   build/bench/sequence_solver_bench --benchmark_counters_tabular=true
// Aim (issue 13, Done-when 5): 1,000 courses in one set sequenced within 2 s.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "bench_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/sequence_solver.h"

namespace stitchsim::planner {
namespace {

// Axes: x, y, z (mm), three head angles (rad), rail (mm), rotator (rad). Laid backwards the
// head is turned by pi and the lift-off differs, so moves are not symmetric.
SequenceProblem Plate(int courses) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> jitter(-2.0, 2.0);
  const int bands = courses >= 1000 ? 40 : 25;
  const int per_band = courses / bands;
  SequenceProblem p;
  p.dim = 8;
  p.bidirectional = true;
  p.norm = CostNorm::kL1;
  p.weights = {1, 1, 1, 100, 100, 100, 1, 100};
  p.start = {-500, -500, 300, 0, 0, 0, 0, 0};
  std::vector<int> slot(static_cast<std::size_t>(bands * per_band));
  std::iota(slot.begin(), slot.end(), 0);
  std::shuffle(slot.begin(), slot.end(), rng);
  for (int s : slot) {
    const double x0 = (s / per_band) * 700.0 + jitter(rng), x1 = x0 + 600.0 + jitter(rng);
    const double y = (s % per_band) * 25.0 + jitter(rng);
    double fwd[2][8] = {{x0, y, 0, 0, 0.1, 0, 0.3 * x0, 0}, {x1, y, 0, 0, 0.1, 0, 0.3 * x1, 0}};
    double back[2][8];
    std::copy(fwd[1], fwd[1] + 8, back[0]);
    std::copy(fwd[0], fwd[0] + 8, back[1]);
    back[0][3] = back[1][3] = kPi;
    back[1][2] = 5.0;
    for (const double* row : {+fwd[0], +fwd[1], +back[0], +back[1]})
      p.points.insert(p.points.end(), row, row + 8);
    ++p.courses;
  }
  return p;
}

void Report(benchmark::State& state, const SequenceProblem& p, const SequenceSolution& s) {
  std::vector<Visit> given;
  for (int c = 0; c < p.courses; ++c) given.push_back({c, false});
  state.counters["courses"] = p.courses;
  state.counters["cost_given"] = PathCost(p, given);
  state.counters["cost"] = s.cost;
  state.counters["iterations"] = static_cast<double>(s.iterations);
  state.counters["peak_rss_MiB"] = static_cast<double>(bench::PeakRssKb()) / 1024.0;
}

void BM_LocalSearch(benchmark::State& state) {
  const SequenceProblem p = Plate(static_cast<int>(state.range(0)));
  SequenceSolution s;
  for (auto _ : state) {
    s = SolveLocalSearch(p);
    benchmark::DoNotOptimize(s.order.data());
  }
  Report(state, p, s);
}
BENCHMARK(BM_LocalSearch)->Arg(250)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SeedMethod(benchmark::State& state) {
  const SequenceProblem p = Plate(static_cast<int>(state.range(0)));
  SequenceSolution s;
  for (auto _ : state) {
    s = SolveSeedMethod(p);
    benchmark::DoNotOptimize(s.order.data());
  }
  Report(state, p, s);
}
BENCHMARK(BM_SeedMethod)->Arg(250)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace stitchsim::planner

BENCHMARK_MAIN();
