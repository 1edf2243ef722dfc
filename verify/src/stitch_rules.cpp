// The stitch formation rules (stitch.*): where the needles pierce the surface, and how the
// head stands there.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "detail/carry_bytes.h"
#include "detail/rule_registry.h"
#include "detail/text_format.h"
#include "stitchsim/common/units.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

using scene::LimitKey;

using detail::Fmt;

class StitchLengthRule final : public Rule {
 public:
  explicit StitchLengthRule(const RuleContext& ctx)
      : Rule("stitch.length",
             "stitch length on the surface per needle against the programme's stitch length, "
             "between consecutive penetrations of a seam (rule limits: the needle at the tool "
             "point; insertion limits for the other needles, if given)",
             "%"),
        ctx_(ctx) {
    summary_.error_limit = ctx.scene->limits.Get(LimitKey::kStitchLengthErrorPct);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kStitchLengthWarningPct);
    insertion_error_ = ctx.scene->limits.Get(LimitKey::kStitchLengthInsertionErrorPct);
    insertion_warning_ = ctx.scene->limits.Get(LimitKey::kStitchLengthInsertionWarningPct);
    // With two or more needles, each needle's figure beside its own limits.
    const auto& needles = ctx.process->needles;
    for (const scene::NeedleSpec& n : needles) {
      const bool at_tool_point = n.through_mm.norm() < 1e-9;
      at_tool_point_.push_back(at_tool_point);
      if (needles.size() < 2) continue;
      AddSubject(n.name, at_tool_point ? summary_.error_limit : insertion_error_,
                 at_tool_point ? summary_.warning_limit : insertion_warning_);
    }
  }
  // A seam ends where stitching is switched off (M11) or the head retracts (M20): the
  // dialect has no thread-cut code. A move with the needles out inside a seam (stitching on,
  // head down) does not end it: it lengthens the stitch the next penetration closes.
  void OnLine(const trace::LineRecord& l) override {
    if (!l.stitching || l.head_retracted) previous_.reset();
  }
  void OnPenetration(const PenetrationRecord& p) override {
    const auto& needles = ctx_.process->needles;
    if (previous_ && previous_->stitch == p.stitch - 1) {
      const double l = ctx_.process->stitch_length_mm;
      for (std::size_t k = 0; k < needles.size(); ++k) {
        if (!p.points[k] || !previous_->points[k]) continue;
        const double len = (*p.points[k] - *previous_->points[k]).norm();
        const double dev = std::abs(len - l) / l * 100.0;
        // Stitch k-1 ends where stitch k starts: report it on the earlier stitch.
        if (k < summary_.subjects.size()) ObserveSubject(k, dev, p.line, p.stitch - 1);
        const auto what = [&] {
          return needles[k].name + " needle stitch of " + Fmt("%.4g", len) + " mm: deviation";
        };
        if (at_tool_point_[k]) {
          CheckUpper(dev, p.line, p.stitch - 1, needles[k].name, what, &p.sample);
          continue;
        }
        // A needle off the tool point: its own (insertion) limits, if any.
        const std::optional<double>* lim[2] = {&insertion_error_, &insertion_warning_};
        for (int s = 0; s < 2; ++s) {
          if (*lim[s] && dev > **lim[s]) {
            Record(s == 0 ? FindingSeverity::kError : FindingSeverity::kWarning, dev, **lim[s],
                   p.line, p.stitch - 1, needles[k].name,
                   needles[k].name +
                       Fmt(" needle stitch of %.4g mm deviates %.3g %% from ", len, dev) +
                       Fmt("%.4g mm (its limit %.4g %%)", l, **lim[s]),
                   &p.sample);
            break;
          }
        }
      }
    }
    previous_ = p;
  }

  // Carry: the last penetration of the seam (what the next one is measured from), bitwise.
  void SaveCarry(std::string& out) const override {
    detail::AppendBytes(out, previous_.has_value());
    if (!previous_) return;
    detail::AppendBytes(out, previous_->stitch);
    detail::AppendBytes(out, previous_->points.size());
    for (const auto& point : previous_->points) {
      detail::AppendBytes(out, point.has_value());
      if (point) detail::AppendMatrix(out, *point);
    }
  }
  void AbsorbExtra(const Rule& later) override {
    if (later.SawAnything()) previous_ = dynamic_cast<const StitchLengthRule&>(later).previous_;
  }

 private:
  // Config: the context, at_tool_point_ and the insertion limits. Carry: previous_.
  const RuleContext& ctx_;
  std::optional<PenetrationRecord> previous_;
  std::vector<bool> at_tool_point_;  ///< per needle: the rule's own limits apply
  std::optional<double> insertion_error_, insertion_warning_;  ///< the other needles' limits
};

