// The kinematic rules: the IK status of the solved samples (kin.reach, kin.joint_limit,
// kin.singularity, kin.config_flip) and the joint speed between them (kin.joint_speed).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "detail/carry_bytes.h"
#include "detail/rule_registry.h"
#include "detail/text_format.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

using scene::LimitKey;

using detail::Fmt;

// ---------------------------------------------------------------------------------------------
// Kinematics (IK status of the solved samples).

class IkStatusRule : public Rule {
 public:
  IkStatusRule(std::string id, std::string description, std::string unit, trace::IkStatus status)
      : Rule(std::move(id), std::move(description), std::move(unit)), status_(status) {}
  void OnSample(const trace::TraceSample& s) override {
    sample_line_ = s.source_line;
    if (!s.has_joints) return;
    Counted();
    if (s.ik_status != status_) return;
    // One finding per line: a line out of reach is one mistake, not one per sample.
    if (s.source_line == last_line_) return;
    last_line_ = s.source_line;
    const double v = Value(s);
    Observe(v, s.source_line, s.stitch, &s);
    Record(FindingSeverity::kError, v, Limit(), s.source_line, s.stitch, Subject(s), Message(s),
           &s);
  }

 protected:
  virtual double Value(const trace::TraceSample&) const { return 1.0; }
  virtual double Limit() const { return 0.0; }
  virtual std::string Subject(const trace::TraceSample&) const { return "arm"; }
  virtual std::string Message(const trace::TraceSample& s) const = 0;

  // Carry: the line already reported, while it is the line being sampled (a line is never
  // sampled again once the next one starts).
  void SaveCarry(std::string& out) const override {
    detail::AppendBytes(out, last_line_ == sample_line_ ? last_line_ : -1);
  }
  void AbsorbExtra(const Rule& later) override {
    const auto& l = dynamic_cast<const IkStatusRule&>(later);
    if (l.sample_line_ < 0) return;
    last_line_ = l.last_line_;
    sample_line_ = l.sample_line_;
  }

 private:
  trace::IkStatus status_;  // config
  int last_line_ = -1;      // carry: the last line with a finding
  int sample_line_ = -1;    // carry: the line of the last sample
};

std::string PoseText(const trace::TraceSample& s) {
  const Eigen::Vector3d p = s.tool_part.translation();
  return Fmt("tool point (%.2f, %.2f, %.2f) mm", p.x(), p.y(), p.z());
}

class ReachRule final : public IkStatusRule {
 public:
  ReachRule()
      : IkStatusRule("kin.reach", "tool poses the arm cannot reach from the rail", "",
                     trace::IkStatus::kUnreachable) {}
  std::string Message(const trace::TraceSample& s) const override {
    return PoseText(s) + " is out of the arm's reach (rail at " +
           Fmt("%.0f mm)", s.joints[trace::kRailX] * 1000.0);
  }
};

class JointLimitRule final : public IkStatusRule {
 public:
  explicit JointLimitRule(const RuleContext& ctx)
      : IkStatusRule("kin.joint_limit", "joints beyond their URDF limits (deg, rail mm)", "deg",
                     trace::IkStatus::kJointLimit),
        cell_(ctx.cell) {}
  double Value(const trace::TraceSample& s) const override { return Excess(s).first; }
  std::string Subject(const trace::TraceSample& s) const override {
    return cell_->joint_names[static_cast<std::size_t>(Excess(s).second)];
  }
  std::string Message(const trace::TraceSample& s) const override {
    const auto [v, j] = Excess(s);
    return PoseText(s) + " needs joint " + cell_->joint_names[static_cast<std::size_t>(j)] + " " +
           Fmt("%.3g", v) + (j == trace::kRailX ? " mm" : " deg") + " beyond its limit";
  }

 private:
  std::pair<double, int> Excess(const trace::TraceSample& s) const {
    double worst = 0.0;
    int joint = trace::kA1;
    for (int j = 0; j < trace::kNumJoints; ++j) {
      const double lo = cell_->lower_limits[j], hi = cell_->upper_limits[j];
      double e = std::max(lo - s.joints[j], s.joints[j] - hi);
      e *= j == trace::kRailX ? 1000.0 : kRadToDeg;
      if (e > worst) {
        worst = e;
        joint = j;
      }
    }
    return {worst, joint};
  }
  const trace::CellDescription* cell_;
};

