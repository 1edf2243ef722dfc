// The seed-001 wing cover at full size (1.66 million stitches with the scene's raster
// defaults): plan it with both strategies (streamed to a file) and verify each programme
// in-process as `stitchsim verify` does, every rule including the FCL collision rules (the
// world also given to the executor for its between-samples guarantee), reporting wall time,
// stitches/s and resident memory per step, for half and full span, so that memory that grew
// with the programme would show. Every rule must pass.
// Usage: raster_bench [--plan-only] [--half-only] [--no-collision]

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "bench_support.h"
#include "stitchsim/planner/raster_planner.h"
#include "stitchsim/sim/collision.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"

namespace {

using stitchsim::bench::CurrentRssKb;
using stitchsim::bench::PeakRssKb;

using namespace stitchsim;
namespace fs = std::filesystem;
constexpr double kInch = 25.4;

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void Row(const char* step, const char* strategy, const char* size, long stitches, double s,
         const std::string& extra) {
  std::printf(
      "%-7s %-10s %-5s %9ld stitches %8.2f s %10.0f stitches/s  peak RSS %7.1f MiB  "
      "RSS %7.1f MiB  %s\n",
      step, strategy, size, stitches, s, static_cast<double>(stitches) / s,
      static_cast<double>(PeakRssKb()) / 1024.0, static_cast<double>(CurrentRssKb()) / 1024.0,
      extra.c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bool plan_only = false, half_only = false, collision = true;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--plan-only") == 0) plan_only = true;
    if (std::strcmp(argv[i], "--half-only") == 0) half_only = true;
    if (std::strcmp(argv[i], "--no-collision") == 0) collision = false;
  }
  DiagnosticSink sink;
  auto scene =
      scene::LoadScene(fs::path(STITCHSIM_SOURCE_DIR) / "scenes" / "wing_cover.yaml", sink);
  if (!scene) return 1;
  auto robot = sim::LoadRobotModel(scene->cell_urdf, sink);
  if (!robot) return 1;
  const fs::path dir = fs::temp_directory_path() / "stitchsim_raster_bench";
  fs::create_directories(dir);
  const program::Dialect& dialect = program::Dialect::Default();
  const planner::RasterOptions defaults = planner::RasterOptionsFor(*scene);
  std::printf(
      "wing_cover: 480 x 96 in, pitch %.3f in, rows %.3f in, margin %.2f in, collision %s; "
      "start peak RSS %.1f MiB\n",
      defaults.pitch_mm / kInch, defaults.row_spacing_mm / kInch, defaults.margin_mm / kInch,
      collision ? "on" : "off", static_cast<double>(PeakRssKb()) / 1024.0);
  for (const char* size : {"half", "full"}) {
    if (half_only && std::strcmp(size, "full") == 0) break;
    for (auto strategy : {planner::RasterStrategy::kJump, planner::RasterStrategy::kSerpentine}) {
      const std::string name(planner::ToString(strategy));
      planner::RasterOptions o = defaults;
      o.strategy = strategy;
      if (std::strcmp(size, "half") == 0) {
        o.region =
            Eigen::AlignedBox2d(Eigen::Vector2d(-240, -48) * kInch, Eigen::Vector2d(0, 48) * kInch);
      }
      const fs::path file = dir / ("wing_" + name + "_" + size + ".nc");
      auto t0 = std::chrono::steady_clock::now();
      std::optional<planner::RasterSummary> sum;
      {
        std::ofstream out(file, std::ios::binary);
        sum = planner::WriteRasterProgram(*scene, o, dialect, out, sink);
      }
      if (!sum) return 1;
      Row("plan", name.c_str(), size, sum->stitches, Seconds(t0),
          std::to_string(sum->jumps) + " jumps, " +
              std::to_string(fs::file_size(file) / (1024 * 1024)) + " MiB text");
      if (plan_only) continue;
      t0 = std::chrono::steady_clock::now();
      const sim::CellSetup cell = sim::MakeCellSetup(*robot, *scene);
      const process::ProcessModel model = process::MakeProcessModel(*scene, o.pitch_mm);
      std::unique_ptr<sim::CollisionWorld> world;
      if (collision) {
        world = sim::CollisionWorld::Create(*scene, *robot, sink);
        if (!world) return 1;
      }
      const trace::CellDescription cell_description = sim::DescribeCell(*robot, world.get());
      verify::RuleContext ctx{scene.get(), &cell_description, &model};
      verify::Verifier verifier(ctx, false);
      std::ifstream in(file, std::ios::binary);
      sim::ExecuteOptions options = sim::ExecuteOptionsFor(*scene);
      options.collision = world.get();
      sim::ExecuteProgram(cell, model, dialect, in, file.string(), options, sink, verifier);
      verify::Report report;
      verifier.Finish(report);
      std::string errors;
      for (const auto& r : report.rules) {
        if (r.errors > 0) errors += " " + r.id + "=" + std::to_string(r.errors);
      }
      Row("verify", name.c_str(), size, report.stitches, Seconds(t0),
          std::to_string(report.rules.size()) +
              " rules; errors:" + (errors.empty() ? std::string(" none") : errors));
    }
  }
  return 0;
}
