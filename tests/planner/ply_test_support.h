#pragma once
// Shared by the ply planner tests: scenes written to a scratch folder and loaded (a fixture
// fails on any diagnostic), plies in scene text.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include "stitchsim/scene/scene.h"

namespace stitchsim::planner::testing {

namespace fs = std::filesystem;

/// A fresh scratch folder per test process and name.
inline fs::path Folder(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("stitchsim_ply_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// The scene at `file`; a test failure for every diagnostic.
inline std::unique_ptr<scene::Scene> Load(const fs::path& file) {
  DiagnosticSink sink;
  auto s = scene::LoadScene(file, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return s;
}

/// A `plies:` section: per angle (degrees, space separated) a ply `p<angle>` with its
/// reference through the origin along x, the (u, v) `boundary` and `coverage` (percent).
inline std::string Plies(const std::string& boundary, int coverage,
                         const std::string& angles = "0 45") {
  std::string text = "plies:\n";
  std::istringstream in(angles);
  for (int a; in >> a;) {
    text += "  - name: p" + std::to_string(a) + "\n    angle_deg: " + std::to_string(a) +
            "\n    reference: {origin: [0, 0, 100], direction: [1, 0, 0]}\n    boundary_uv: " +
            boundary + "\n    coverage: " + std::to_string(coverage) + "\n";
  }
  return text;
}

/// A scene on the bundled AFP head with `surface` (its YAML lines) and `plies` (the `plies:`
/// section), with `extra` (YAML lines: limits ...) at its end.
inline std::string SceneText(const std::string& surface, const std::string& plies,
                             const std::string& extra = "") {
  return "stitchsim_scene: 1\nname: ply_test\nunits: mm\nhead: afp\npart:\n  mount: table\n"
         "  position: [0, -400, 50]\n" +
         surface +
         "preform:\n  thickness: 2\nmold:\n  depth: 40\npaths:\n  - name: row\n"
         "    type: line\n    from: [100, 100]\n    to: [200, 100]\n" +
         plies + extra;
}

}  // namespace stitchsim::planner::testing
