#pragma once
// A scene file read with the robot model of the cell it names: what every run starts from.

#include <filesystem>
#include <memory>
#include <optional>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::run {

/// A loaded scene and its cell's robot model (both owned; never null once loaded).
struct LoadedScene {
  std::unique_ptr<scene::Scene> scene;     ///< owned; its files resolved against its folder
  std::unique_ptr<sim::RobotModel> robot;  ///< owned; from scene->cell_urdf
};

/// Loads the scene and the cell URDF it names, reporting into `sink`; nullopt on any error.
std::optional<LoadedScene> LoadScene(const std::filesystem::path& scene_file,
                                     const scene::LoadOptions& options, DiagnosticSink& sink);

}  // namespace stitchsim::run
