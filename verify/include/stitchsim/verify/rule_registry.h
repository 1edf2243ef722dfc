#pragma once
// The rule registry: every rule's id, close-up family, when it runs and its factory, declared
// in the rule's own file next to its class (a function returning its RuleEntry) and listed
// once, in report order, in verify/src/rules.cpp. MakeRules and SkippedRules both read it.

#include <memory>
#include <string>
#include <vector>

#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {

namespace detail {
struct RuleMaking;  // what the factories of one MakeRules call share (detail/rule_registry.h)
}  // namespace detail

/// Whether a rule runs in a context, and if not whether the report names it as skipped.
struct RulePresence {
  enum class Kind {
    kRuns,     ///< MakeRules makes it
    kAbsent,   ///< it does not apply (another head, no constraints...): in no list
    kSkipped,  ///< it applies but cannot run: the report's "skipped" list, with `reason`
  };
  Kind kind = Kind::kRuns;
  std::string reason;  ///< kSkipped: why, as the report prints it ("--no-collision")

  static RulePresence Runs() { return {}; }
  static RulePresence Absent() { return {Kind::kAbsent, {}}; }
  static RulePresence Skipped(std::string why) { return {Kind::kSkipped, std::move(why)}; }
  /// kRuns when `applies`, else kAbsent.
  static RulePresence RunsIf(bool applies) { return applies ? Runs() : Absent(); }
};

/// One registered rule.
struct RuleEntry {
  const char* id = "";                            ///< the rule's id, as its summary says
  CloseUpFamily close_up = CloseUpFamily::kNone;  ///< what its close-up snapshot frames
  /// Runs, absent or skipped (with the reason) in a context; a pure function of it.
  RulePresence (*presence)(const RuleContext& ctx) = nullptr;
  /// Makes the rule (called only where presence is kRuns).
  std::unique_ptr<Rule> (*make)(const RuleContext& ctx, detail::RuleMaking& making) = nullptr;
};

/// Every registered rule, in report order (verify/src/rules.cpp).
const std::vector<RuleEntry>& RuleRegistry();

}  // namespace stitchsim::verify
