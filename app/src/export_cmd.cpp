// `stitchsim export-step`: the scene's surface (part frame) as one B-spline face of a STEP or
// IGES file, for another CAD tool. CAD surfaces give their own kernel surface; the others an
// interpolating bicubic patch, and the command prints the largest deviation it measured.
#include <stdlib.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "cli_common.h"
#include "commands.h"
#include "stitchsim/common/files.h"
#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/geom/surface_export.h"

namespace stitchsim::app {
namespace {

constexpr double kToleranceMm = 0.001;

struct ExportArgs {
  std::string scene;
  std::string output;
  std::string format = "step";
  std::string unit = "mm";
};

// The kernel writes to a path: a private temporary file, read back and then written whole or
// not at all to the target. Empty text and `error` set on failure.
std::string WriteCadText(const geom::SurfaceBSpline& patch, const std::string& name,
                         geom::CadFormat format, const std::string& unit, std::string& error) {
  std::string tmpl = (std::filesystem::temp_directory_path() / "stitchsim_export_XXXXXX").string();
  const int fd = mkstemp(tmpl.data());
  if (fd < 0) {
    error = "cannot create a temporary file";
    return "";
  }
  close(fd);
  std::string text;
  if (geom::WriteBSplineCad({patch.spec}, {name}, tmpl, format, unit, error)) {
    const FileText file = ReadRegularFile(tmpl, 1ULL << 32);
    if (file.ok()) {
      text = file.text;
    } else {
      error = file.error;
    }
  }
  std::remove(tmpl.c_str());
  return text;
}

int RunExport(const ExportArgs& a) {
  DiagnosticSink sink;
  const auto scene = scene::LoadScene(a.scene, sink, SceneLoadOptions());
  if (PrintDiagnostics(sink) || !scene) return kExitBadInput;
  std::string error;
  const auto patch = geom::SurfaceToBSpline(*scene->surface, kToleranceMm, error);
  if (!patch) {
    PrintError("export-failed", a.scene + ": " + scene->surface->Kind() + " surface: " + error);
    return kExitBadInput;
  }
  const std::map<std::string, std::string> units = {
      {"mm", "MM"}, {"cm", "CM"}, {"m", "M"}, {"inch", "INCH"}};
  const geom::CadFormat format =
      a.format == "iges" ? geom::CadFormat::kIges : geom::CadFormat::kStep;
  // The IGES writer carries a reversed face by reversing the surface's u, which would not
  // keep (u, v): IGES gets the face unreversed (its normal dP/du x dP/dv), and says so.
  geom::SurfaceBSpline written = *patch;
  const bool iges_flipped = format == geom::CadFormat::kIges && written.spec.flip_normal;
  if (iges_flipped) written.spec.flip_normal = false;
  const std::string text = WriteCadText(written, scene->name, format, units.at(a.unit), error);
  if (text.empty()) {
    PrintError("export-failed", a.output + ": " + error);
    return kExitBadInput;
  }
  if (std::string err = WriteFileAtomically(a.output, text); !err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  const std::size_t nu = patch->spec.poles.size();
  const std::size_t nv = nu ? patch->spec.poles[0].size() : 0;
  std::printf(
      "%s: %s surface as one %s B-spline face, degree %d x %d, %zu x %zu poles (%s); "
      "largest deviation %.3g mm -> %s (%s, %s)\n",
      scene->name.c_str(), scene->surface->Kind().c_str(),
      patch->spec.weights.empty() ? "polynomial" : "rational", patch->spec.degree_u,
      patch->spec.degree_v, nu, nv,
      patch->converted ? "the kernel's own surface" : "interpolated on a grid",
      patch->max_deviation_mm, a.output.c_str(), a.format.c_str(), a.unit.c_str());
  if (iges_flipped) {
    std::printf(
        "%s: the IGES face's normal points away from the head: read it back with "
        "flip_normal: true\n",
        scene->name.c_str());
  }
  return kExitOk;
}

}  // namespace

void AddExportStepCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd =
      app.add_subcommand("export-step",
                         "Write the scene's surface (part frame) as one B-spline face of a STEP or "
                         "IGES file");
  cmd->add_option("--scene", args->scene, "Scene YAML file")->required();
  cmd->add_option("-o,--output", args->output, "Output CAD file")->required();
  cmd->add_option("--format", args->format, "step | iges")->check(CLI::IsMember({"step", "iges"}));
  cmd->add_option("--unit", args->unit, "Length unit written in the file: mm | cm | m | inch")
      ->check(CLI::IsMember({"mm", "cm", "m", "inch"}));
  AddScenePathFlag(*cmd);
  cmd->callback([args, &exit_code] { exit_code = RunExport(*args); });
}

}  // namespace stitchsim::app
