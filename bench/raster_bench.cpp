// The seed-001 wing cover at full size (1.66 million stitches with the scene's raster
// defaults): plan it with both strategies (streamed to a file) and verify each programme
// in-process as `stitchsim verify` does, every rule including the FCL collision rules (the
// world also given to the executor for its between-samples guarantee), reporting wall time,
// stitches/s and resident memory per step, for half and full span, so that memory that grew
// with the programme would show. Every rule must pass. First, planning in a surface's own
// (u, v): the same skin as an OCCT B-spline (a Bezier patch, scene kind `bspline`) against the
// polynomial, a 30 x 20 in window and the whole cover, jump, planned and written to a null
// stream.
// Usage: raster_bench [--plan-only] [--half-only] [--no-collision] [--cad-only]

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
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

// wing_cover.yaml with its skin as a `bspline` surface (z = -0.002 y^2 in inches is a Bezier
// patch: degree 1 along x, 2 along y) and its path moved into the patch's (u, v).
std::unique_ptr<scene::Scene> BSplineWingCover(const fs::path& dir, DiagnosticSink& sink) {
  std::ifstream in(fs::path(STITCHSIM_SOURCE_DIR) / "scenes" / "wing_cover.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t surface = text.find("\nsurface:\n"), preform = text.find("\npreform:");
  const std::size_t paths = text.find("\npaths:");
  if (surface == std::string::npos || preform == std::string::npos || paths == std::string::npos)
    return nullptr;
  text = text.substr(0, surface) +
         "\nsurface:\n  type: bspline\n  degree: [1, 2]\n  poles:\n"
         "    - [[-240, -48, -4.608], [-240, 0, 4.608], [-240, 48, -4.608]]\n"
         "    - [[240, -48, -4.608], [240, 0, 4.608], [240, 48, -4.608]]" +
         text.substr(preform, paths - preform) +
         "\npaths:\n  - {name: bay_row, type: line, from: [210, 26], to: [270, 26]}\n";
  const fs::path file = dir / "wing_cover_bspline.yaml";
  std::ofstream(file, std::ios::binary) << text;
  return scene::LoadScene(file, sink);
}

// Plans `o` on `s` to a null stream: one line of timing.
bool PlanLine(const scene::Scene& s, const planner::RasterOptions& o, const char* what,
              const char* size, DiagnosticSink& sink) {
  std::ostream null(nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  const auto sum = planner::WriteRasterProgram(s, o, program::Dialect::Default(), null, sink);
  if (!sum) return false;
  Row("plan", what, size, sum->stitches, Seconds(t0),
      std::to_string(sum->rows) + " rows, " + std::to_string(sum->jumps) + " jumps");
  return true;
}

// The polynomial skin and the B-spline one, jump, over a window (part frame x, y in inches;
// the B-spline's (u, v) window from the closest points of its corners) and the whole cover.
bool CadLines(const scene::Scene& poly, const fs::path& dir, DiagnosticSink& sink) {
  const auto bspline = BSplineWingCover(dir, sink);
  if (!bspline) return false;
  const Eigen::AlignedBox2d window_in(Eigen::Vector2d(-55, -18), Eigen::Vector2d(-25, 2));
  for (const char* size : {"30x20", "full"}) {
    planner::RasterOptions o = planner::RasterOptionsFor(poly);
    planner::RasterOptions ob = o;
    if (std::strcmp(size, "full") != 0) {
      o.region = Eigen::AlignedBox2d(window_in.min() * kInch, window_in.max() * kInch);
      Eigen::AlignedBox2d uv;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d xy =
            window_in.corner(static_cast<Eigen::AlignedBox2d::CornerType>(k));
        const Eigen::Vector3d p(xy.x(), xy.y(), -0.002 * xy.y() * xy.y());
        uv.extend(bspline->surface->Project(p * kInch).uv);
      }
      ob.region = uv;
    }
    if (!PlanLine(poly, o, "poly", size, sink) || !PlanLine(*bspline, ob, "bspline", size, sink))
      return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  bool plan_only = false, half_only = false, collision = true, cad_only = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--plan-only") == 0) plan_only = true;
    if (std::strcmp(argv[i], "--half-only") == 0) half_only = true;
    if (std::strcmp(argv[i], "--no-collision") == 0) collision = false;
    if (std::strcmp(argv[i], "--cad-only") == 0) cad_only = true;
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
  if (!CadLines(*scene, dir, sink)) {
    for (const auto& d : sink.Diagnostics())
      std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
    return 1;
  }
  if (cad_only) return 0;
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
