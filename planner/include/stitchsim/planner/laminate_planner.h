#pragma once
// The laminate planner (`stitchsim plan laminate`, docs/afp.md "Laminates"): every ply of a
// scene laminate's stack planned by PlanPly (on the tool surface: a ply's courses do not depend
// on the plies below), the references of same-angle plies shifted sideways to keep the stagger
// rule, and then, in stack order, each ply's poses lifted along the surface normal by the
// thickness the plies below it actually lay (a uv thickness field built from their tows).
// Part frame, mm; pure data like PlyPlan.

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/plan_progress.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

struct LaminatePlanOptions {
  PlyPlanOptions ply;  ///< each ply's options (its `progress` is not called: see `progress`)
  int jobs = 0;        ///< threads planning plies; 0: the hardware's concurrency
  /// The thickness field's cell in (u, v), mm (at most 2 mm: larger is taken as 2).
  double thickness_cell_mm = 2.0;
  /// After each ply planned (plies done, plies in the stack), on the planning thread that
  /// finished it, one call at a time. Null: not called.
  PlanProgress progress;
};

/// The thickness laid on the tool surface, a grid over (u, v) (cell-centred samples, bilinear
/// lookup, zero outside the grid). Built by the laminate planner from the plies' laid tows.
class ThicknessField {
 public:
  /// A field of zeros over `domain` (u, v, mm) with square cells of at most `cell_mm`.
  ThicknessField(const geom::Domain2& domain, double cell_mm);
  /// Adds `thickness_mm` wherever one of `plan`'s tows lays (the uv quads of a laid segment
  /// between consecutive course points' boundary_uv; overlapping tows of the ply count once).
  /// Returns the smallest and largest thickness that was there before, over the cells it
  /// covers ({0, 0} when it covers none).
  std::pair<double, double> AddPly(const PlyPlan& plan, double thickness_mm);
  /// The thickness at `uv` (bilinear between cell centres), mm.
  double At(const Eigen::Vector2d& uv) const;
  double CellMm() const { return cell_; }
  /// The largest thickness of any cell, mm.
  double MaxMm() const;

 private:
  double Sample(long i, long j) const;
  Eigen::Vector2d origin_;  ///< (u, v) of the grid's corner, mm
  double cell_ = 2.0;       ///< mm
  long nu_ = 0, nv_ = 0;    ///< cells along u and v
  std::vector<double> mm_;  ///< thickness per cell, mm; index i + nu * j
};

/// One ply of the laminate as planned, in stack order.
struct LaminatePly {
  std::size_t stack_index = 0;  ///< 0-based position in LaminateSpec::stack
  std::size_t scene_ply = 0;    ///< index into Scene::plies
  /// Same-angle index: how many plies of its angle (mod 180 deg) lie below it in the stack.
  int same_angle_index = 0;
  /// Its reference moved this far to the left of its fibre direction (N x T at the origin's
  /// foot point, tangent plane), mm: (same_angle_index mod (w + 1)) * W / (w + 1).
  double stagger_shift_mm = 0.0;
  double course_width_mm = 0.0;  ///< W: its band's tows x tow width, mm
  double thickness_mm = 0.0;     ///< its own cured thickness (PlySpec), mm
  /// Thickness of the plies below over the cells it lays on (its poses are lifted by it), mm.
  double below_min_mm = 0.0;
  double below_max_mm = 0.0;
  PlyPlan plan;  ///< poses lifted onto the plies below; courses numbered per ply
};

struct LaminatePlan {
  std::string laminate;            ///< LaminateSpec::name
  std::vector<LaminatePly> plies;  ///< stack order, bottom first
  double thickness_cell_mm = 0.0;  ///< the field's cell, mm
  double max_thickness_mm = 0.0;   ///< most laid anywhere (all plies), mm
  // Whole laminate: sums over its plies.
  int courses = 0;
  int tow_segments = 0;
  int events = 0;
  double laid_length_mm = 0.0;
};

/// Stacks `plans` in order as PlanLaminate does: each plan's poses and tow edges lifted along
/// the surface normal by the thickness the plans before it lay (a ThicknessField of
/// `cell_mm`), then its own tows added at `thickness_mm[i]`. Returns per plan the smallest and
/// largest thickness below it; `max_mm` (may be null) gets the stack's largest, `cell` (may
/// be null) the field's cell. For `plan ply` of several plies and for PlanLaminate.
std::vector<std::pair<double, double>> StackPlies(const geom::Surface& surface,
                                                  const std::vector<PlyPlan*>& plans,
                                                  const std::vector<double>& thickness_mm,
                                                  double cell_mm, double* max_mm = nullptr,
                                                  double* cell = nullptr);

/// Plans `laminate` (one of scene.laminates). Diagnostics: PlanPly's for each ply (in stack
/// order), plan-laminate-stagger when a course cannot hold W / (w + 1) >= the stagger offset
/// for plies of an angle stacked more than once. Nullopt when any ply fails.
std::optional<LaminatePlan> PlanLaminate(const scene::Scene& scene,
                                         const scene::LaminateSpec& laminate,
                                         const LaminatePlanOptions& options, DiagnosticSink& sink);

/// The laminate's programme: its plies in stack order (WritePlyProgram), the header naming
/// the laminate (`laminate=NAME`).
void WriteLaminateProgram(const LaminatePlan& plan, const scene::Scene& scene,
                          const program::Dialect& dialect, std::ostream& out);

/// WritePlyTowsCsv of each ply in stack order, each row led by the ply's stack position (from
/// 1): stack,course,tow,segment,... (the edges lifted onto the plies below).
void WriteLaminateTowsCsv(const LaminatePlan& plan, std::ostream& out);

}  // namespace stitchsim::planner
