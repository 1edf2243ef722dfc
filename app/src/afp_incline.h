#pragma once
// `plan afp --incline auto`: the judge of the planner's inclination search
// (planner/afp_incline.h): a candidate programme is executed and verified with every rule,
// the collision rules on, as `stitchsim verify` judges it.

#include "cli_common.h"
#include "stitchsim/planner/afp_incline.h"
#include "stitchsim/sim/collision.h"

namespace stitchsim::app {

/// A judge that runs a programme on `ls`'s cell with `world` (both must outlive it) and
/// verifies it with every rule.
planner::InclineJudge VerifyJudge(const LoadedScene& ls, sim::CollisionWorld& world);

}  // namespace stitchsim::app
