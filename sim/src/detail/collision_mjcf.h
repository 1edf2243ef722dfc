#pragma once
// Reads the robot, cell and head collision primitives from the MJCF files: the cell model with
// the head fragment inserted at its marker, compiled by MuJoCo (compiled geom frames are exact:
// fromto, euler and the like are resolved by the compiler).

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"

namespace stitchsim::sim::detail {

enum class MjcfShape { kBox, kSphere, kCapsule, kCylinder, kPlane };

/// One geom of the compiled model, posed in the frame of the nearest body that is a URDF link.
struct MjcfGeom {
  std::string name;      ///< geom name ("geom_<id>" when unnamed)
  std::string body;      ///< MuJoCo body that carries it
  std::string link;      ///< URDF link whose frame `pose_in_link` is in ("world" for body 0)
  std::string top_body;  ///< the world's child the geom hangs under ("" for world geoms)
  bool in_head = false;  ///< the geom comes from the head fragment
  MjcfShape shape = MjcfShape::kBox;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< MuJoCo geom_size (half extents, m)
  Eigen::Isometry3d pose_in_link = Eigen::Isometry3d::Identity();
};

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;

/// The cell model with the head's worldbody inserted at its marker (the head's bodies under a
/// body "stitchsim_head_root", which starts with `head_root_extra`, e.g. an <inertial>),
/// compiled by MuJoCo; null and a diagnostic with `code` on failure.
MjModelPtr CompileCellWithHead(const std::filesystem::path& cell_mjcf,
                               const std::filesystem::path& head_mjcf, DiagnosticSink& sink,
                               const std::string& head_root_extra = {},
                               const std::string& code = "collision-mjcf",
                               bool strip_geoms = false);

/// `xml` without its <geom> elements (bodies, joints, sites, inertials kept): a model for
/// kinematics and dynamics only (masses come from <inertial>), whose mj_kinematics does not
/// pose a geom it never uses.
std::string WithoutGeoms(const std::string& xml);

/// Compiles `cell_mjcf` with `head_mjcf` inserted at <!--STITCHSIM:HEAD--> and returns every
/// geom; `link_names` are the URDF links (bodies of those names share their frames). Codes
/// collision-mjcf, collision-unsupported-geom) and an empty vector on failure.
std::vector<MjcfGeom> LoadMjcfGeoms(const std::filesystem::path& cell_mjcf,
                                    const std::filesystem::path& head_mjcf,
                                    const std::vector<std::string>& link_names,
                                    DiagnosticSink& sink, bool& ok);

}  // namespace stitchsim::sim::detail
