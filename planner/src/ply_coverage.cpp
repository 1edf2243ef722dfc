// The ply planner's check of its own plan against afp.coverage (docs/afp.md, "Coverage"): a
// plan leaving more of the ply bare (or doubled) than the rule allows never goes out as a
// clean plan.

#include "ply_course.h"
#include "stitchsim/process/afp_coverage.h"

namespace stitchsim::planner {

process::PlyCoveragePct PlanCoverage(const PlyPlan& plan, const geom::Surface& surface,
                                     const scene::PlySpec& ply) {
  if (ply.boundary_uv.size() < 3) return {};
  const auto map = process::MapForPly(surface, ply.boundary_uv, plan.layout);
  for (const PlyCourse& c : plan.courses) {
    for (const PlyTow& t : c.tows) {
      const auto i = static_cast<std::size_t>(t.tow - plan.band.first + 1);
      for (std::size_t j = 1; j < c.points.size(); ++j) {
        const PlyPoint &a = c.points[j - 1], &b = c.points[j];
        bool laid = false;
        for (const TowSegment& g : t.laid)
          laid = laid || (g.start_mm <= a.s_mm && b.s_mm <= g.end_mm);
        if (!laid) continue;
        map->PaintQuad(
            {a.boundary_uv[i - 1], a.boundary_uv[i], b.boundary_uv[i], b.boundary_uv[i - 1]},
            c.number);
      }
    }
    map->EndCourse();
  }
  return process::CoveragePercent(process::MeasurePly(*map, ply.boundary_uv, plan.layout.width_mm));
}

}  // namespace stitchsim::planner
