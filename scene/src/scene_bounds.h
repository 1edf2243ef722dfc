#pragma once
// Scene checks past the reading of single values: bounds on what a scene's STL files hold and
// on the stitches its paths ask for, so every command that loads the scene refuses the same
// scenes (docs/limits.md).

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "stitchsim/geom/surface.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene::detail {

/// False, reported as "scene-bad-mesh" at `file_node` (the entry naming the STL), when a
/// vertex of `mesh` (mm) lies beyond limits::kMaxLengthMm of the origin on any axis.
bool CheckMeshExtent(YamlReader& r, const YAML::Node& file_node,
                     const std::filesystem::path& stl_file, const geom::TriangleMesh& mesh);

/// False, reported as "scene-too-many-stitches" at `item`, when `path` on `surface` would
/// take more than limits::kMaxStitchesPerPath stitches of `nominal_stitch_mm`.
bool CheckStitchCount(YamlReader& r, const YAML::Node& item, const PathSpec& path,
                      const geom::Surface& surface, double nominal_stitch_mm);

}  // namespace stitchsim::scene::detail
