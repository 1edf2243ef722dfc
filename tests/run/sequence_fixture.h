#pragma once
// Sequencing tests' inputs: plies of scenes/seq_plate.yaml planned by the ply planner (the
// library, not the CLI) into one programme file, and the run's inputs loaded from it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/sequence_run.h"

namespace stitchsim::run::test {

inline const std::filesystem::path kSeqPlate =
    std::filesystem::path(STITCHSIM_SOURCE_DIR) / "scenes" / "seq_plate.yaml";

/// A folder of this test process's own (removed by the caller's fixture, if it likes).
inline std::filesystem::path SequenceTestDir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("run_sequence_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

/// Plans `plies` of seq_plate (or of `scene`), in that order, into `file` (one M70 each).
inline void PlanSeqPlate(const std::vector<std::string>& plies, const std::filesystem::path& file,
                         const std::filesystem::path& scene = kSeqPlate) {
  DiagnosticSink sink;
  const auto loaded = LoadScene(scene, {}, sink);
  ASSERT_TRUE(loaded.has_value());
  std::vector<planner::PlyPlan> plans;
  for (const std::string& name : plies) {
    const scene::PlySpec* ply = loaded->scene->FindPly(name);
    ASSERT_NE(ply, nullptr) << name;
    auto plan = planner::PlanPly(*loaded->scene, *ply, {}, sink);
    ASSERT_TRUE(plan.has_value()) << name;
    plans.push_back(std::move(*plan));
  }
  std::vector<const planner::PlyPlan*> ptrs;
  for (const auto& p : plans) ptrs.push_back(&p);
  std::ofstream out(file, std::ios::binary);
  planner::WritePlyProgram(ptrs, *loaded->scene, program::Dialect::Default(), out);
}

/// Options for a run of `programme` on seq_plate (or on `scene`).
inline SequenceOptions SeqPlateOptions(const std::filesystem::path& programme,
                                       const std::filesystem::path& scene = kSeqPlate) {
  SequenceOptions o;
  o.program_file = programme.string();
  o.scene_file = scene.string();
  o.output_file = "out.nc";
  return o;
}

/// The run's inputs; fails the test on any diagnostic error or error.
inline SequenceInputs LoadOrFail(const SequenceOptions& o) {
  DiagnosticSink sink;
  SequenceError error;
  auto in = LoadSequenceInputs(o, sink, error);
  EXPECT_FALSE(sink.HasErrors()) << (sink.Diagnostics().empty() ? std::string()
                                                                : sink.Diagnostics()[0].message);
  EXPECT_TRUE(error.code.empty()) << error.code << ": " << error.message;
  if (!in) throw std::runtime_error("sequence inputs did not load");
  return std::move(*in);
}

}  // namespace stitchsim::run::test
