// The needle rules (needle.*): the process model's metrics of each needle window.
#include <algorithm>
#include <memory>
#include <string>

#include "detail/rule_registry.h"
#include "detail/text_format.h"
#include "stitchsim/common/units.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

using scene::LimitKey;

using detail::Fmt;

class RotationInPreformRule final : public Rule {
 public:
  explicit RotationInPreformRule(const RuleContext& ctx)
      : Rule("needle.rotation_in_preform",
             "head rotation about tool x, y, z and in total while the needles are in the preform",
             "deg") {
    const LimitKey keys[4] = {LimitKey::kRotationXErrorDeg, LimitKey::kRotationYErrorDeg,
                              LimitKey::kRotationZErrorDeg, LimitKey::kRotationTotalErrorDeg};
    for (int i = 0; i < 4; ++i) limit_deg_[i] = ctx.scene->limits.Get(keys[i]);
    summary_.error_limit = limit_deg_[2] ? limit_deg_[2] : limit_deg_[3];
  }
  void OnWindow(const WindowRecord& w) override {
    Counted();
    static const char* names[4] = {"about x", "about y", "about z", "total"};
    double values[4];
    for (int i = 0; i < 3; ++i) values[i] = w.metrics.rotation_rad[i] * kRadToDeg;
    values[3] = w.metrics.rotation_total_rad * kRadToDeg;
    double worst = 0.0;
    for (int i = 0; i < 4; ++i) worst = std::max(worst, values[i]);
    Observe(worst, w.exit_line, w.stitch, &w.exit_sample);
    for (int i = 0; i < 4; ++i) {
      if (limit_deg_[i] && values[i] > *limit_deg_[i]) {
        Record(FindingSeverity::kError, values[i], *limit_deg_[i], w.exit_line, w.stitch, names[i],
               "head rotated " + Fmt("%.3g", values[i]) + " deg (" + names[i] +
                   ") while the needles were in the preform; limit " + Fmt("%.3g", *limit_deg_[i]) +
                   " deg",
               &w.exit_sample);
        break;
      }
    }
  }

 private:
  std::optional<double> limit_deg_[4];
};

class SideForceRule final : public Rule {
 public:
  explicit SideForceRule(const RuleContext& ctx)
      : Rule("needle.side_force",
             "side-force proxy per needle: lateral drift of the shaft inside the preform from its "
             "entry, after the walk",
             "mm"),
        ctx_(ctx) {
    summary_.error_limit = ctx.scene->limits.Get(LimitKey::kSideForceErrorMm);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kSideForceWarningMm);
    stiffness_ = ctx.scene->limits.Get(LimitKey::kSideForceStiffness);
  }
  void OnWindow(const WindowRecord& w) override {
    const auto& needles = ctx_.process->needles;
    for (std::size_t k = 0; k < needles.size(); ++k) {
      const double v = w.metrics.side_force_mm[k];
      CheckUpper(
          v, w.exit_line, w.stitch, needles[k].name,
          [&] {
            std::string what = "side-force proxy on the " + needles[k].name + " needle";
            if (stiffness_) what += Fmt(" (about %.3g N)", v * *stiffness_);
            return what;
          },
          &w.exit_sample);
    }
  }

 private:
  const RuleContext& ctx_;
  std::optional<double> stiffness_;
};

class WalkRule final : public Rule {
 public:
  explicit WalkRule(const RuleContext& ctx)
      : Rule("needle.walk", "needle walk the motion asks for, against the walk capacity", "mm") {
    summary_.error_limit = ctx.scene->limits.Get(LimitKey::kWalkErrorMm);
    if (!summary_.error_limit) summary_.error_limit = ctx.process->walk_capacity_mm;
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kWalkWarningMm);
  }
  void OnWindow(const WindowRecord& w) override {
    CheckUpper(
        w.metrics.walk_demand_mm, w.exit_line, w.stitch, "walk",
        [] { return std::string("walk demand"); }, &w.exit_sample);
  }
};

}  // namespace

RuleEntry RotationInPreformRuleEntry() {
  return {"needle.rotation_in_preform", CloseUpFamily::kNeedle, detail::RunsWhenStitching,
          detail::Make<RotationInPreformRule>};
}
RuleEntry SideForceRuleEntry() {
  return {"needle.side_force", CloseUpFamily::kNeedle, detail::RunsWhenStitching,
          detail::Make<SideForceRule>};
}
RuleEntry WalkRuleEntry() {
  return {"needle.walk", CloseUpFamily::kNeedle, detail::RunsWhenStitching, detail::Make<WalkRule>};
}

}  // namespace stitchsim::verify
