#include "stitchsim/run/loaded_scene.h"

namespace stitchsim::run {

std::optional<LoadedScene> LoadScene(const std::filesystem::path& scene_file,
                                     const scene::LoadOptions& options, DiagnosticSink& sink) {
  LoadedScene out;
  out.scene = scene::LoadScene(scene_file, sink, options);
  if (out.scene) {
    auto robot = sim::LoadRobotModel(out.scene->cell_urdf, sink);
    if (robot) out.robot = std::make_unique<sim::RobotModel>(std::move(*robot));
  }
  if (sink.HasErrors() || !out.scene || !out.robot) return std::nullopt;
  return out;
}

}  // namespace stitchsim::run
