// The rules of the timed trajectory and the dynamic run: joint accelerations and torques
// (kin.acceleration, kin.torque), the head against the arm's load diagram (kin.payload) and the
// servo's tracking error (dyn.tracking). docs/timing.md.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "detail/rule_registry.h"
#include "detail/text_format.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

using scene::LimitKey;

using detail::Fmt;

// Percent of a per-joint limit at each sample with timed joints; the worst joint is the subject.
class JointLoadRule : public Rule {
 public:
  JointLoadRule(std::string id, std::string description, const trace::CellDescription* cell,
                const trace::JointVector& limits, const char* quantity)
      : Rule(std::move(id), std::move(description), "%"),
        cell_(cell),
        limits_(limits),
        quantity_(quantity) {}
  void OnSample(const trace::TraceSample& s) override {
    if (!s.has_timing || !trace::JointsUsable(s) || !Applies(s)) return;
    const trace::JointVector& v = Values(s);
    double worst = 0.0;
    int joint = -1;
    for (int j = 0; j < trace::kNumJoints; ++j) {
      if (!(limits_[j] > 0.0)) continue;
      const double ratio = std::abs(v[j]) / limits_[j];
      if (joint < 0 || ratio > worst) {
        worst = ratio;
        joint = j;
      }
    }
    if (joint < 0) return;
    // To a millionth of a percent: the time law plans exactly at a limit, and the last bits
    // of the finite differences are not a finding.
    worst = std::round(worst * 1e8) / 1e6;
    const std::string& name = cell_->joint_names[static_cast<std::size_t>(joint)];
    const bool rail = joint == trace::kRailX;
    CheckUpper(
        worst, s.source_line, s.stitch, name,
        [&] {
          return "joint " + name + " " + quantity_ + " " + Detail(v[joint], limits_[joint], rail) +
                 " (of its limit)";
        },
        &s);
  }

 protected:
  virtual const trace::JointVector& Values(const trace::TraceSample& s) const = 0;
  virtual bool Applies(const trace::TraceSample&) const { return true; }
  virtual std::string Detail(double value, double limit, bool rail) const = 0;

 private:
  const trace::CellDescription* cell_;
  trace::JointVector limits_;
  std::string quantity_;
};

class AccelerationRule final : public JointLoadRule {
 public:
  explicit AccelerationRule(const RuleContext& ctx)
      : JointLoadRule("kin.acceleration",
                      "joint acceleration on the timed trajectory against the URDF's limit",
                      ctx.cell, ctx.cell->max_accelerations, "acceleration") {
    summary_.error_limit = 100.0 * ctx.scene->limits.Value(LimitKey::kAccelerationMaxFraction);
  }

 protected:
  const trace::JointVector& Values(const trace::TraceSample& s) const override {
    return s.joint_accelerations;
  }
  std::string Detail(double v, double limit, bool rail) const override {
    return rail ? Fmt("%.3g m/s^2, limit %.3g", std::abs(v), limit)
                : Fmt("%.3g deg/s^2, limit %.3g", std::abs(v) * kRadToDeg, limit * kRadToDeg);
  }
};

class TorqueRule final : public JointLoadRule {
 public:
  explicit TorqueRule(const RuleContext& ctx)
      : JointLoadRule("kin.torque",
                      "joint torque (rail force) the timed trajectory needs, by MuJoCo's inverse "
                      "dynamics, against the URDF effort limit",
                      ctx.cell, ctx.cell->max_efforts, "torque") {
    summary_.error_limit = 100.0 * ctx.scene->limits.Value(LimitKey::kTorqueMaxFraction);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kTorqueWarningPct);
  }

 protected:
  const trace::JointVector& Values(const trace::TraceSample& s) const override {
    return s.joint_torques;
  }
  // The torques are computed on the executor's grid (line ends, events, the IK grid), not at
  // the collision subdivision's extra samples between them.
  bool Applies(const trace::TraceSample& s) const override { return !s.collision_probe; }
  std::string Detail(double v, double limit, bool rail) const override {
    return rail ? Fmt("%.4g N, limit %.4g N", std::abs(v), limit)
                : Fmt("%.4g N m, limit %.4g N m", std::abs(v), limit);
  }
};

