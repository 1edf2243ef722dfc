// Evaluation and closest points on an OCCT-backed surface (Google Benchmark): a bicubic
// 6 x 6 B-spline bump over 400 x 300 mm. "Near" projections walk a path in small steps (each
// starts from the last foot point); "cold" ones jump across the patch.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "stitchsim/geom/cad_surface.h"

namespace {

using stitchsim::geom::Surface;

const Surface& Bump() {
  static const auto surface = [] {
    stitchsim::geom::BSplineSpec spec;
    spec.degree_u = 3;
    spec.degree_v = 3;
    for (int i = 0; i < 6; ++i) {
      spec.poles.emplace_back();
      for (int k = 0; k < 6; ++k) {
        const double x = -200 + 80.0 * i, y = -150 + 60.0 * k;
        spec.poles.back().emplace_back(x, y, 40 * std::sin(x / 90) * std::cos(y / 70));
      }
    }
    std::string err;
    auto s = stitchsim::geom::MakeBSplineSurface(spec, err);
    if (!s) {
      std::fprintf(stderr, "%s\n", err.c_str());
      std::abort();
    }
    return s;
  }();
  return *surface;
}

// Points a few mm off the surface along a diagonal, in steps of about 0.3 mm.
std::vector<Eigen::Vector3d> Walk() {
  const Surface& s = Bump();
  const Eigen::Vector2d max = s.Domain().max;
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector2d uv = max * (0.1 + 0.8 * i / 1000.0);
    out.push_back(s.Point(uv) + 2.0 * s.Normal(uv));
  }
  return out;
}

void BM_Point(benchmark::State& state) {
  const Surface& s = Bump();
  const Eigen::Vector2d uv = s.Domain().max * 0.37;
  for (auto _ : state) benchmark::DoNotOptimize(s.Point(uv));
}
BENCHMARK(BM_Point);

void BM_Normal(benchmark::State& state) {
  const Surface& s = Bump();
  const Eigen::Vector2d uv = s.Domain().max * 0.37;
  for (auto _ : state) benchmark::DoNotOptimize(s.Normal(uv));
}
BENCHMARK(BM_Normal);

void BM_ProjectNear(benchmark::State& state) {
  const Surface& s = Bump();
  const auto walk = Walk();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.Project(walk[i]));
    i = (i + 1) % walk.size();
  }
}
BENCHMARK(BM_ProjectNear);

void BM_ProjectCold(benchmark::State& state) {
  const Surface& s = Bump();
  auto walk = Walk();
  std::shuffle(walk.begin(), walk.end(), std::mt19937(7));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.Project(walk[i]));
    i = (i + 1) % walk.size();
  }
}
BENCHMARK(BM_ProjectCold);

}  // namespace

BENCHMARK_MAIN();