class SingularityRule final : public IkStatusRule {
 public:
  explicit SingularityRule(const RuleContext& ctx)
      : IkStatusRule("kin.singularity", "wrist (a5 near 0) or shoulder singular poses", "deg",
                     trace::IkStatus::kWristSingularity),
        a5_min_deg_(ctx.scene->limits.Value(LimitKey::kSingularityA5MinDeg)) {
    summary_.error_limit = a5_min_deg_;
  }
  void OnSample(const trace::TraceSample& s) override {
    if (s.has_joints && s.ik_status == trace::IkStatus::kShoulderSingularity) {
      Record(FindingSeverity::kError, 0.0, 0.0, s.source_line, s.stitch, "shoulder",
             PoseText(s) + " puts the wrist centre on the a1 axis (shoulder singularity)", &s);
    }
    IkStatusRule::OnSample(s);
  }
  double Value(const trace::TraceSample& s) const override {
    return std::abs(s.joints[trace::kA5]) * kRadToDeg;
  }
  double Limit() const override { return a5_min_deg_; }
  std::string Subject(const trace::TraceSample&) const override { return "a5"; }
  std::string Message(const trace::TraceSample& s) const override {
    return PoseText(s) + Fmt(" puts a5 at %.3g deg, inside the %.3g deg wrist singularity band",
                             Value(s), a5_min_deg_);
  }

 private:
  double a5_min_deg_;
};

class ConfigFlipRule final : public IkStatusRule {
 public:
  ConfigFlipRule()
      : IkStatusRule("kin.config_flip",
                     "arm configuration (shoulder/elbow/wrist) changes between consecutive poses",
                     "", trace::IkStatus::kConfigFlip) {}
  std::string Message(const trace::TraceSample& s) const override {
    return PoseText(s) + " is reachable only by flipping the arm configuration to " +
           trace::ToString(s.configuration);
  }
};

class JointSpeedRule final : public Rule {
 public:
  explicit JointSpeedRule(const RuleContext& ctx)
      : Rule("kin.joint_speed", "joint speed at the programmed feed against the URDF maximum", "%"),
        cell_(ctx.cell) {
    summary_.error_limit = 100.0 * ctx.scene->limits.Value(LimitKey::kJointSpeedMaxFraction);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kJointSpeedWarningPct);
  }
  void OnSample(const trace::TraceSample& s) override {
    if (!s.has_joints) return;
    const bool usable = trace::IkUsable(s.ik_status);
    if (have_ && usable) {
      const double dt = s.time_s - time_;
      if (dt > 1e-9) {
        double worst = 0.0;
        int joint = 0;
        for (int j = 0; j < trace::kNumJoints; ++j) {
          const double pct = std::abs(s.joints[j] - q_[j]) / dt / cell_->max_velocities[j] * 100.0;
          if (pct > worst) {
            worst = pct;
            joint = j;
          }
        }
        const std::string& name = cell_->joint_names[static_cast<std::size_t>(joint)];
        CheckUpper(
            worst, s.source_line, s.stitch, name,
            [&] { return "joint " + name + " speed (of its maximum)"; }, &s);
      }
    }
    if (usable) {
      q_ = s.joints;
      time_ = s.time_s;
      have_ = true;
    }
  }

  // Carry: the last usable sample (bitwise).
  void SaveCarry(std::string& out) const override {
    detail::AppendBytes(out, have_);
    if (!have_) return;
    detail::AppendMatrix(out, q_);
    detail::AppendBytes(out, time_);
  }
  void AbsorbExtra(const Rule& later) override {
    const auto& l = dynamic_cast<const JointSpeedRule&>(later);
    if (!l.have_) return;
    q_ = l.q_;
    time_ = l.time_;
    have_ = true;
  }

 private:
  const trace::CellDescription* cell_;                 // config
  trace::JointVector q_ = trace::JointVector::Zero();  // carry: the last usable sample's joints
  double time_ = 0.0;                                  // carry: its time, s
  bool have_ = false;                                  // carry: there is one
};

}  // namespace

RuleEntry ReachRuleEntry() {
  return {"kin.reach", CloseUpFamily::kKinematics, detail::RunsAlways, detail::Make<ReachRule>};
}
RuleEntry JointLimitRuleEntry() {
  return {"kin.joint_limit", CloseUpFamily::kKinematics, detail::RunsAlways,
          detail::Make<JointLimitRule>};
}
RuleEntry SingularityRuleEntry() {
  return {"kin.singularity", CloseUpFamily::kKinematics, detail::RunsAlways,
          detail::Make<SingularityRule>};
}
RuleEntry ConfigFlipRuleEntry() {
  return {"kin.config_flip", CloseUpFamily::kKinematics, detail::RunsAlways,
          detail::Make<ConfigFlipRule>};
}
RuleEntry JointSpeedRuleEntry() {
  return {"kin.joint_speed", CloseUpFamily::kKinematics, detail::RunsAlways,
          detail::Make<JointSpeedRule>};
}

}  // namespace stitchsim::verify
