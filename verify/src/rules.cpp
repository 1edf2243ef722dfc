// The rule registry: one line per rule, in report order. Each rule's file declares its entry
// next to its class (`RuleEntry <Name>Entry()`: id, close-up family, when it runs, factory;
// stitchsim/verify/rule_registry.h); MakeRules and SkippedRules read the list.
#include "afp_laid.h"
#include "detail/rule_registry.h"

// X(entry function): the registry, in report order.
#define STITCHSIM_RULE_REGISTRY(X) \
  X(RotationInPreformRuleEntry)    \
  X(SideForceRuleEntry)            \
  X(WalkRuleEntry)                 \
  X(StitchLengthRuleEntry)         \
  X(StitchWidthRuleEntry)          \
  X(StandoffRuleEntry)             \
  X(NormalityRuleEntry)            \
  X(AfpSteeringRuleEntry)          \
  X(AfpGapRuleEntry)               \
  X(AfpOverlapRuleEntry)           \
  X(AfpCompactionRuleEntry)        \
  X(AfpCoverageRuleEntry)          \
  X(AfpMinTowLengthRuleEntry)      \
  X(AfpRestartDistanceRuleEntry)   \
  X(AfpFiberAngleRuleEntry)        \
  X(AfpStaggerRuleEntry)           \
  X(ReachRuleEntry)                \
  X(JointLimitRuleEntry)           \
  X(SingularityRuleEntry)          \
  X(ConfigFlipRuleEntry)           \
  X(JointSpeedRuleEntry)           \
  X(AccelerationRuleEntry)         \
  X(TorqueRuleEntry)               \
  X(PayloadRuleEntry)              \
  X(TrackingRuleEntry)             \
  X(SyncRuleEntry)                 \
  X(EmptyProgramRuleEntry)         \
  X(StitchCountRuleEntry)          \
  X(LineSamplingRuleEntry)         \
  X(CollisionHeadMoldRuleEntry)    \
  X(CollisionRobotCellRuleEntry)   \
  X(CollisionClearanceRuleEntry)   \
  X(ConstraintCrossingRuleEntry)

namespace stitchsim::verify {

#define STITCHSIM_DECLARE_RULE_ENTRY(entry) RuleEntry entry();
STITCHSIM_RULE_REGISTRY(STITCHSIM_DECLARE_RULE_ENTRY)
#undef STITCHSIM_DECLARE_RULE_ENTRY

const std::vector<RuleEntry>& RuleRegistry() {
#define STITCHSIM_LIST_RULE_ENTRY(entry) entry(),
  static const std::vector<RuleEntry> registry = {
      STITCHSIM_RULE_REGISTRY(STITCHSIM_LIST_RULE_ENTRY)};
#undef STITCHSIM_LIST_RULE_ENTRY
  return registry;
}

const char* CloseUpFamilyName(CloseUpFamily family) {
  switch (family) {
    case CloseUpFamily::kNone:
      return "";
    case CloseUpFamily::kCollision:
      return "collision";
    case CloseUpFamily::kNeedle:
      return "needle";
    case CloseUpFamily::kStitch:
      return "stitch";
    case CloseUpFamily::kKinematics:
      return "kinematics";
    case CloseUpFamily::kConstraint:
      return "constraint";
    case CloseUpFamily::kAfp:
      return "afp";
  }
  return "";
}

namespace detail {

const std::shared_ptr<LaidTows>& RuleMaking::Laid(const RuleContext& ctx) {
  if (!laid) laid = MakeLaidTows(ctx);
  return laid;
}

RulePresence RunsAlways(const RuleContext& /*ctx*/) { return RulePresence::Runs(); }
RulePresence RunsWhenStitching(const RuleContext& ctx) {
  return RulePresence::RunsIf(ctx.scene->head.IsStitching());
}
RulePresence RunsWhenLaying(const RuleContext& ctx) {
  return RulePresence::RunsIf(!ctx.scene->head.IsStitching());
}

RulePresence RunsWhenLayingWithLimit(const RuleContext& ctx, std::optional<double> limit,
                                     const char* missing) {
  if (ctx.scene->head.IsStitching()) return RulePresence::Absent();
  if (!limit) return RulePresence::Skipped(missing);
  return RulePresence::Runs();
}

}  // namespace detail

std::vector<std::unique_ptr<Rule>> MakeRules(const RuleContext& ctx) {
  detail::RuleMaking making;
  return MakeRules(ctx, making);
}

std::vector<std::unique_ptr<Rule>> MakeRules(const RuleContext& ctx, detail::RuleMaking& making) {
  std::vector<std::unique_ptr<Rule>> rules;
  for (const RuleEntry& entry : RuleRegistry()) {
    if (entry.presence(ctx).kind != RulePresence::Kind::kRuns) continue;
    rules.push_back(entry.make(ctx, making));
    rules.back()->close_up_ = entry.close_up;
  }
  return rules;
}

std::vector<SkippedRule> SkippedRules(const RuleContext& ctx) {
  std::vector<SkippedRule> skipped;
  for (const RuleEntry& entry : RuleRegistry()) {
    RulePresence presence = entry.presence(ctx);
    if (presence.kind == RulePresence::Kind::kSkipped) {
      skipped.push_back({entry.id, std::move(presence.reason)});
    }
  }
  return skipped;
}

}  // namespace stitchsim::verify
