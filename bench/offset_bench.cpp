// Offset curves (seed 002) per second: 790 offsets of d = 3.81 mm (the seed's wing count and
// tow width) on a doubly curved bowl z = (x^2 + y^2) / 10 m (radius 5 m), from a reference
// curve 800 mm long sampled to 0.01 mm, by the paper's method and by the corrected one.
// Run the Release build:
//   build/bench/offset_bench --benchmark_counters_tabular=true
// Aim (issue 12): the 790 offsets in under 1 s. Rates are per CPU second of this process.

#include <benchmark/benchmark.h>

#include "stitchsim/planner/offset_curves.h"

namespace stitchsim::planner {
namespace {

constexpr int kOffsets = 790;
constexpr double kTowWidthMm = 3.81;

void BM_Offsets(benchmark::State& state) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(2, 0) = 1e-4;
  c(0, 2) = 1e-4;
  geom::Domain2 dom;
  dom.min = Eigen::Vector2d(-500, -200);
  dom.max = Eigen::Vector2d(500, 3200);
  const auto surface = geom::MakePolynomialHeightField(c, dom);
  FiberAxis axis;
  axis.start_mm = Eigen::Vector3d(-400, 0, 500);
  axis.end_mm = Eigen::Vector3d(400, 0, 500);
  const ReferenceCurve ref = ProjectFiberAxis(*surface, axis, 0.01);
  OffsetOptions o;
  o.distance_mm = kTowWidthMm;
  o.count = kOffsets;
  o.method = state.range(0) == 0 ? OffsetMethod::kPaper : OffsetMethod::kCorrected;
  OffsetFamily f;
  for (auto _ : state) {
    f = OffsetCurves(*surface, ref.points, o);
    if (!f.ok) state.SkipWithError(f.message.c_str());
    benchmark::DoNotOptimize(f.curves.back().back().position);
  }
  if (f.ok) {
    const OffsetDrift drift = MeasureDrift(*surface, f, kTowWidthMm, ref.points.size() / 2);
    state.counters["drift_pct_of_d"] = drift.drift_mm / kTowWidthMm * 100;
  }
  state.SetLabel(state.range(0) == 0 ? "paper" : "corrected");
  state.counters["points_per_curve"] = static_cast<double>(ref.points.size());
  state.counters["offsets_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kOffsets, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Offsets)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stitchsim::planner

BENCHMARK_MAIN();
