#pragma once
// Shared by the run library's tests: a bundled scene loaded, a small programme planned on it,
// a scratch folder removed afterwards.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/raster_planner.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/verify/afp_laid_material.h"

namespace stitchsim::run::testing {

/// An empty laid-material record of a head of `tows` tows `width_mm` wide, stations at most
/// `spacing_mm` apart (the laid-material tests build their strips into it).
inline verify::LaidMaterial EmptyLaid(int tows, double width_mm, double spacing_mm) {
  verify::LaidMaterial m;
  m.tows = tows;
  m.tow_width_mm = width_mm;
  m.spacing_mm = spacing_mm;
  return m;
}

inline std::filesystem::path SourceDir() { return std::filesystem::path(STITCHSIM_SOURCE_DIR); }

inline std::string AllDiagnostics(const DiagnosticSink& sink) {
  std::string out;
  for (const auto& d : sink.Diagnostics()) out += FormatDiagnostic(d) + "\n";
  return out;
}

/// A bundled scene (scenes/<name>.yaml) with its robot; fails the test on any diagnostic.
inline LoadedScene Bundled(const std::string& name) {
  DiagnosticSink sink;
  std::optional<LoadedScene> loaded =
      LoadScene(SourceDir() / "scenes" / (name + ".yaml"), scene::LoadOptions{}, sink);
  EXPECT_TRUE(loaded && sink.Diagnostics().empty()) << AllDiagnostics(sink);
  return loaded ? std::move(*loaded) : LoadedScene{};
}

/// A folder of its own under the system's temporary folder, removed with this object.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("stitchsim-run-test-" + name + "-" +
               std::to_string(::testing::UnitTest::GetInstance()->random_seed()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// The decoupled programme of the scene's first path, written to `file`.
inline void PlanFirstPath(const LoadedScene& loaded, const std::string& file) {
  DiagnosticSink sink;
  const scene::Scene& scene = *loaded.scene;
  planner::StitchPlanOptions options;
  options.mode = planner::Mode::kDecoupled;
  auto p = planner::StitchPathPlanner::Create(scene, scene.paths.front(), options, sink);
  ASSERT_TRUE(p) << AllDiagnostics(sink);
  std::ofstream out(file, std::ios::binary);
  planner::WriteStitchProgram(*p, scene, scene.paths.front().name, program::Dialect::Default(),
                              out);
}

/// The jump raster of a 4 in square corner of the scene's preform (840 stitches, about 900
/// lines: cut into a couple of dozen chunks at 10 lines), written to `file`.
inline void PlanSmallRaster(const LoadedScene& loaded, const std::string& file) {
  DiagnosticSink sink;
  planner::RasterOptions o = planner::RasterOptionsFor(*loaded.scene);
  o.region = Eigen::AlignedBox2d(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(101.6, 101.6));
  std::ofstream out(file, std::ios::binary);
  ASSERT_TRUE(planner::WriteRasterProgram(*loaded.scene, o, program::Dialect::Default(), out, sink))
      << AllDiagnostics(sink);
}

}  // namespace stitchsim::run::testing
