// Collision checks per pose on the full cell with each head (Google Benchmark): the collision
// world (per-body near lists under a motion bound, oriented-box bounds, pair table, objects
// updated in place) against a naive baseline in the same run (every checked pair, no broad
// phase, FCL objects and BVHs rebuilt for each query). Poses are the joints of a decoupled
// programme executed on the scene, cycled; each query's a6 is moved by a different
// nanoradian so the world's result cache never answers (every query is a miss).

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/collision.h"
#include "stitchsim/sim/executor.h"

namespace {

using namespace stitchsim;

[[noreturn]] void Fail(const DiagnosticSink& sink) {
  for (const auto& d : sink.Diagnostics())
    std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
  std::abort();
}

class JointCollector : public sim::TraceSink {
 public:
  void OnLine(const sim::LineRecord&) override {}
  void OnSample(const sim::TraceSample& s) override {
    if (s.has_joints && s.ik_status == sim::IkStatus::kOk) joints.push_back(s.joints);
  }
  std::vector<sim::JointVector> joints;
};

struct Fixture {
  std::unique_ptr<scene::Scene> scene;
  std::unique_ptr<sim::RobotModel> robot;
  std::unique_ptr<sim::CollisionWorld> world;
  std::vector<sim::JointVector> joints;
};

// Poses for a stitching scene: its first path planned decoupled and executed. For the AFP head
// (no stitch planner): the stitching poses of flat_straight, same cell, AFP head on; or the
// scene's own AFP course at normal pressure.
Fixture& Get(const std::string& scene_name, const std::string& poses_from) {
  static std::map<std::string, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[scene_name + "|" + poses_from];
  if (slot) return *slot;
  slot = std::make_unique<Fixture>();
  Fixture& f = *slot;
  DiagnosticSink sink;
  f.scene = scene::LoadScene(DataDir() / "scenes" / (scene_name + ".yaml"), sink);
  if (!f.scene) Fail(sink);
  auto robot = sim::LoadRobotModel(f.scene->cell_urdf, sink);
  if (!robot) Fail(sink);
  f.robot = std::make_unique<sim::RobotModel>(std::move(*robot));
  f.world = sim::CollisionWorld::Create(*f.scene, *f.robot, sink);
  if (!f.world) Fail(sink);
  auto source = scene::LoadScene(DataDir() / "scenes" / (poses_from + ".yaml"), sink);
  if (!source) Fail(sink);
  std::ostringstream text;
  if (source->head.IsStitching()) {
    planner::StitchPlanOptions options;
    options.mode = planner::Mode::kDecoupled;
    auto plan = planner::StitchPathPlanner::Create(*source, source->paths.front(), options, sink);
    if (!plan) Fail(sink);
    planner::WriteStitchProgram(*plan, *source, source->paths.front().name,
                                program::Dialect::Default(), text);
  } else {
    // The AFP course at normal pressure (--lay-angle 45 --incline 0): the feed module in
    // the mold on most poses (slab contacts, docs/collision.md "Depth").
    planner::AfpPlanOptions options;
    options.lay_angle_rad = 45.0 * kPi / 180.0;
    auto plan = planner::PlanAfpCourse(*source, nullptr, options, sink);
    if (!plan) Fail(sink);
    planner::WriteAfpProgram(*plan, *source, program::Dialect::Default(), text);
  }
  std::istringstream in(text.str());
  const sim::CellSetup cell = sim::MakeCellSetup(*f.robot, *source);
  const process::ProcessModel model =
      process::MakeProcessModel(*source, source->nominal_stitch_length_mm);
  JointCollector collect;
  sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, "bench.nc",
                      sim::ExecuteOptionsFor(*source), sink, collect);
  f.joints = std::move(collect.joints);
  if (f.joints.size() < 100) std::abort();
  return f;
}

void Run(benchmark::State& state, const std::string& scene_name, const std::string& poses_from,
         bool naive, bool clearance) {
  Fixture& f = Get(scene_name, poses_from);
  sim::CollisionOptions options;
  options.naive_baseline = naive;
  options.compute_clearance = clearance;
  std::size_t i = 0;
  long contacts = 0;
  long n = 0;
  for (auto _ : state) {
    sim::JointVector q = f.joints[i];
    q[sim::kA6] += 1e-9 * static_cast<double>(++n % 1000000);
    const sim::CollisionResult r = f.world->Check(q, options);
    contacts += static_cast<long>(r.contacts.size());
    benchmark::DoNotOptimize(r.min_clearance_m);
    i = (i + 1) % f.joints.size();
  }
  state.counters["poses"] = static_cast<double>(f.joints.size());
  state.counters["contacts_per_pose"] =
      benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kAvgIterations);
}

void Register() {
  struct Case {
    const char* label;
    const char* scene;
    const char* poses;
  };
  const Case cases[] = {{"rs535", "flat_straight", "flat_straight"},
                        {"rs566", "rs566_stringer_seam", "rs566_stringer_seam"},
                        {"afp", "concave_cylinder_small", "flat_straight"},
                        {"afp_in_mold", "concave_cylinder_small", "concave_cylinder_small"}};
  for (const Case& c : cases) {
    for (bool clearance : {false, true}) {
      for (bool naive : {false, true}) {
        const std::string name = std::string("Collision/") + c.label +
                                 (clearance ? "/contacts+clearance" : "/contacts") +
                                 (naive ? "/naive" : "/world");
        const std::string scene = c.scene, poses = c.poses;
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
          Run(s, scene, poses, naive, clearance);
        })->Unit(benchmark::kMicrosecond);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Register();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
