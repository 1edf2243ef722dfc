// Verify a decoupled raster programme end to end (parse, modal state, IK, needle windows,
// every rule); report stitches/s and the peak resident memory, for two programme lengths so
// that memory that grows with the programme would show.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench_support.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"

namespace {

using stitchsim::bench::PeakRssKb;

using namespace stitchsim;
namespace fs = std::filesystem;

// A flat panel on the table.
fs::path WriteScene() {
  const fs::path dir = fs::temp_directory_path() / "stitchsim_verify_bench";
  fs::create_directories(dir);
  const fs::path scene = dir / "raster.yaml";
  std::ofstream(scene) << "stitchsim_scene: 1\nname: raster\nunits: mm\nhead: rs535\n"
                          "part: {mount: table, position: [0, 0, 50]}\n"
                          "surface: {type: plane, size: [1000, 700]}\n"
                          "paths: [{name: row, type: line, from: [-250, 0], to: [250, 0]}]\n";
  return scene;
}

// A decoupled raster: rows of 100 stitches of 5 mm, 0.5 mm apart, alternating direction;
// between rows the needles are out and the head repositions and turns (no U advance).
fs::path WriteProgram(long stitches) {
  const fs::path file = fs::temp_directory_path() / "stitchsim_verify_bench" /
                        ("raster_" + std::to_string(stitches) + ".nc");
  std::ofstream out(file);
  out << "%\n(STITCHSIM scene=raster head=rs535 stitch_length_mm=5)\nG21 G90\nT1 M6\n";
  const long rows = std::max(1L, stitches / 100);
  double u = 0.0;
  char buf[160];
  for (long r = 0; r < rows; ++r) {
    const double y = -250.0 + 0.5 * static_cast<double>(r);
    const bool forward = r % 2 == 0;
    const double x0 = forward ? -250.0 : 250.0;
    const double dir = forward ? 1.0 : -1.0;
    const int c = forward ? -90 : 90;
    std::snprintf(buf, sizeof(buf), "G0 X%.6g Y%.6g Z0 A0 B0 C%d U%.6f V%.6f\nM10\n", x0, y, c, u,
                  u);
    out << buf;
    for (int i = 1; i <= 100; ++i) {
      u += 5.0;
      std::snprintf(buf, sizeof(buf), "G1 X%.6g U%.6f V%.6f%s\nG1 C%d\n", x0 + dir * 5.0 * i, u, u,
                    i == 1 ? " F1500" : "", c);
      out << buf;
    }
    out << "M11\n";
  }
  out << "M30\n%\n";
  return file;
}

struct Prepared {
  std::unique_ptr<scene::Scene> scene;
  std::unique_ptr<sim::RobotModel> robot;
  fs::path program;
  double stitch_length_mm = 5.0;
  long stitches = 0;
};

Prepared Prepare(long stitches) {
  Prepared p;
  DiagnosticSink sink;
  p.scene = scene::LoadScene(WriteScene(), sink);
  p.robot = std::make_unique<sim::RobotModel>(*sim::LoadRobotModel(p.scene->cell_urdf, sink));
  p.program = WriteProgram(stitches);
  p.stitches = std::max(1L, stitches / 100) * 100;
  return p;
}

void BM_VerifyDecoupledRaster(benchmark::State& state) {
  const Prepared p = Prepare(state.range(0));
  const sim::CellSetup cell = sim::MakeCellSetup(*p.robot, *p.scene);
  const process::ProcessModel model = process::MakeProcessModel(*p.scene, p.stitch_length_mm);
  const long rss_before = PeakRssKb();
  std::string verdict;
  for (auto _ : state) {
    const trace::CellDescription cell_description = sim::DescribeCell(*p.robot, nullptr);
    verify::RuleContext ctx{p.scene.get(), &cell_description, &model};
    verify::Verifier verifier(ctx, false);
    DiagnosticSink sink;
    std::ifstream in(p.program, std::ios::binary);
    const auto run =
        sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, p.program.string(),
                            sim::ExecuteOptionsFor(*p.scene), sink, verifier);
    verify::Report report;
    verifier.Finish(report);
    verdict = report.verdict;
    if (!run.ok || report.stitches != p.stitches || report.verdict != "pass") {
      state.SkipWithError("verification failed");
    }
  }
  state.SetItemsProcessed(state.iterations() * p.stitches);
  state.counters["stitches"] = static_cast<double>(p.stitches);
  state.counters["stitches_per_s"] = benchmark::Counter(
      static_cast<double>(p.stitches), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["peak_rss_MiB"] = static_cast<double>(PeakRssKb()) / 1024.0;
  state.counters["rss_growth_MiB"] = static_cast<double>(PeakRssKb() - rss_before) / 1024.0;
  state.SetLabel(verdict);
}
BENCHMARK(BM_VerifyDecoupledRaster)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
