#pragma once
// Reads a scene's `plies:` list (docs/scene-format.md) into scene::PlySpec, after the surface
// and the head are read, and the `materials:` list the plies name (read first). Every problem
// with a ply is `scene-bad-ply`, with a material `scene-bad-material` (or the reader's
// number codes), at its file:line.

#include <yaml-cpp/yaml.h>

#include "stitchsim/common/units.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene::detail {

/// Appends the materials of `root["materials"]` (optional) to scene.materials, then the plies
/// of `root["plies"]` (optional) to scene.plies; errors go to the reader.
void ReadPlies(YamlReader& r, const YAML::Node& root, LengthUnit unit, Scene& scene);

}  // namespace stitchsim::scene::detail
