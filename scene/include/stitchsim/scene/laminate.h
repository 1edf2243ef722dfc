#pragma once
// A laminate as the scene gives it (`laminates:`, docs/scene-format.md): an ordered stack of
// plies laid one on another, the rosette their fibre angles are measured from, and the stagger
// rule their course seams keep. The scene loader reads and validates it (scene/src/
// laminate_reader.cpp); `plan laminate` and the afp.* rules read it. Lengths in mm (converted
// from the scene unit), part frame. Owned by scene::Scene (Scene::laminates).

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"

namespace stitchsim::scene {

/// One ply of a laminate's stack, bottom first.
struct LaminateStackEntry {
  /// The ply: an index into Scene::plies (a named `plies:` entry, or the inline ply the
  /// loader appended there under the name `<laminate>/<position from 1>`).
  std::size_t ply = 0;
  /// True when the ply was given inline in the stack (and appended to Scene::plies by the
  /// loader); false for a named `plies:` entry.
  bool inline_ply = false;
  /// The material's name (`material:`, one of Scene::materials), empty when not given. The
  /// loader sets the ply's material, thickness and areal weight in Scene::plies from it, and
  /// then the thickness below over them: read a stacked ply's data from its PlySpec.
  std::string material;
  /// The cured ply thickness (`thickness:`), mm, > 0; nullopt when not given. A named ply
  /// stacked twice with two thicknesses is an error.
  std::optional<double> thickness_mm;
  SourceLocation where;  ///< the stack entry in the scene
};

struct LaminateSpec {
  std::string name;      ///< unique among the laminates; [A-Za-z0-9_-]
  SourceLocation where;  ///< the laminate's entry in the scene
  /// The rosette: the laminate's 0 deg reference, read and checked as a ply's `reference:`
  /// (scene::PlySpec). An inline ply without a reference of its own takes these three.
  struct Rosette {
    Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();   ///< part frame, mm
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< part frame, unit vector
    /// Part frame, unit vector; default minus the surface normal at the origin's foot point.
    Eigen::Vector3d projection = -Eigen::Vector3d::UnitZ();
  } rosette;
  /// Stagger rule: course seams of same-angle plies must lie at least this far apart, mm,
  /// in [0, one course width (head tows x tow width)].
  double stagger_offset_mm = 0.0;
  /// ... and a seam position may repeat only after this many same-angle plies (>= 1).
  int stagger_plies_before_repeat = 1;
  std::vector<LaminateStackEntry> stack;  ///< bottom ply first; not empty
};

}  // namespace stitchsim::scene
