#pragma once
// Per rule family, what a close-up shows (docs/report-format.md, "Snapshots"): collisions
// framed on the two bodies in contact, needle and stitch rules on the needles with the preform
// as a section, kinematic rules on the whole arm with the offending joint's link, constraint
// crossings from above, AFP rules on the roller.

#include <mujoco/mujoco.h>

#include <optional>
#include <string>

#include "cli_common.h"
#include "snapshot_shot.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/rule.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::app {

/// What the planners read besides the rule.
struct SnapshotContext {
  const LoadedScene* ls = nullptr;
  const process::ProcessModel* process = nullptr;  ///< the needles (stitching heads)
  const trace::CellDescription* cell = nullptr;    ///< collision body names
  mjModel* model = nullptr;                        ///< the scene's MuJoCo model
  mjData* data = nullptr;                          ///< posed by PlanCloseUp at the picture's joints
  const std::vector<verify::StitchMark>* stitches = nullptr;  ///< every stitch, by verdict
};

/// The family a rule's close-up belongs to: "collision", "needle", "stitch", "kinematics",
/// "constraint", "afp", "" (no close-up: program.*, afp.coverage, afp.gaps).
std::string SnapshotFamily(const std::string& rule_id);

/// The finding a rule's close-up is about: the error at the worst sample's line, else the
/// first error, else the first finding; null when the rule kept none.
const verify::Finding* FocusFinding(const verify::Rule& rule);

/// The close-up of `rule` (which has errors), the model posed in ctx.data; nullopt for a rule
/// without a close-up (SnapshotFamily empty, or nothing to place it: no worst sample). False
/// with `error` set when the model cannot be posed.
bool PlanCloseUp(const SnapshotContext& ctx, const verify::Rule& rule,
                 std::optional<CloseUpPlan>& plan, std::string& error);

// The family planners of snapshot_arm.cpp; each fills `plan` for the model posed at the
// picture's joints, false when it finds nothing to frame.

/// kin.* and dyn.*: the whole arm, the offending joint's link highlighted, its axis drawn.
bool PlanKinematics(const SnapshotContext& ctx, const verify::Rule& rule,
                    const trace::TraceSample& s, CloseUpPlan& plan);
/// constraint.*: from above the stitch, the constraint highlighted, the crossings marked
/// (`s` may be null: a line crossing has no sample).
bool PlanConstraint(const SnapshotContext& ctx, const verify::Rule& rule,
                    const trace::TraceSample* s, CloseUpPlan& plan);
/// afp.* and any other rule: the head at the sample, the roller or the tool point in view.
bool PlanHead(const SnapshotContext& ctx, const trace::TraceSample& s, CloseUpPlan& plan);

}  // namespace stitchsim::app
