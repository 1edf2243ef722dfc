#pragma once
// Reads a scene's `laminates:` list (docs/scene-format.md) into scene::LaminateSpec, after the
// plies are read: named stack plies resolve to Scene::plies, inline ones are read by the ply
// reader and appended there. Every problem with a laminate is `scene-bad-laminate` (an inline
// ply's own problems `scene-bad-ply`) at its file:line.

#include <yaml-cpp/yaml.h>

#include "stitchsim/common/units.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene::detail {

/// Appends the laminates of `root["laminates"]` (optional) to scene.laminates and their
/// inline plies to scene.plies; errors go to the reader.
void ReadLaminates(YamlReader& r, const YAML::Node& root, LengthUnit unit, Scene& scene);

}  // namespace stitchsim::scene::detail
