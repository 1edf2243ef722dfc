#pragma once
// Composes the MuJoCo model of a scene: the cell MJCF with the head bolted to the flange and
// the part (mold, preform, constraints) on its mount, and loads it from memory.

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::render {

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

/// Names of the geoms stitchsim adds, for segmentation and highlighting.
inline constexpr const char* kMoldGeom = "part_mold";
inline constexpr const char* kPreformGeom = "part_preform";
inline constexpr const char* kConstraintGeomPrefix = "constraint_";
/// Geom group of omitted cell fixtures (scene `cell.omit`): never drawn.
inline constexpr int kHiddenGeomGroup = 5;

/// The model geoms of a collision-world body (trace::CellDescription::bodies): "head:<geom>"
/// is the head geom of that name, "mold" / "preform" the part's slabs, "constraint:<name>"
/// that constraint, a link or cell body name ("link_3", "rail", "carriage") that body's own
/// geoms, else a world geom of that name ("floor"). Empty when the model has none.
std::vector<int> GeomsOfCollisionBody(const mjModel& model, const std::string& body);
/// The geoms attached to body `body_id` itself (not its children), in id order.
std::vector<int> GeomsOfBody(const mjModel& model, int body_id);

/// The MJCF text of the whole scene (cell + head + part).
std::string ComposeSceneMjcf(const scene::Scene& scene, DiagnosticSink& sink);

/// Composes and compiles the scene; a MuJoCo compile error becomes a diagnostic.
MjModelPtr LoadSceneModel(const scene::Scene& scene, DiagnosticSink& sink);

}  // namespace stitchsim::render
