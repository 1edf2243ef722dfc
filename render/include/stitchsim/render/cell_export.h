#pragma once
// The compiled MuJoCo model of a scene as data a browser can draw and pose (the HTML report's
// `cell`, docs/report-format.md "HTML report"): the body tree with each body's offset from its
// parent, its joint and its visible geoms, and the meshes (thinned by vertex clustering to a
// face budget). Posing is the browser's forward kinematics: MuJoCo's body frames, a hinge
// turning about its axis through its anchor, a slide moving along its axis.

#include <mujoco/mujoco.h>

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace stitchsim::render {

struct CellExportOptions {
  /// The joints a pose lists, in its order (URDF names: "rail_x", "a1".."a6", "rotator").
  std::array<std::string, 8> joints;
  /// Faces of all meshes together at most about this many (large meshes are thinned).
  std::size_t max_faces = 300000;
};

/// The JSON `cell` object; on a joint of `options.joints` missing from the model, `error` is
/// set and the result is null.
nlohmann::json ExportCell(const mjModel& model, const CellExportOptions& options,
                          std::string& error);

struct ThinnedMesh {
  std::vector<float> vertices;       ///< x y z, the mesh's frame, metres
  std::vector<std::uint32_t> faces;  ///< i j k
};

/// Vertex clustering: vertices snapped to a grid, merged per cell (their mean), faces that
/// collapse dropped; the grid is the finest power-of-two step that leaves at most
/// `max_faces` faces. A mesh already within the budget is returned as it is.
ThinnedMesh ThinMesh(const float* vertices, int vertex_count, const int* faces, int face_count,
                     std::size_t max_faces);

}  // namespace stitchsim::render
