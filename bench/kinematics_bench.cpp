// FK/s and IK solves/s on the cell model (Google Benchmark). Run from anywhere: the model is
// found through stitchsim::DataDir().

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "stitchsim/common/files.h"
#include "stitchsim/sim/kinematics.h"
#include "stitchsim/sim/robot_model.h"

namespace {

using stitchsim::sim::JointVector;
using stitchsim::sim::RobotModel;

const RobotModel& Cell() {
  static const RobotModel model = [] {
    stitchsim::DiagnosticSink sink;
    auto loaded =
        stitchsim::sim::LoadRobotModel(stitchsim::DataDir() / "models/isaac_cell.urdf", sink);
    if (!loaded) {
      for (const auto& d : sink.Diagnostics()) {
        std::fprintf(stderr, "%s\n", stitchsim::FormatDiagnostic(d).c_str());
      }
      std::abort();
    }
    return *std::move(loaded);
  }();
  return model;
}

// Joint vectors within limits, and their flange poses, fixed seed.
struct Samples {
  std::vector<JointVector> joints;
  std::vector<Eigen::Isometry3d> flange;
};

const Samples& Poses() {
  static const Samples samples = [] {
    Samples s;
    std::mt19937_64 rng(3);
    const RobotModel& model = Cell();
    for (int n = 0; n < 1024; ++n) {
      JointVector q;
      for (int i = 0; i < stitchsim::sim::kNumJoints; ++i) {
        std::uniform_real_distribution<double> d(model.lower_limits()(i), model.upper_limits()(i));
        q(i) = d(rng);
      }
      s.joints.push_back(q);
      s.flange.push_back(stitchsim::sim::FlangePose(model, q));
    }
    return s;
  }();
  return samples;
}

void BM_ForwardKinematicsAllLinks(benchmark::State& state) {
  const RobotModel& model = Cell();
  const Samples& s = Poses();
  stitchsim::sim::LinkFrames frames = stitchsim::sim::MakeLinkFrames(model);
  std::size_t i = 0;
  for (auto _ : state) {
    stitchsim::sim::ForwardKinematics(model, s.joints[i++ & 1023], frames);
    benchmark::DoNotOptimize(frames.world_pose.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ForwardKinematicsAllLinks);

void BM_FlangePose(benchmark::State& state) {
  const RobotModel& model = Cell();
  const Samples& s = Poses();
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Isometry3d pose = stitchsim::sim::FlangePose(model, s.joints[i++ & 1023]);
    benchmark::DoNotOptimize(pose);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FlangePose);

void BM_AllArmIkSolutions(benchmark::State& state) {
  const RobotModel& model = Cell();
  const Samples& s = Poses();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1023;
    auto all =
        stitchsim::sim::AllArmIkSolutions(model, s.flange[k], s.joints[k](stitchsim::sim::kRailX));
    benchmark::DoNotOptimize(all);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AllArmIkSolutions);

void BM_SolveIkWithPrevious(benchmark::State& state) {
  const RobotModel& model = Cell();
  const Samples& s = Poses();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1023;
    auto result = stitchsim::sim::SolveIk(model, s.flange[k], s.joints[k](stitchsim::sim::kRailX),
                                          &s.joints[k]);
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SolveIkWithPrevious);

}  // namespace

BENCHMARK_MAIN();
