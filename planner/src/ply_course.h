#pragma once
// Private to the ply planner: one course along a centre curve (poses, tows, cuts and adds),
// and the seam between two neighbouring courses.

#include <optional>

#include "stitchsim/planner/offset_curves.h"
#include "stitchsim/planner/ply_planner.h"

namespace stitchsim::planner {

struct CourseContext {
  const geom::Surface& surface;
  const scene::PlySpec& ply;
  process::TowLayout layout;
  const PlyPlanOptions& options;
};

/// The course along `centre` (a dense curve on the surface), or nullopt when no tow is laid,
/// or when the tows leave the surface between the first add and the last cut (then
/// `*off_surface_s` = the course length there).
std::optional<PlyCourse> PlanCourse(const CourseContext& ctx, const SurfaceCurve& centre,
                                    int offset_index, double* off_surface_s);

/// Gap and overlap between the left edge of `right` and the right edge of `left`.
CourseSeam MeasureSeam(const PlyCourse& right, const PlyCourse& left);

}  // namespace stitchsim::planner
