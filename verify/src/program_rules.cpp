// Programme bookkeeping (program.*): U and V against the tool travel, and the programme as a
// whole (it stitches; it makes the stitches it declares).
#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "detail/rule_registry.h"
#include "detail/text_format.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

using scene::LimitKey;

using detail::Fmt;

class SyncRule final : public Rule {
 public:
  explicit SyncRule(const RuleContext& ctx)
      : Rule("program.sync",
             "U (drive) and V (path length) consistent with each other and with the tool travel; "
             "inside a seam (stitching on, head down) every move of the tool point is stitched",
             "mm") {
    summary_.error_limit = ctx.scene->limits.Value(LimitKey::kSyncErrorMm);
    // A chord is shorter than its arc: V may exceed the straight travel by this fraction.
    sag_fraction_ = ctx.scene->limits.Value(LimitKey::kSyncChordAllowancePct) / 100.0;
  }
  // Each line's value is its largest inconsistency of the checks that apply to it, in mm:
  // V going back; |dU - dV| where U advances (AFP has no U); V against the tool travel where
  // V or U advances or the line moves inside a seam (beyond the chord allowance).
  void OnLine(const trace::LineRecord& l) override {
    Counted();
    const double tol = *summary_.error_limit;
    const double du = l.drive_to_mm - l.drive_from_mm;
    const double dv = l.path_to_mm - l.path_from_mm;
    const double travel = (l.to.translation() - l.from.translation()).norm();
    const bool in_seam = l.stitching && !l.head_retracted;
    std::optional<std::pair<double, std::string>> worst;  // value, subject
    std::string message;
    auto consider = [&](double value, const char* subject, const std::string& msg) {
      if (!worst || value > worst->first) {
        worst = {value, subject};
        message = msg;
      }
    };
    consider(std::max(0.0, -dv), "V", Fmt("the path length V goes back by %.4g mm", -dv));
    if (du > tol) {
      consider(std::abs(du - dv), "U-V",
               Fmt("the drive advances %.4g mm but the path length %.4g mm", du, dv));
    }
    if (dv > tol || du > tol || in_seam) {
      const double value = std::max({0.0, travel - dv, dv - travel - sag_fraction_ * dv});
      std::string msg =
          Fmt("the path length advances %.4g mm but the tool point travels %.4g mm", dv, travel);
      if (in_seam && dv <= tol && du <= tol) {
        msg += " with stitching on and the head down (a move inside a seam lengthens the stitch)";
      }
      consider(value, "V-travel", msg);
    }
    Observe(worst->first, l.source_line, 0, nullptr);
    if (worst->first > tol) {
      const Eigen::Vector3d end = l.to.translation();  // where the line ends
      Record(FindingSeverity::kError, worst->first, tol, l.source_line, 0, worst->second, message,
             nullptr, &end);
    }
  }

 private:
  double sag_fraction_ = 0.02;
};

class EmptyProgramRule final : public Rule {
 public:
  EmptyProgramRule() : Rule("program.empty", "a programme that makes no stitch never passes", "") {}
  void OnSample(const trace::TraceSample& s) override {
    if (s.event == trace::SampleEvent::kNeedleEntry) ++stitches_;
  }
  void Finish(const RuleContext&) override {
    Counted();
    if (stitches_ == 0) {
      Record(FindingSeverity::kError, 0.0, 1.0, 0, 0, "programme",
             "the programme makes no stitch (no line advances the drive axis U through a "
             "needle cycle)",
             nullptr);
    }
  }

 protected:
  void AbsorbExtra(const Rule& later) override {
    stitches_ += dynamic_cast<const EmptyProgramRule&>(later).stitches_;
  }
  void ResetExtra() override { stitches_ = 0; }
  void SaveExtra(nlohmann::json& extra) const override { extra["stitches"] = stitches_; }
  bool LoadExtra(const nlohmann::json& extra) override {
    stitches_ = extra.at("stitches").get<long>();
    return true;
  }

 private:
  long stitches_ = 0;  ///< accumulator: needle entries
};

// A programme that declares how many stitches it makes must make exactly that many: a
// programme cut short (or edited) still parses, and every stitch it does make may pass.
class StitchCountRule final : public Rule {
 public:
  explicit StitchCountRule(const RuleContext& ctx)
      : Rule("program.stitch_count",
             "the programme makes as many stitches as its header declares (stitches=N)", ""),
        declared_(*ctx.declared_stitches) {
    summary_.error_limit = static_cast<double>(declared_);
  }
  void OnLine(const trace::LineRecord& line) override { last_line_ = line.source_line; }
  void OnSample(const trace::TraceSample& s) override {
    if (s.event == trace::SampleEvent::kNeedleEntry) ++made_;
  }
  void Finish(const RuleContext&) override {
    Counted();
    Observe(static_cast<double>(made_), last_line_, 0, nullptr);
    if (made_ == declared_) return;
    Record(FindingSeverity::kError, static_cast<double>(made_), static_cast<double>(declared_),
           last_line_, 0, "programme",
           "the header declares " + std::to_string(declared_) +
               " stitches but the programme makes " + std::to_string(made_) +
               " (cut short or edited?); the last motion is on this line",
           nullptr);
  }

 protected:
  void AbsorbExtra(const Rule& later) override {
    const auto& l = dynamic_cast<const StitchCountRule&>(later);
    made_ += l.made_;
    if (l.last_line_ != 0) last_line_ = l.last_line_;
  }
  void ResetExtra() override {
    made_ = 0;
    last_line_ = 0;
  }
  void SaveExtra(nlohmann::json& extra) const override {
    extra["made"] = made_;
    extra["last_line"] = last_line_;
  }
  bool LoadExtra(const nlohmann::json& extra) override {
    const long made = extra.at("made").get<long>();
    last_line_ = extra.at("last_line").get<int>();
    made_ = made;
    return true;
  }

 private:
  long declared_;      ///< config
  long made_ = 0;      ///< accumulator: needle entries
  int last_line_ = 0;  ///< accumulator: the last line seen (0: none), where a finding goes
};

}  // namespace

RuleEntry SyncRuleEntry() {
  return {"program.sync", CloseUpFamily::kNone, detail::RunsAlways, detail::Make<SyncRule>};
}
RuleEntry EmptyProgramRuleEntry() {
  return {"program.empty", CloseUpFamily::kNone, detail::RunsWhenStitching,
          detail::Make<EmptyProgramRule>};
}
RuleEntry StitchCountRuleEntry() {
  // Only a programme whose header declares its stitch count (`stitches=N`).
  return {"program.stitch_count", CloseUpFamily::kNone,
          [](const RuleContext& ctx) {
            return RulePresence::RunsIf(ctx.scene->head.IsStitching() &&
                                        ctx.declared_stitches.has_value());
          },
          detail::Make<StitchCountRule>};
}

}  // namespace stitchsim::verify
