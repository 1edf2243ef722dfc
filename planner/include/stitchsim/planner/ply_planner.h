#pragma once
// The fibre-placement ply planner (`stitchsim plan ply`, docs/afp.md "Plies, courses and
// tows"): fills a scene ply with courses of the head's tows. The reference course is the
// ply's fibre axis projected onto the surface, the geodesic from its origin, or the streamline
// of its design direction field (scene::ReferencePath); every other course is an offset of its
// neighbour by the course width (planner/offset_curves.h). Along each course the tows are
// placed by process::TowsAt (the one tow model the afp.* rules share) and cut and restarted
// at the ply boundary under the ply's coverage policy, at positions found by bisection. Part
// frame, mm; pure data like RasterPlan.

#include <Eigen/Geometry>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/offset_curves.h"
#include "stitchsim/planner/plan_progress.h"
#include "stitchsim/process/afp_tows.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

struct PlyPlanOptions {
  double point_spacing_mm = 5.0;  ///< longest step between centre points
  double chord_tol_mm = 0.05;     ///< fibre axis projection (ProjectFiberAxis)
  double event_tol_mm = 1e-3;     ///< cut / add positions found to this along the course
  double merge_tol_mm = 0.01;     ///< events this close share one programme point
  double max_substep_mm = 0.0;    ///< tow walks (process::TowsAt; 0: its default)
  int max_courses = 2000;         ///< a ply needing more is an error
  /// After each course: band offset plies (courses laid so far, 0: the count is found as they
  /// go), laminate family plies (course lines done, course lines). Null: not called.
  PlanProgress progress;
};

/// One point of a course: the tool pose (z = surface normal towards the head, y = the course
/// direction, x = y cross z) and the boundaries of the ply's band of tows there
/// (process::TowsAt with the plan's band).
struct PlyPoint {
  double s_mm = 0.0;  ///< along the course's centre curve from the curve's start, mm
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  /// band.count + 1 boundaries, left to right: boundary j is the left edge of head tow
  /// band.first + j.
  std::vector<Eigen::Vector3d> boundary;
  std::vector<Eigen::Vector2d> boundary_uv;  ///< the same in (u, v)
  std::vector<Eigen::Vector3d> across;       ///< unit tangents there, left to right (TowCross)
  bool event = false;                        ///< inserted at a cut / add position
};

/// A tow's material along a course: [start, end] in course length.
struct TowSegment {
  double start_mm = 0.0;
  double end_mm = 0.0;
};

/// What the planner did to the tow pieces and restarts the head cannot lay (docs/afp.md,
/// "Short pieces and restarts"): under coverage >= 0.5 short pieces are extended past the ply
/// boundary and close restarts bridged; below it short pieces are dropped and restarts moved.
struct TowPieceFixes {
  int pieces_dropped = 0;    ///< pieces shorter than the minimum left bare
  int pieces_extended = 0;   ///< pieces lengthened to the minimum past the ply boundary
  int restarts_bridged = 0;  ///< cuts and restarts closer than the minimum, laid through
  int restarts_moved = 0;    ///< restarts moved on to the minimum distance from the cut
  TowPieceFixes& operator+=(const TowPieceFixes& o) {
    pieces_dropped += o.pieces_dropped;
    pieces_extended += o.pieces_extended;
    restarts_bridged += o.restarts_bridged;
    restarts_moved += o.restarts_moved;
    return *this;
  }
};

struct PlyTow {
  int tow = 1;                   ///< as the head numbers it (1 leftmost), in the band
  std::vector<TowSegment> laid;  ///< in order along the course
  /// Smallest steering radius of its centre line where laid (process/afp_steering.h: the
  /// definition afp.steering_radius applies to the programme); infinity: straight or too short.
  double min_radius_mm = INFINITY;
  /// Its shortest laid piece: the centre line's chords between the course points, mm
  /// (infinity: nothing laid).
  double shortest_piece_mm = INFINITY;
};

struct PlyCourse {
  int number = 1;                ///< 1-based, right to left across the ply
  int offset_index = 0;          ///< 0 = the reference course; > 0 to its left (N x T)
  std::vector<PlyPoint> points;  ///< centre points from the first add to the last cut
  std::vector<PlyTow> tows;      ///< every tow of the band (some may lay nothing)
  TowPieceFixes fixes;           ///< short pieces and close restarts this course mended
  double Start() const { return points.empty() ? 0.0 : points.front().s_mm; }
  double End() const { return points.empty() ? 0.0 : points.back().s_mm; }
};

/// Between courses `left` and `right` (numbers; left = right + 1): the largest gap and the
/// largest overlap between their facing edges, measured across the course inside the ply.
struct CourseSeam {
  int right = 1;
  int left = 2;
  double max_gap_mm = 0.0;
  double max_overlap_mm = 0.0;
};

struct PlyFinding {
  std::string code;  ///< "ply-steering-radius", "ply-coverage"
  std::string message;
};

