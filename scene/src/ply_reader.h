#pragma once
// Reads a scene's `plies:` list (docs/scene-format.md) into scene::PlySpec, after the surface
// and the head are read, and the `materials:` list the plies name (read first). Every problem
// with a ply is `scene-bad-ply`, with a material `scene-bad-material` (or the reader's
// number codes), at its file:line.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "stitchsim/common/units.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene::detail {

/// True when `s` is a name a ply or laminate may have: not empty; letters, digits, '_', '-'.
bool SceneNameOk(const std::string& s);

/// A 0 deg reference as a ply's `reference:` and a laminate's `rosette:` give it. Part frame.
struct ReferenceAxes {
  Eigen::Vector3d origin_mm;   ///< mm (converted from the scene unit)
  Eigen::Vector3d direction;   ///< unit vector
  Eigen::Vector3d projection;  ///< unit vector; default minus the normal at the origin's foot
};

/// Reads `origin`, `direction` and the optional `projection` of the map `ref` and checks that
/// the reference projects onto `surface`: a non-zero direction and projection, an origin whose
/// foot point lies on the surface, a direction along neither the surface normal there nor the
/// projection. Each problem is `code` at the offending key; nullopt then.
std::optional<ReferenceAxes> ReadReferenceAxes(YamlReader& r, const YAML::Node& ref,
                                               LengthUnit unit, const geom::Surface& surface,
                                               std::string_view code);

/// How a laminate's inline stack ply is read: its generated name, and the rosette it takes
/// its reference from when it gives none of its own.
struct InlinePly {
  std::string name;
  ReferenceAxes rosette;
};

/// Reads `item` as a `plies:` entry is read (scene-bad-ply problems), except that it has no
/// `name` (it gets `inline_ply.name`), its `reference` is optional (the rosette's), and it may
/// carry the stack entry's `material` and `thickness` (read by the laminate reader).
std::optional<PlySpec> ReadInlinePly(YamlReader& r, const YAML::Node& item, LengthUnit unit,
                                     const Scene& scene, const InlinePly& inline_ply);

/// The list `root[key]` when given, a non-empty sequence of at most `most` items; nullopt when
/// absent, or not such a list (reported as `code` at it).
std::optional<YAML::Node> SceneList(YamlReader& r, const YAML::Node& root, std::string_view key,
                                    std::string_view code, std::size_t most);

/// Appends the materials of `root["materials"]` (optional) to scene.materials, then the plies
/// of `root["plies"]` (optional) to scene.plies; errors go to the reader.
void ReadPlies(YamlReader& r, const YAML::Node& root, LengthUnit unit, Scene& scene);

}  // namespace stitchsim::scene::detail
