#pragma once
// A scene (scenes/*.yaml): the part on its mount, the stitching surface, preform, mold,
// constraints, named paths and stitch parameters, plus the head. Format: docs/scene-format.md.
// Inside, part-frame lengths are millimetres and cell transforms are metres.

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/curve.h"
#include "stitchsim/geom/surface.h"
#include "stitchsim/scene/head_spec.h"
#include "stitchsim/scene/laminate.h"
#include "stitchsim/scene/ply.h"

namespace stitchsim::scene {

enum class Mount { kTable, kRotator };

/// An obstacle that must not be stitched through (stringer, intercostal, spar cap).
struct Constraint {
  std::string name;
  enum class Shape { kBox, kMesh } shape = Shape::kBox;
  Eigen::Isometry3d pose_mm = Eigen::Isometry3d::Identity();  ///< box centre, part frame
  Eigen::Vector3d size_mm = Eigen::Vector3d::Zero();          ///< box full extents
  geom::TriangleMesh mesh;                                    ///< part frame, mm
  SourceLocation where;
};

/// A named path: a 2D curve in the surface's (u, v) domain.
struct PathSpec {
  std::string name;
  std::string type;  ///< line | arc | circle | polyline | slot
  std::unique_ptr<geom::Curve2> curve;
  SourceLocation where;
};

struct Scene {
  std::filesystem::path file;
  std::string name;
  LengthUnit units = LengthUnit::kMillimetre;  ///< unit of lengths in the file
  std::filesystem::path cell_urdf;
  std::filesystem::path cell_mjcf;
  HeadSpec head;
  Mount mount = Mount::kTable;
  Eigen::Isometry3d mount_to_part_m = Eigen::Isometry3d::Identity();  ///< metres
  std::unique_ptr<geom::Surface> surface;
  double preform_thickness_mm = 12.0;
  double mold_depth_mm = 50.0;
  std::vector<Constraint> constraints;
  std::vector<PathSpec> paths;
  std::vector<PlySpec> plies;           ///< AFP plies (`plies:`), in lay-up order
  std::vector<LaminateSpec> laminates;  ///< `laminates:`; their inline plies end `plies`
  std::vector<MaterialSpec> materials;  ///< `materials:`, in file order (the plies name them)
  double nominal_stitch_length_mm = 5.0;
  RuleLimits limits;            ///< the head's limits overridden key by key by the scene's
  double rail_offset_mm = 0.0;  ///< rail policy: carriage x minus tool x (world), preferred
  /// Raster stitching defaults (`raster:`), mm; the planner's options override them.
  struct RasterDefaults {
    std::optional<double> pitch_mm, row_spacing_mm, margin_mm;
  } raster;
  /// Cell fixtures absent from this set-up (`cell.omit`): their geometry is left out of
  /// rendering and collision checks; their frames stay (kinematics unchanged).
  std::vector<std::string> omitted_fixtures;

  /// True when the top-level MJCF body `body` (a child of the world) belongs to an omitted
  /// fixture.
  bool OmitsMjcfBody(const std::string& body) const;
  /// The stitch length a run uses, mm: `given_mm` (a programme header's, a planner option's)
  /// when set, else this scene's nominal (the one place this fallback lives).
  double StitchLengthMm(std::optional<double> given_mm) const {
    return given_mm.value_or(nominal_stitch_length_mm);
  }

  const PathSpec* FindPath(const std::string& path_name) const;
  const PlySpec* FindPly(const std::string& ply_name) const;
};

/// The cell fixtures a scene may omit, and the top-level MJCF body of each.
struct CellFixture {
  const char* name;
  const char* mjcf_body;
};
inline constexpr CellFixture kCellFixtures[] = {{"table", "table"}, {"rotator", "rotator_base"}};

/// Loads and validates a scene. Every problem is a diagnostic with file:line:col and a
/// stable code ("scene-..."); returns nullptr if any error was reported.
/// Files it names must lie where `options` allows (docs/scene-format.md).
std::unique_ptr<Scene> LoadScene(const std::filesystem::path& file, DiagnosticSink& sink,
                                 const LoadOptions& options = {});

/// The shortest tow piece the cell may lay, mm: the scene's `afp.min_tow_length` limit, else
/// the head's cutter-to-roller distance; nullopt when neither is given. The ply planner mends
/// pieces to it and afp.min_tow_length judges against it.
std::optional<double> MinTowLengthMm(const Scene& scene);
/// The shortest distance from a tow's cut to its restart, mm: the scene's
/// `afp.restart_distance` limit, else the head's `min_restart_mm`; nullopt when neither.
std::optional<double> MinRestartMm(const Scene& scene);

}  // namespace stitchsim::scene
