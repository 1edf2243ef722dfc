#pragma once
// `plan afp --incline auto`: the judge of the planner's inclination search
// (planner/afp_incline.h) built from the scene's cell: a candidate programme is executed and
// verified with every rule, the collision rules on, as `stitchsim verify` judges it; and the
// search itself with its collision world.

#include <functional>
#include <optional>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/afp_incline.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/status.h"
#include "stitchsim/sim/collision.h"

namespace stitchsim::run {

/// A judge that runs a programme text on `loaded`'s cell with `world` (both not owned; they
/// must outlive it) and verifies it with every rule.
planner::InclineJudge VerifyJudge(const LoadedScene& loaded, sim::CollisionWorld& world);

/// The search's outcome with the scene it planned on (the programme is written against it).
struct AutoInclineRun {
  RunStatus status = RunStatus::kBadInput;  ///< kOk when searched (a plan or none passed)
  std::optional<LoadedScene> loaded;        ///< owned; the scene and robot searched on
  planner::InclineSearchResult search;      ///< candidates in the order tried; the plan
};

/// Loads the scene and its collision world and searches the lean of the course named
/// `path_name` (nullopt: by options.lay_angle_rad) from 0 out to the search's limit.
/// `on_candidate` (may be null) sees each verdict as it is reached. Problems into `sink`
/// (plan-incline-check when a candidate could not be planned or judged).
AutoInclineRun PlanAfpAutoIncline(
    const std::string& scene_file, const scene::LoadOptions& load,
    const std::optional<std::string>& path_name, const planner::AfpPlanOptions& options,
    const planner::InclineSearchOptions& search,
    const std::function<void(const planner::InclineCandidate&)>& on_candidate,
    DiagnosticSink& sink);

/// "<rule> on <n>, ..." over the first failing rule of each candidate, rules in name order
/// (why no lean passed).
std::string FailuresByRule(const std::vector<planner::InclineCandidate>& candidates);

}  // namespace stitchsim::run