struct PlyPlan {
  std::string ply_name;
  int ply_index = 1;  ///< 1-based position in the scene's plies (M70 P)
  double angle_rad = 0.0;
  double coverage = 0.5;
  process::TowLayout layout;  ///< the head's tows
  /// The head's tows the ply lays (process::PlyTowBand of the ply's `tows:`); the course
  /// curves are the tool point's paths, the band's centre BandCentreOffset to their side.
  process::TowBand band;
  std::vector<PlyCourse> courses;  ///< only courses that lay material, numbered 1..N
  std::vector<CourseSeam> seams;
  int tow_segments = 0;  ///< laid segments over all courses and tows
  int events = 0;        ///< tow adds + cuts
  double min_radius_mm = INFINITY;
  double max_gap_mm = 0.0;
  double max_overlap_mm = 0.0;
  double laid_length_mm = 0.0;  ///< sum of the courses' lay-up lengths
  /// The head's limits the tows were planned to (mm; 0: none given): afp.min_tow_length's
  /// (the scene limit, else the head's cut_to_roller_mm) and afp.restart_distance's (the
  /// scene limit, else the head's min_restart_mm).
  double min_tow_length_mm = 0.0;
  double min_restart_mm = 0.0;
  TowPieceFixes fixes;  ///< over all courses
  /// Shortest tow piece laid: its centre line along the surface through the course points,
  /// mm (infinity: none laid). Measured on the final tows.
  double shortest_piece_mm = INFINITY;
  /// The plan's own afp.coverage figures: percent of the ply's area beyond the band of one tow
  /// width along its boundary left bare, covered twice, and laid outside the ply.
  double bare_pct = 0.0;
  double doubled_pct = 0.0;
  double laid_outside_pct = 0.0;
  std::vector<PlyFinding> findings;  ///< empty: the cell can lay it as planned
};

/// The design fibre direction of `ply` in the tangent plane with unit normal `normal` (part
/// frame): the ply's reference direction projected onto that plane along its `projection`,
/// turned by `angle_rad` about the normal; unit. nullopt where it does not project (the
/// projection lies in the tangent plane, or the direction runs along the projection).
std::optional<Eigen::Vector3d> DesignFiberDirection(const scene::PlySpec& ply, double angle_rad,
                                                    const Eigen::Vector3d& normal);

/// The `constant_angle` reference course of `ply` at `angle_rad` (scene::ReferencePath): the
/// streamline of DesignFiberDirection through the foot point of the ply origin, integrated
/// both ways by RK4 in (u, v) in arc-length steps of `step_mm` (mm) until it leaves `region`
/// ((u, v), mm) or the surface's domain; points ordered along the direction at the origin,
/// each with the field as its tangent. Not ok (with a message) if the direction does not
/// project at the origin or the streamline has fewer than 2 points in `region`.
ReferenceCurve ConstantAngleReference(const geom::Surface& surface, const scene::PlySpec& ply,
                                      double angle_rad, const geom::Domain2& region,
                                      double step_mm);

/// Plans `ply` (one of scene.plies). Diagnostics ("plan-...") for a non-AFP head, a fibre
/// axis that does not reach the ply, a rule not implemented, too many courses, and courses the
/// ply needs whose tows would leave the surface (plan-ply-off-surface: part of a course, or
/// whole courses when the plan without them leaves more of the ply bare than afp.coverage
/// allows). A plan that fails afp.coverage for any other reason carries a "ply-coverage"
/// finding: PlanPly never returns a plan without findings that its own coverage rule fails.
/// Tow pieces shorter than the minimum tow length and restarts closer than the minimum
/// restart distance are mended per the ply's coverage (TowPieceFixes) before the coverage is
/// measured, and each course has points at +-cut_add_zone_mm around its cuts and adds (the
/// head's slow zones, which WritePlyProgram writes at their feed).
std::optional<PlyPlan> PlanPly(const scene::Scene& scene, const scene::PlySpec& ply,
                               const PlyPlanOptions& options, DiagnosticSink& sink);

/// Writes the programme (docs/program-format.md, "Fibre placement"): header, mm, the AFP head,
/// M70 for the ply, per course M71, approach along the normal, M21, G1 lay-up with M62/M63 at
/// their positions, M63 P0, M20, retract, M72; M30.
void WritePlyProgram(const PlyPlan& plan, const scene::Scene& scene,
                     const program::Dialect& dialect, std::ostream& out);
/// Several plies in one programme, laid in the order given: one M70 each (its position in
/// the scene's `plies:`), courses numbered per ply; the header names them (`plies=a,b`) and,
/// when `laminate` is not empty, the scene laminate they are (`laminate=NAME`).
void WritePlyProgram(std::span<const PlyPlan* const> plans, const scene::Scene& scene,
                     const program::Dialect& dialect, std::ostream& out,
                     const std::string& laminate = {});

/// Per course, tow and laid segment, one row per course point inside the segment:
/// course,tow,segment,s_start_mm,s_end_mm,s_mm,left_x,left_y,left_z,right_x,right_y,right_z.
void WritePlyTowsCsv(const PlyPlan& plan, std::ostream& out);

/// Safe height of the approach and retract above the surface along its normal, mm.
inline constexpr double kPlyApproachHeightMm = 100.0;

}  // namespace stitchsim::planner
