#pragma once
// The fibre-placement (AFP) course planner (seed 003): a course on the surface, the head
// axis along the surface normal (normal pressure) or leaned by theta along the course
// tangent (inclined pressure), and the B (swing) / C (about the vertical) angles of seed
// 003's 5-axis head per point. Frames and conventions: docs/afp.md.

#include <Eigen/Geometry>
#include <cmath>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/curve.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

/// Seed 003's head axes: the head axis (unit q, part frame, z up) is Rz(C) * Ry(B) * ez.
/// C = atan(q_y / q_x) in [-pi/2, pi/2]; B = acos(q_z), negative when q_x < 0. For
/// q_x = 0, C = +-pi/2 by the sign of q_y (seed eq. 12). Radians.
struct AfpHeadAxes {
  double b_rad = 0.0;
  double c_rad = 0.0;
};

/// B and C for head axis direction `q` (need not be unit).
AfpHeadAxes AfpHeadAxesFromDirection(const Eigen::Vector3d& q);

/// Seed 003 eq. (4), any surface: q = sin(theta) t + cos(theta) n, with t the course
/// direction made unit and orthogonal to the unit normal n. nullopt if t is along n.
std::optional<Eigen::Vector3d> InclinationVector(const Eigen::Vector3d& normal,
                                                 const Eigen::Vector3d& course_direction,
                                                 double incline_rad);

/// Seed 003's closed forms for the concave cylinder, in the seed's frame (x = cylinder
/// axis = our part x, z up). alpha: circumferential angle (normal (0, cos a, sin a));
/// seed_beta: the seed's laying angle (tangent (tan b, sin a, -cos a)), = pi/2 - our lay
/// angle; theta: inclination. Radians.
struct SeedCylinderPose {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();       ///< eq. (1)
  Eigen::Vector3d tangent = Eigen::Vector3d::Zero();      ///< eq. (2), not unit (|t| = r)
  Eigen::Vector3d inclination = Eigen::Vector3d::Zero();  ///< eq. (4), unit
  AfpHeadAxes axes;                                       ///< eqs. (7), (11) general form
};
SeedCylinderPose SeedConcaveCylinderPose(double alpha_rad, double seed_beta_rad, double theta_rad);

/// B / C travel the cell allows (limits `kin.afp_axes`: b_min_deg, b_max_deg, c_min_deg,
/// c_max_deg; defaults +-90 / +-180 deg in the limit table, seed 003 section 4). Radians.
struct AfpAxisLimits {
  double b_min_rad = -kPi / 2;
  double b_max_rad = kPi / 2;
  double c_min_rad = -kPi;
  double c_max_rad = kPi;
};
AfpAxisLimits AfpAxisLimitsFrom(const scene::RuleLimits& limits);

struct AfpPlanOptions {
  /// Course = the straight line of the (u, v) domain at this angle to the u axis (on a
  /// cylinder: a helix, 0 = axial, 90 deg = hoop) through the domain centre, clipped to
  /// the domain. nullopt: the course is the given scene path.
  std::optional<double> lay_angle_rad;
  double incline_rad = 0.0;       ///< theta; 0 = normal pressure; > 0 leans forward
  double point_spacing_mm = 5.0;  ///< nominal; points are equally spaced in arc length
};

/// One course point. Part frame, mm; unit vectors.
struct AfpPoint {
  int index = 0;      ///< 0-based
  double s_mm = 0.0;  ///< course length from the start
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();      ///< course direction, _|_ normal
  Eigen::Vector3d inclination = Eigen::Vector3d::UnitZ();  ///< head axis q (to the head)
  double alpha_rad = 0.0;  ///< atan2(n_z, n_y): seed 003's cylinder angle on a cylinder
  AfpHeadAxes axes;
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< z = q, y = course (_|_ q)
  /// Feed of the move that ends here, as a fraction of the head's layup speed (1 as planned;
  /// `plan afp --incline auto` lowers it where a joint would exceed its speed limit).
  double feed_fraction = 1.0;
};

/// An axis over its travel: a finding the cell cannot run.
struct AfpOverTravel {
  std::string code;  ///< "afp-b-over-travel" | "afp-c-over-travel"
  int points = 0;    ///< how many points are outside the travel
  int first_index = 0;
  double worst_rad = 0.0;  ///< the value furthest outside
  double limit_rad = 0.0;  ///< the limit it passes
  std::string message;
};

struct AfpPlan {
  std::string course_name;              ///< the path's name, or "lay<deg>"
  double lay_angle_rad = std::nan("");  ///< NaN when the course is a scene path
  double incline_rad = 0.0;
  /// The course laid: the stretch of the path over which every tow of the head lies on the
  /// surface (process::TowsAt), to 0.01 mm.
  double length_mm = 0.0;
  double trimmed_start_mm = 0.0;  ///< path length left off before the course, where tows hang off
  double trimmed_end_mm = 0.0;    ///< path length left off after it
  std::vector<AfpPoint> points;
  AfpAxisLimits limits;
  double b_min_rad = 0.0, b_max_rad = 0.0, c_min_rad = 0.0, c_max_rad = 0.0;  ///< used
  double c_max_step_rad = 0.0;  ///< largest C change between neighbours (normal-pressure flip)
  std::vector<AfpOverTravel> over_travel;  ///< empty: B and C stay in their travel
};

/// The straight course of `lay_angle_rad` through the centre of `domain`, clipped to it.
std::unique_ptr<geom::Curve2> MakeLayAngleCourse(const geom::Domain2& domain, double lay_angle_rad);

/// Plans one course. `path` is used when options.lay_angle_rad is empty. Diagnostics
/// ("plan-...") for a non-AFP head, a missing path, a degenerate course or frame.
std::optional<AfpPlan> PlanAfpCourse(const scene::Scene& scene, const scene::PathSpec* path,
                                     const AfpPlanOptions& options, DiagnosticSink& sink);

/// The ply number `plan afp` writes its course under: the one after the scene's plies (a ply
/// the scene does not define; afp.coverage judges it by what it lays).
int AfpCoursePly(const scene::Scene& scene);

/// Writes the programme (mm, G90, T<afp> M6, M70 P<AfpCoursePly> and M71 P1, G0 to the start,
/// M62 P0 (every tow of the head), G1 X Y Z A B C V per point, M63 P0, M72; A B C = the
/// dialect's Euler angles of the tool pose, V = course length). F (modal) on the first G1 and
/// wherever a point's feed_fraction changes the feed.
void WriteAfpProgram(const AfpPlan& plan, const scene::Scene& scene,
                     const program::Dialect& dialect, std::ostream& out);

/// Header + one row per point: index, s_mm, alpha_deg, tangent x y z, inclination x y z,
/// B_deg, C_deg. Fixed decimals (6), '\n' line ends.
void WriteAfpCsv(const AfpPlan& plan, std::ostream& out);

}  // namespace stitchsim::planner
