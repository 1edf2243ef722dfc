#pragma once
// Shared by the picture tests: a bundled scene loaded as `stitchsim verify` loads it, its
// rules' context, and a finished verifier with one planted sample: joint a5 beyond its upper
// limit on line 7 (a kin.joint_limit error, the rule's worst sample).

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "stitchsim/common/units.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/start_pose.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run::testing {

inline constexpr int kPlantedLine = 7;
inline constexpr double kPlantedExcessDeg = 10.0;

struct PlantedRun {
  LoadedScene ls;
  std::unique_ptr<process::ProcessModel> process;
  trace::CellDescription cell;
  std::unique_ptr<verify::Verifier> verifier;
  verify::Report report;
  trace::TraceSample planted;
};

/// scenes/<name>.yaml verified over the one planted sample.
inline std::unique_ptr<PlantedRun> PlantJointLimit(const std::string& name) {
  auto run = std::make_unique<PlantedRun>();
  DiagnosticSink sink;
  const auto path = std::filesystem::path(STITCHSIM_SOURCE_DIR) / "scenes" / (name + ".yaml");
  std::optional<LoadedScene> ls = LoadScene(path, scene::LoadOptions{}, sink);
  EXPECT_FALSE(sink.HasErrors()) << path;
  if (!ls) return nullptr;
  run->ls = std::move(*ls);
  run->process = std::make_unique<process::ProcessModel>(
      process::MakeProcessModel(*run->ls.scene, run->ls.scene->nominal_stitch_length_mm));
  run->cell = sim::DescribeCell(*run->ls.robot, nullptr);
  run->verifier = std::make_unique<verify::Verifier>(
      verify::RuleContext{run->ls.scene.get(), &run->cell, run->process.get()}, true);
  trace::TraceSample& s = run->planted;
  s.source_line = kPlantedLine;
  s.has_joints = true;
  s.ik_status = trace::IkStatus::kJointLimit;
  s.joints = sim::HomeJoints(*run->ls.robot, 0.0);
  s.joints[trace::kA5] = run->cell.upper_limits[trace::kA5] + kPlantedExcessDeg * kDeg;
  s.tool_part = PathStartTool(*run->ls.scene, run->ls.scene->paths.front());
  run->verifier->OnSample(s);
  run->verifier->Finish(run->report);
  return run;
}

/// The rule `id` of the run's verifier (null when it did not run).
inline const verify::Rule* RuleOf(const PlantedRun& run, const std::string& id) {
  for (const auto& r : run.verifier->Rules()) {
    if (r->Summary().id == id) return r.get();
  }
  return nullptr;
}

}  // namespace stitchsim::run::testing
