// A whole fibre-placement ply planned (PlanPly) and its programme and tow CSV written, timed
// per ply. Run the Release build:
//   build/bench/ply_bench                       the bundled panel's plies (scenes/afp_panel.yaml)
//   build/bench/ply_bench SCENE [PLY ...]       the given scene's plies (all when none named)
// Prints per ply: courses, tow segments, events, programme bytes, plan and write seconds.

#include <chrono>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "bench_support.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/scene/scene.h"

int main(int argc, char** argv) {
  using namespace stitchsim;
  using Clock = std::chrono::steady_clock;
  const std::string file =
      argc > 1 ? argv[1] : std::string(STITCHSIM_SOURCE_DIR) + "/scenes/afp_panel.yaml";
  DiagnosticSink sink;
  const auto scene = scene::LoadScene(file, sink);
  for (const auto& d : sink.Diagnostics())
    std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
  if (!scene) return 2;
  std::vector<std::string> names;
  for (int i = 2; i < argc; ++i) names.push_back(argv[i]);
  if (names.empty())
    for (const auto& p : scene->plies) names.push_back(p.name);
  std::printf("%-16s %8s %9s %8s %12s %9s %9s\n", "ply", "courses", "segments", "events", "bytes",
              "plan_s", "write_s");
  for (const std::string& name : names) {
    const scene::PlySpec* ply = scene->FindPly(name);
    if (ply == nullptr) {
      std::fprintf(stderr, "no ply '%s'\n", name.c_str());
      return 2;
    }
    const auto t0 = Clock::now();
    const auto plan = planner::PlanPly(*scene, *ply, {}, sink);
    const auto t1 = Clock::now();
    if (!plan) {
      for (const auto& d : sink.Diagnostics())
        std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
      return 2;
    }
    bench::CountingSink counter;
    std::ostream out(&counter);
    planner::WritePlyProgram(*plan, *scene, program::Dialect::Default(), out);
    planner::WritePlyTowsCsv(*plan, out);
    const auto t2 = Clock::now();
    std::printf("%-16s %8zu %9d %8d %12llu %9.3f %9.3f\n", name.c_str(), plan->courses.size(),
                plan->tow_segments, plan->events, static_cast<unsigned long long>(counter.bytes),
                std::chrono::duration<double>(t1 - t0).count(),
                std::chrono::duration<double>(t2 - t1).count());
  }
  return 0;
}