class StitchWidthRule final : public Rule {
 public:
  explicit StitchWidthRule(const RuleContext& ctx)
      : Rule("stitch.width",
             "spacing of the insertion and catcher penetrations on the surface against nominal",
             "%"),
        ctx_(ctx) {
    summary_.error_limit = ctx.scene->limits.Get(LimitKey::kStitchWidthErrorPct);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kStitchWidthWarningPct);
  }
  void OnPenetration(const PenetrationRecord& p) override {
    const double nominal = ctx_.process->nominal_width_mm;
    if (p.points.size() < 2 || nominal <= 0) return;
    if (!p.points[0] || !p.points[1]) return;
    const double width = (*p.points[1] - *p.points[0]).norm();
    const double dev = (width - nominal) / nominal * 100.0;
    CheckUpper(
        std::abs(dev), p.line, p.stitch, "width",
        [&] { return Fmt("stitch width %.4g mm (%+.3g %% from nominal); deviation", width, dev); },
        &p.sample);
  }

 private:
  const RuleContext& ctx_;
};

class StandoffRule final : public Rule {
 public:
  explicit StandoffRule(const RuleContext& ctx)
      : Rule("stitch.standoff", "tool point distance from the stitching surface at needle entry",
             "mm") {
    summary_.error_limit = ctx.scene->limits.Get(LimitKey::kStandoffErrorMm);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kStandoffWarningMm);
  }
  void OnPenetration(const PenetrationRecord& p) override {
    const double d = p.foot.signed_distance_mm;
    CheckUpper(
        std::abs(d), p.line, p.stitch, "tool point",
        [&] {
          return std::string("tool point ") + (d < 0 ? "below" : "above") +
                 " the stitching surface; standoff";
        },
        &p.sample);
  }
};

class NormalityRule final : public Rule {
 public:
  explicit NormalityRule(const RuleContext& ctx)
      : Rule("stitch.normality",
             "angle between the head z axis and the surface normal at needle "
             "entry",
             "deg") {
    summary_.error_limit = ctx.scene->limits.Get(LimitKey::kNormalityErrorDeg);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kNormalityWarningDeg);
  }
  void OnPenetration(const PenetrationRecord& p) override {
    const double c = std::clamp(p.tool.linear().col(2).dot(p.foot.normal), -1.0, 1.0);
    CheckUpper(
        std::acos(c) * kRadToDeg, p.line, p.stitch, "head z",
        [] { return std::string("head tilt from the normal"); }, &p.sample);
  }
};

}  // namespace

RuleEntry StitchLengthRuleEntry() {
  return {"stitch.length", CloseUpFamily::kStitch, detail::RunsWhenStitching,
          detail::Make<StitchLengthRule>};
}
RuleEntry StitchWidthRuleEntry() {
  // The spacing of the insertion and catcher penetrations: two needles or more.
  return {"stitch.width", CloseUpFamily::kStitch,
          [](const RuleContext& ctx) {
            return RulePresence::RunsIf(ctx.scene->head.IsStitching() &&
                                        ctx.process->needles.size() >= 2);
          },
          detail::Make<StitchWidthRule>};
}
RuleEntry StandoffRuleEntry() {
  return {"stitch.standoff", CloseUpFamily::kStitch, detail::RunsWhenStitching,
          detail::Make<StandoffRule>};
}
RuleEntry NormalityRuleEntry() {
  return {"stitch.normality", CloseUpFamily::kStitch, detail::RunsWhenStitching,
          detail::Make<NormalityRule>};
}

}  // namespace stitchsim::verify
