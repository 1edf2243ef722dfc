#pragma once
// What the rule files need to declare their registry entries (stitchsim/verify/rule_registry.h):
// the state the factories of one MakeRules call share, and the common run conditions.

#include <memory>
#include <type_traits>

#include "stitchsim/scene/rule_limits.h"
#include "stitchsim/verify/rule_registry.h"

namespace stitchsim::verify::detail {

class LaidTows;

/// Shared by the factories of one MakeRules call: the afp.* rules' one sampler of what the
/// programme lays (afp_laid.h), made by the first of them.
struct RuleMaking {
  std::shared_ptr<LaidTows> laid;
  /// The sampler, made on first use.
  const std::shared_ptr<LaidTows>& Laid(const RuleContext& ctx);
};

/// The factory of a rule class constructed from the context (or from nothing).
template <typename R>
std::unique_ptr<Rule> Make(const RuleContext& ctx, RuleMaking& /*making*/) {
  if constexpr (std::is_constructible_v<R, const RuleContext&>) {
    return std::make_unique<R>(ctx);
  } else {
    return std::make_unique<R>();
  }
}

/// Runs in every context.
RulePresence RunsAlways(const RuleContext& ctx);
/// Runs with a stitching head, absent with an AFP head.
RulePresence RunsWhenStitching(const RuleContext& ctx);
/// Runs with an AFP head, absent with a stitching head.
RulePresence RunsWhenLaying(const RuleContext& ctx);
/// Runs with an AFP head when `limit` is given (the scene's or the head's); skipped with
/// `missing` as the reason when it is not; absent with a stitching head.
RulePresence RunsWhenLayingWithLimit(const RuleContext& ctx, std::optional<double> limit,
                                     const char* missing);

/// The factory of an afp.* rule constructed from the context and the shared sampler.
template <typename R>
std::unique_ptr<Rule> MakeLaying(const RuleContext& ctx, RuleMaking& making) {
  return std::make_unique<R>(ctx, making.Laid(ctx));
}

}  // namespace stitchsim::verify::detail
