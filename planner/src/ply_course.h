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
};

/// Where a course's tows leave the surface (process::TowsAt fails).
struct CourseOffSurface {
  bool anywhere = false;   ///< at some sample along the course (it lays nothing there)
  double laying_s = -1.0;  ///< >= 0: the course length where they leave it while it lays
};

/// The course along `centre` (a dense curve on the surface), or nullopt when no tow is laid,
/// or when the tows leave the surface between the first add and the last cut.
std::optional<PlyCourse> PlanCourse(const CourseContext& ctx, const SurfaceCurve& centre,
                                    int offset_index, CourseOffSurface& off_surface);

/// The plan's coverage of `ply` as the afp.coverage rule reads a programme (the band's laid
/// tows painted between consecutive course points; process::MapForPly, MeasurePly).
process::PlyCoveragePct PlanCoverage(const PlyPlan& plan, const geom::Surface& surface,
                                     const scene::PlySpec& ply);

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
