#pragma once
// `plan afp --incline auto` (docs/afp.md): the inclination search. Candidate leans are tried
// in order; each candidate's whole programme is judged by a caller's judge (the CLI executes
// and verifies it with every rule; the planner links neither simulator nor verifier), the
// feed lowered on the moves where only the joint speed fails, and the first candidate that
// passes wins.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

struct InclineSearchOptions {
  double max_deg = 30.0;  ///< largest lean tried, degrees
  double step_deg = 1.0;  ///< lean step, degrees
  /// Where only the joint speed fails, a move's feed is scaled so that its worst joint runs
  /// at this fraction of the rule's limit; then the programme is judged again.
  double feed_target_fraction = 0.95;
  int max_feed_rounds = 6;  ///< judgements per candidate spent lowering feeds
};

/// A judge's verdict on one candidate programme.
struct InclineVerdict {
  std::string error;  ///< the programme could not be judged (it did not run): stops the search
  bool pass = false;  ///< no error anywhere
  /// When !pass: the first failure, "<rule> at line N: <message>" (and how many more errors).
  std::string first_failure;
  /// Every error comes from the joint-speed rule (feeds may be lowered).
  bool only_joint_speed_fails = false;
  std::string joint_speed_rule;  ///< that rule's id, for messages
  /// Programme line -> its worst joint speed in % of the joint's maximum, for every line the
  /// joint-speed rule reports as an error.
  std::map<int, double> joint_speed_pct;
  double joint_speed_limit_pct = 100.0;  ///< the joint-speed rule's error limit, %
};

/// Judges a whole programme (text in the default dialect).
using InclineJudge = std::function<InclineVerdict(const std::string& programme_text)>;

/// One candidate inclination and its verdict.
struct InclineCandidate {
  double incline_rad = 0.0;
  bool pass = false;                   ///< the programme verifies with no error
  int slowed_moves = 0;                ///< moves whose feed was lowered
  double slowest_feed_fraction = 1.0;  ///< the lowest feed written, of the layup speed
  std::string failure;  ///< why not: "<rule> at line N: <message>" ("" when it passes)
};

struct InclineSearchResult {
  std::optional<AfpPlan> plan;               ///< the first candidate that passes
  std::vector<InclineCandidate> candidates;  ///< in the order tried
  std::string error;  ///< a candidate could not be planned or judged (input problem)
};

/// The leans tried, in order: 0, +step, -step, +2 step, -2 step, ... up to max_deg (the
/// smallest lean either way first; forward before back at equal size). Radians.
std::vector<double> InclineCandidates(const InclineSearchOptions& search);

/// Plans the course at each candidate lean, has `judge` judge its whole programme and returns
/// the first that passes, lowering the feed on the moves where the joint speed is the only
/// failure. `on_candidate`, if set, is called as each verdict is reached. Planner diagnostics
/// go to `sink`.
InclineSearchResult SearchAfpIncline(
    const scene::Scene& scene, const scene::PathSpec* path, AfpPlanOptions options,
    const InclineSearchOptions& search, const InclineJudge& judge, DiagnosticSink& sink,
    const std::function<void(const InclineCandidate&)>& on_candidate = {});

}  // namespace stitchsim::planner
