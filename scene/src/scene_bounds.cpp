#include "scene_bounds.h"

#include <cmath>
#include <sstream>

#include "stitchsim/common/limits.h"
#include "stitchsim/geom/curve.h"

namespace stitchsim::scene::detail {

bool CheckMeshExtent(YamlReader& r, const YAML::Node& file_node,
                     const std::filesystem::path& stl_file, const geom::TriangleMesh& mesh) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    if (v.allFinite() && v.cwiseAbs().maxCoeff() <= limits::kMaxLengthMm) continue;
    std::ostringstream text;
    text << "STL file " << stl_file.string() << ": vertex " << i << " at (" << v.x() << ", "
         << v.y() << ", " << v.z() << ") mm lies beyond the "
         << static_cast<long>(limits::kMaxLengthMm)
         << " mm (1 km) a coordinate may have (docs/limits.md)";
    r.Error(file_node, "bad-mesh", text.str());
    return false;
  }
  return true;
}

bool CheckStitchCount(YamlReader& r, const YAML::Node& item, const PathSpec& path,
                      const geom::Surface& surface, double nominal_stitch_mm) {
  const double length_mm = geom::SurfacePath(surface, *path.curve).Length();
  // As the stitch planner counts (planner/src/stitch_planner.cpp), which keeps its own check
  // for a --stitch-length given on the command line.
  if (length_mm / nominal_stitch_mm <= static_cast<double>(limits::kMaxStitchesPerPath) + 1.0) {
    return true;
  }
  r.Error(item, "too-many-stitches",
          "path '" + path.name + "' (" + std::to_string(length_mm) + " mm) would take more than " +
              std::to_string(limits::kMaxStitchesPerPath) + " stitches of " +
              std::to_string(nominal_stitch_mm) +
              " mm (stitch.nominal_length), the limit for one path (docs/limits.md)");
  return false;
}

}  // namespace stitchsim::scene::detail
