#pragma once
// Private to the ply planner: one course along a centre curve (poses, tows, cuts and adds),
// and the seam between two neighbouring courses.

#include <functional>
#include <optional>
#include <vector>

#include "stitchsim/common/units.h"
#include "stitchsim/planner/offset_curves.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/process/afp_coverage.h"

namespace stitchsim::planner {

struct CourseContext {
  const geom::Surface& surface;
  const scene::PlySpec& ply;
  process::TowLayout layout;  ///< the head's tows
  process::TowBand band;      ///< the head's tows this ply lays
  const PlyPlanOptions& options;
  double min_piece_mm = 0.0;    ///< shortest tow piece the head lays (0: any)
  double min_restart_mm = 0.0;  ///< shortest cut-to-restart distance (0: any)
  double slow_zone_mm = 0.0;    ///< points this far either side of each cut and add (0: none)
};

/// Where a course's tows leave the surface (process::TowsAt fails).
struct CourseOffSurface {
  bool anywhere = false;   ///< at some sample along the course (it lays nothing there)
  double laying_s = -1.0;  ///< >= 0: the course length where they leave it while it lays
};

/// The course along `centre` (a dense curve on the surface), or nullopt when no tow is laid,
/// or when the tows leave the surface between the first add and the last cut. Its tow pieces
/// are mended to the context's limits (MendTowPieces); a piece that needs to run past the
/// curve's ends gets a course planned on the curve extended along its end geodesics.
std::optional<PlyCourse> PlanCourse(const CourseContext& ctx, const SurfaceCurve& centre,
                                    int offset_index, CourseOffSurface& off_surface);

/// The plan's coverage of `ply` as the afp.coverage rule reads a programme (the band's laid
/// tows painted between consecutive course points; process::MapForPly, MeasurePly).
process::PlyCoveragePct PlanCoverage(const PlyPlan& plan, const geom::Surface& surface,
                                     const scene::PlySpec& ply);

/// A tow's centre line along one course: what the tow piece rules measure (afp.min_tow_length,
/// afp.restart_distance: chords of the tow centre on the surface at most half a tow apart).
class TowRuler {
 public:
  virtual ~TowRuler() = default;
  /// Tow `tow`'s (1-based in the band) centre on the surface at course length s (in
  /// [0, End()]), part mm; nullopt where the tows leave the surface.
  virtual std::optional<Eigen::Vector3d> Centre(int tow, double s) const = 0;
  /// The course's centre curve runs over [0, End()], mm.
  virtual double End() const = 0;
  /// Longest step along the course between two centre points measured, mm.
  virtual double Step() const = 0;
};

/// Length of tow `tow`'s centre line from course length s0 to s1 (s0 <= s1), mm; nullopt
/// where the tows leave the surface.
std::optional<double> TowLength(const TowRuler& ruler, int tow, double s0, double s1);

/// Where a walk along a tow's centre line got to.
struct TowReach {
  bool ok = false;  ///< reached: `s` is where
  double s = 0.0;   ///< course length, mm
  /// Not reached: what was left when the course's curve ended, mm (0: the tows left the
  /// surface).
  double short_mm = 0.0;
};

/// The course length at which tow `tow`'s centre line, walked from `from` in direction `dir`
/// (+1 / -1 along the course), has length `length`.
TowReach WalkTow(const TowRuler& ruler, int tow, double from, int dir, double length);

/// Mends tow `tow`'s laid segments (in order, disjoint) to the context's limits per the ply's
/// coverage (TowPieceFixes); counts into `fixes`. A piece that would run past an end of the
/// course's curve raises `need_mm` to what it lacks there when `curve_can_grow` (the caller
/// plans the course again on a longer curve), else it is mended with what the curve has.
void MendTowPieces(const CourseContext& ctx, const TowRuler& ruler, int tow,
                   std::vector<TowSegment>& segments, bool curve_can_grow, TowPieceFixes& fixes,
                   double& need_mm);

/// Under a coverage of 0.5 or more: the ends MendTowPieces moved past the boundary (those not
/// in `boundary_ends`, sorted) lying within a tow width of one another along the course move to
/// the outermost of them (adds to the first, cuts to the last) where the tow's restart distance
/// allows: tows extended side by side start and stop together, not in steps of hundredths of a
/// mm (a line laying part of the band there reads as a gap beside the next course's extended
/// tows).
void AlignExtendedEnds(const CourseContext& ctx, const TowRuler& ruler,
                       const std::vector<double>& boundary_ends,
                       std::vector<std::vector<TowSegment>>& laid);

/// `c` continued at both ends along the surface geodesic of its end direction by `length`, in
/// steps of at most `step` (fewer where the surface's domain ends).
SurfaceCurve Extended(const geom::Surface& surface, const SurfaceCurve& c, double length,
                      double step);

/// `c` run backwards (points reversed, tangents negated).
SurfaceCurve Reversed(SurfaceCurve c);

/// Gap and overlap between the left edge of `right` and the right edge of `left`, along the
/// surface.
CourseSeam MeasureSeam(const geom::Surface& surface, const PlyCourse& right, const PlyCourse& left);

/// What a laminate family ply is built from.
struct LaminateInputs {
  const geom::Surface& surface;
  const SurfaceCurve& reference;  ///< the 0 deg reference course
  double angle_rad = 0.0;         ///< the ply angle (not a multiple of pi)
  double course_width_mm = 1.0;
  /// One offset of a curve by a tow width to `side` (> 0: N x T), trimmed to the ply; nullopt
  /// when the ply is behind or the surface ends.
  std::function<std::optional<SurfaceCurve>(const SurfaceCurve&, int side)> offset;
};

/// The course centre lines of a laminate family ply: laminate family curves at the ply angle
/// across the reference's offset curves, a course width apart across the fibres.
std::vector<SurfaceCurve> LaminateCourseLines(const LaminateInputs& in);

}  // namespace stitchsim::planner
