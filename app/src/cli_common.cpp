#include "cli_common.h"

#include <iostream>

namespace stitchsim::app {

bool PrintDiagnostics(const DiagnosticSink& sink) {
  for (const auto& d : sink.Diagnostics()) std::cerr << FormatDiagnostic(d) << '\n';
  return sink.HasErrors();
}

void PrintError(const std::string& code, const std::string& message) {
  std::cerr << "stitchsim: error[" << code << "]: " << message << '\n';
}

std::optional<program::Dialect> DialectOption(const std::string& file) {
  if (file.empty()) return program::Dialect::Default();
  DiagnosticSink sink;
  auto dialect = program::LoadDialect(file, sink);
  if (PrintDiagnostics(sink) || !dialect) return std::nullopt;
  return dialect;
}

std::optional<LoadedScene> LoadSceneAndRobot(const std::filesystem::path& scene_file) {
  DiagnosticSink sink;
  LoadedScene out;
  out.scene = scene::LoadScene(scene_file, sink);
  if (out.scene) {
    auto robot = sim::LoadRobotModel(out.scene->cell_urdf, sink);
    if (robot) out.robot = std::make_unique<sim::RobotModel>(std::move(*robot));
  }
  if (PrintDiagnostics(sink) || !out.scene || !out.robot) return std::nullopt;
  return out;
}

}  // namespace stitchsim::app
