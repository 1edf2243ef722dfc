#pragma once
// `plan afp --incline auto`: the inclination search (docs/afp.md). The planner does not link
// the simulator, so the search lives here: each candidate's whole programme is executed and
// verified with every rule, the collision rules on, as `stitchsim verify` judges it.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/sim/collision.h"

namespace stitchsim::app {

struct InclineSearchOptions {
  double max_deg = 30.0;  ///< largest lean tried, degrees
  double step_deg = 1.0;  ///< lean step, degrees
  /// Where only kin.joint_speed fails, a move's feed is scaled so that its worst joint runs
  /// at this fraction of the rule's limit; then the programme is judged again.
  double feed_target_fraction = 0.95;
  int max_feed_rounds = 6;  ///< judgements per candidate spent lowering feeds
};

/// One candidate inclination and its verdict.
struct InclineCandidate {
  double incline_rad = 0.0;
  bool pass = false;                   ///< the programme verifies with no error
  int slowed_moves = 0;                ///< moves whose feed was lowered
  double slowest_feed_fraction = 1.0;  ///< the lowest feed written, of the layup speed
  std::string failure;  ///< why not: "<rule> at line N: <message>" ("" when it passes)
};

struct InclineSearchResult {
  std::optional<planner::AfpPlan> plan;      ///< the first candidate that passes
  std::vector<InclineCandidate> candidates;  ///< in the order tried
  std::string error;  ///< a candidate could not be planned or judged (input problem)
};

/// The leans tried, in order: 0, +step, -step, +2 step, -2 step, ... up to max_deg (the
/// smallest lean either way first; forward before back at equal size). Radians.
std::vector<double> InclineCandidates(const InclineSearchOptions& search);

/// Plans the course at each candidate lean, judges its whole programme with every rule
/// (`world` is the scene's collision world) and returns the first that passes, lowering the
/// feed on the moves where kin.joint_speed is the only rule that fails. `on_candidate` is
/// called as each verdict is reached. Planner diagnostics go to `sink`.
InclineSearchResult SearchAfpIncline(
    const LoadedScene& ls, sim::CollisionWorld& world, const scene::PathSpec* path,
    planner::AfpPlanOptions options, const InclineSearchOptions& search, DiagnosticSink& sink,
    const std::function<void(const InclineCandidate&)>& on_candidate);

}  // namespace stitchsim::app
