#pragma once
// A fibre-placement ply as the scene gives it (`plies:`, docs/scene-format.md): where on the
// surface it lies, which way its fibres run, and how the planner fills and cuts it. The
// planner (`stitchsim plan ply`) fills it with courses of the head's tows; the afp.* rules
// judge what the programme lays against it. Lengths in mm (converted from the scene unit),
// angles in radians, part frame.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"

namespace stitchsim::scene {

/// How the courses of a ply follow its fibre angle (seed 002, "a choice for the designer").
enum class PlyRule {
  /// Band offset ply: one reference course at the ply angle, every other course an offset of
  /// its neighbour by the course width (no gaps or overlaps by construction; the angle drifts
  /// on a doubly curved surface).
  kOffset,
  /// Laminate family ply: each course's reference is a laminate family curve at the ply angle
  /// to the offset curves of the 0 deg reference (angle kept, gaps and overlaps where courses
  /// converge or diverge, controlled by the coverage policy).
  kLaminateFamily,
};

/// The ply's reference course (`reference: path:`); every other course is an offset of it.
enum class ReferencePath {
  /// The fibre axis projected onto the surface along `projection` (seed 002).
  kProjected,
  /// The surface geodesic from the origin's foot point along the turned direction: no
  /// steering in the reference, so its offsets steer least.
  kGeodesic,
  /// The streamline through the origin's foot point of the design direction field: at each
  /// surface point the reference direction projected into the tangent plane along
  /// `projection`, turned by the ply angle about the normal (the direction afp.fiber_angle
  /// judges against): the reference keeps the design angle everywhere.
  kConstantAngle,
};

/// Which offset construction fills the ply (planner/offset_curves.h).
enum class PlyOffsetMethod { kPaper, kCorrected };

/// Ply thickness and areal weight when a ply names no material: assumptions (domain.md, a
/// typical carbon/epoxy prepreg tow; no datasheet of the scene's material is given).
inline constexpr double kDefaultPlyThicknessMm = 0.18;
inline constexpr double kDefaultArealWeightGM2 = 300.0;

/// A material the plies are laid of (the scene's `materials:`).
struct MaterialSpec {
  std::string name;
  SourceLocation where;                               ///< its entry in the scene
  double ply_thickness_mm = kDefaultPlyThicknessMm;   ///< cured ply thickness, mm (> 0)
  double areal_weight_g_m2 = kDefaultArealWeightGM2;  ///< fibre + resin per area, g/m^2 (> 0)
};

struct PlySpec {
  std::string name;
  SourceLocation where;  ///< the ply's entry in the scene (diagnostics name it)
  /// Fibre angle from the reference direction, turning about the surface normal (right-handed
  /// about the normal that points to the head), radians.
  double angle_rad = 0.0;
  /// The 0 deg direction: the fibre axis is the line through `origin_mm` along `direction`
  /// turned by the angle about the normal at the origin's foot point, projected onto the
  /// surface along `projection` (seed 002, Fig. 3). Part frame.
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  Eigen::Vector3d projection = -Eigen::Vector3d::UnitZ();
  /// How the reference course runs (`reference: path:`, ReferencePath above).
  ReferencePath reference_path = ReferencePath::kProjected;
  /// The ply boundary, a closed polygon in the surface's (u, v) (mm; the scene may give it in
  /// 3D, projected onto the surface along `projection`, or in (u, v)). Counter-clockwise.
  std::vector<Eigen::Vector2d> boundary_uv;
  PlyRule rule = PlyRule::kOffset;
  PlyOffsetMethod method = PlyOffsetMethod::kCorrected;
  /// Coverage policy: a tow is cut (and restarted) where this fraction of its width has
  /// crossed the boundary: 0 (cut as soon as its edge reaches the boundary: gaps, no tow
  /// past the edge), 0.5 (at its centre line), 1 (when wholly outside: full coverage,
  /// material past the edge). Seed 002 / commercial AFP programming: 0, 50 or 100 %.
  double coverage = 0.5;
  /// Tows per course, from the head spec unless the ply narrows it (<= head tows).
  int tows = 0;
  /// The ply's `material:` (a name among the scene's `materials:`), "" when none is given;
  /// its thickness (mm) and areal weight (g/m^2), else the defaults above (assumptions).
  std::string material;
  double thickness_mm = kDefaultPlyThicknessMm;
  double areal_weight_g_m2 = kDefaultArealWeightGM2;
};

}  // namespace stitchsim::scene
