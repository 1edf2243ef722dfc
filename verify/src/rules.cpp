// The rules. Each is a small class; MakeRules at the bottom is the registry.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "afp_laid.h"
#include "detail/carry_bytes.h"
#include "detail/text_format.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

using scene::LimitKey;

using detail::Fmt;

// ---------------------------------------------------------------------------------------------
// Needle rules (the process model's window metrics).

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

// ---------------------------------------------------------------------------------------------
// Stitch formation (where the needles pierce the surface).

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

// ---------------------------------------------------------------------------------------------
// Programme bookkeeping.

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

}  // namespace

// collision_rules.cpp
std::unique_ptr<Rule> MakeCollisionHeadMoldRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeCollisionRobotCellRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeCollisionClearanceRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeConstraintCrossingRule(const RuleContext& ctx);  // constraint_rules.cpp
std::unique_ptr<Rule> MakeStitchCountRule(const RuleContext& ctx);         // program_rules.cpp
// kin_rules.cpp
std::unique_ptr<Rule> MakeReachRule();
std::unique_ptr<Rule> MakeJointLimitRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeSingularityRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeConfigFlipRule();
std::unique_ptr<Rule> MakeJointSpeedRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeLineSamplingRule();  // sampling_rule.cpp
// dynamics_rules.cpp
std::unique_ptr<Rule> MakeAccelerationRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeTorqueRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakePayloadRule(const RuleContext& ctx);
std::unique_ptr<Rule> MakeTrackingRule(const RuleContext& ctx);
// afp_*.cpp: the fibre-placement rules over what the programme lays (one sampler shared).
using LaidTowsPtr = std::shared_ptr<detail::LaidTows>;
std::unique_ptr<Rule> MakeAfpSteeringRule(const RuleContext& ctx, LaidTowsPtr laid);
std::unique_ptr<Rule> MakeAfpGapRule(const RuleContext& ctx, LaidTowsPtr laid);
std::unique_ptr<Rule> MakeAfpOverlapRule(const RuleContext& ctx, LaidTowsPtr laid);
std::unique_ptr<Rule> MakeAfpCompactionRule(const RuleContext& ctx, LaidTowsPtr laid);
std::unique_ptr<Rule> MakeAfpCoverageRule(const RuleContext& ctx, LaidTowsPtr laid);

namespace {

// kin.payload needs the head's mass (head spec `inertial:`) and the arm's load diagram.
bool PayloadCheckable(const RuleContext& ctx) {
  return ctx.scene->head.inertial && ctx.cell->payload_rated_kg > 0.0;
}

}  // namespace

std::vector<std::unique_ptr<Rule>> MakeRules(const RuleContext& ctx) {
  std::vector<std::unique_ptr<Rule>> rules;
  const bool stitching = ctx.scene->head.IsStitching();
  if (stitching) {
    rules.push_back(std::make_unique<RotationInPreformRule>(ctx));
    rules.push_back(std::make_unique<SideForceRule>(ctx));
    rules.push_back(std::make_unique<WalkRule>(ctx));
    rules.push_back(std::make_unique<StitchLengthRule>(ctx));
    if (ctx.process->needles.size() >= 2) rules.push_back(std::make_unique<StitchWidthRule>(ctx));
    rules.push_back(std::make_unique<StandoffRule>(ctx));
    rules.push_back(std::make_unique<NormalityRule>(ctx));
  } else {
    const LaidTowsPtr laid = detail::MakeLaidTows(ctx);
    rules.push_back(MakeAfpSteeringRule(ctx, laid));
    rules.push_back(MakeAfpGapRule(ctx, laid));
    rules.push_back(MakeAfpOverlapRule(ctx, laid));
    rules.push_back(MakeAfpCompactionRule(ctx, laid));
    rules.push_back(MakeAfpCoverageRule(ctx, laid));
  }
  rules.push_back(MakeReachRule());
  rules.push_back(MakeJointLimitRule(ctx));
  rules.push_back(MakeSingularityRule(ctx));
  rules.push_back(MakeConfigFlipRule());
  rules.push_back(MakeJointSpeedRule(ctx));
  if (ctx.cell->timed) rules.push_back(MakeAccelerationRule(ctx));
  if (ctx.cell->timed) rules.push_back(MakeTorqueRule(ctx));
  if (PayloadCheckable(ctx)) rules.push_back(MakePayloadRule(ctx));
  if (ctx.cell->dynamic) rules.push_back(MakeTrackingRule(ctx));
  rules.push_back(std::make_unique<SyncRule>(ctx));
  if (stitching) rules.push_back(std::make_unique<EmptyProgramRule>());
  if (stitching && ctx.declared_stitches) rules.push_back(MakeStitchCountRule(ctx));
  rules.push_back(MakeLineSamplingRule());
  if (ctx.cell->collision_checked) rules.push_back(MakeCollisionHeadMoldRule(ctx));
  if (ctx.cell->collision_checked) rules.push_back(MakeCollisionRobotCellRule(ctx));
  if (ctx.cell->collision_checked) rules.push_back(MakeCollisionClearanceRule(ctx));
  if (!ctx.scene->constraints.empty()) rules.push_back(MakeConstraintCrossingRule(ctx));
  return rules;
}

std::vector<SkippedRule> SkippedRules(const RuleContext& ctx) {
  std::vector<SkippedRule> skipped;
  if (!ctx.cell->timed) {
    for (const char* id : {"kin.acceleration", "kin.torque"}) {
      skipped.push_back({id, "the trace has no timed trajectory"});
    }
  }
  if (!PayloadCheckable(ctx)) {
    skipped.push_back({"kin.payload", ctx.scene->head.inertial
                                          ? "the cell model gives no load diagram"
                                          : "the head spec gives no mass (`inertial:`)"});
  }
  if (ctx.cell->collision_checked) return skipped;
  const std::string reason = "--no-collision";
  for (const char* id : {"collision.head_mold", "collision.robot_cell", "collision.clearance"}) {
    skipped.push_back({id, reason});
  }
  return skipped;
}

}  // namespace stitchsim::verify