// The head on the flange against the load diagram: its mass, its moment about a5 (lever from
// the a5 axis to the centre of mass) and about a6 (lever off the flange axis), each against
// the rated payload's at its rated centre of mass. Checked once, on the first motion line.
class PayloadRule final : public Rule {
 public:
  explicit PayloadRule(const RuleContext& ctx)
      : Rule("kin.payload",
             "head mass and centre of mass against the arm's load diagram (mass, moments about "
             "a5 and a6)",
             "%"),
        ctx_(ctx) {
    summary_.error_limit = 100.0 * ctx.scene->limits.Value(LimitKey::kPayloadMaxFraction);
  }
  void OnLine(const trace::LineRecord& l) override {
    if (line_ == 0) line_ = l.source_line;
  }
  void Finish(const RuleContext&) override {
    if (line_ == 0) return;
    const trace::CellDescription& c = *ctx_.cell;
    const scene::HeadInertial& h = *ctx_.scene->head.inertial;
    const double lz = h.com_m.z(), lxy = std::hypot(h.com_m.x(), h.com_m.y());
    const auto a5_lever = [&](double z, double xy) {
      return std::hypot(c.wrist_to_flange_m + z, xy);
    };
    struct Part {
      const char* subject;
      double pct;
    };
    const Part parts[3] = {
        {"mass", h.mass_kg / c.payload_rated_kg * 100.0},
        {"a5 moment",
         h.mass_kg * a5_lever(lz, lxy) /
             (c.payload_rated_kg * a5_lever(c.payload_rated_lz_m, c.payload_rated_lxy_m)) * 100.0},
        {"a6 moment", c.payload_rated_lxy_m > 0.0
                          ? h.mass_kg * lxy / (c.payload_rated_kg * c.payload_rated_lxy_m) * 100.0
                          : 0.0},
    };
    const Part* worst = &parts[0];
    for (const Part& p : parts) {
      if (p.pct > worst->pct) worst = &p;
    }
    const std::string head = ctx_.scene->head.name;
    CheckUpper(
        worst->pct, line_, 0, worst->subject,
        [&] {
          return "head '" + head + "' (" +
                 Fmt("%.4g kg, centre of mass %.3g m along and %.3g m off the flange axis",
                     h.mass_kg, lz, lxy) +
                 ") against the load diagram (" +
                 Fmt("rated %.4g kg at %.3g m, %.3g m", c.payload_rated_kg, c.payload_rated_lz_m,
                     c.payload_rated_lxy_m) +
                 "): " + worst->subject;
        },
        nullptr);
  }

 protected:
  void AbsorbExtra(const Rule& later) override {
    if (line_ == 0) line_ = dynamic_cast<const PayloadRule&>(later).line_;
  }
  void ResetExtra() override { line_ = 0; }
  void SaveExtra(nlohmann::json& extra) const override { extra["line"] = line_; }
  bool LoadExtra(const nlohmann::json& extra) override {
    line_ = extra.at("line").get<int>();
    return true;
  }

 private:
  const RuleContext& ctx_;  ///< config
  int line_ = 0;            ///< accumulator: the first motion line (0: none yet)
};

class TrackingRule final : public Rule {
 public:
  explicit TrackingRule(const RuleContext& ctx)
      : Rule("dyn.tracking",
             "tool point lag behind its command while the servos track the timed trajectory "
             "(verify --dynamics)",
             "mm") {
    summary_.error_limit = ctx.scene->limits.Get(LimitKey::kTrackingErrorMm);
    summary_.warning_limit = ctx.scene->limits.Get(LimitKey::kTrackingWarningMm);
  }
  void OnSample(const trace::TraceSample& s) override {
    if (!s.tracked) return;
    CheckUpper(
        s.tracking_error_mm, s.source_line, s.stitch, "tool point",
        [&] {
          return "tool point lag behind its command (" + Fmt("%.3g deg", s.tracking_error_deg) +
                 " in orientation)";
        },
        &s);
  }
};

}  // namespace

namespace {

// kin.acceleration and kin.torque read the timed trajectory.
RulePresence RunsWhenTimed(const RuleContext& ctx) {
  return ctx.cell->timed ? RulePresence::Runs()
                         : RulePresence::Skipped("the trace has no timed trajectory");
}

}  // namespace

RuleEntry AccelerationRuleEntry() {
  return {"kin.acceleration", CloseUpFamily::kKinematics, RunsWhenTimed,
          detail::Make<AccelerationRule>};
}
RuleEntry TorqueRuleEntry() {
  return {"kin.torque", CloseUpFamily::kKinematics, RunsWhenTimed, detail::Make<TorqueRule>};
}
RuleEntry PayloadRuleEntry() {
  // kin.payload needs the head's mass (head spec `inertial:`) and the arm's load diagram.
  return {"kin.payload", CloseUpFamily::kKinematics,
          [](const RuleContext& ctx) {
            if (!ctx.scene->head.inertial) {
              return RulePresence::Skipped("the head spec gives no mass (`inertial:`)");
            }
            if (ctx.cell->payload_rated_kg <= 0.0) {
              return RulePresence::Skipped("the cell model gives no load diagram");
            }
            return RulePresence::Runs();
          },
          detail::Make<PayloadRule>};
}
RuleEntry TrackingRuleEntry() {
  // Only with --dynamics (the trace carries the servos' actual joints).
  return {"dyn.tracking", CloseUpFamily::kKinematics,
          [](const RuleContext& ctx) { return RulePresence::RunsIf(ctx.cell->dynamic); },
          detail::Make<TrackingRule>};
}

}  // namespace stitchsim::verify
