#pragma once
// Shared by the verify tests: a scene and its robot loaded the way `stitchsim verify` loads
// them, failing the test on any diagnostic.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::verify::testing {

struct Loaded {
  std::unique_ptr<scene::Scene> scene;
  std::unique_ptr<sim::RobotModel> robot;
};

/// The scene file `path` and its cell.
inline Loaded LoadFile(const std::filesystem::path& path) {
  DiagnosticSink sink;
  Loaded l;
  l.scene = scene::LoadScene(path, sink);
  EXPECT_NE(l.scene, nullptr) << path;
  if (!l.scene) return l;
  auto robot = sim::LoadRobotModel(l.scene->cell_urdf, sink);
  EXPECT_TRUE(robot.has_value()) << path;
  if (robot) l.robot = std::make_unique<sim::RobotModel>(std::move(*robot));
  return l;
}

/// The bundled scene `name` (scenes/<name>.yaml).
inline Loaded Load(const std::string& name) {
  return LoadFile(std::filesystem::path(STITCHSIM_SOURCE_DIR) / "scenes" / (name + ".yaml"));
}

}  // namespace stitchsim::verify::testing
