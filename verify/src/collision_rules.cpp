// Collision rules: what the executor's collision world measured at every trace sample with
// usable joints (line ends, the coarse IK grid and the extra samples that keep consecutive
// checks closer than the measured clearance), read from the trace. Bodies are indices into
// the trace's body table (CellDescription::bodies).
#include <cstdio>
#include <set>
#include <utility>

#include "detail/carry_bytes.h"
#include "detail/rule_registry.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

std::string PointText(const Eigen::Vector3d& p_m) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.0f, %.0f, %.0f) mm", p_m.x() * 1000.0, p_m.y() * 1000.0,
                p_m.z() * 1000.0);
  return buf;
}

// A body's name from the trace's table ("" for none).
const std::string& BodyName(const trace::CellDescription& cell, int index) {
  static const std::string kNone;
  return index >= 0 && static_cast<std::size_t>(index) < cell.bodies.size()
             ? cell.bodies[static_cast<std::size_t>(index)]
             : kNone;
}

// One finding per line (Rule::Record merges the body pairs of a line: the deepest stays); a
// pair is recorded at its first contact on the line.
class ContactRule final : public Rule {
 public:
  ContactRule(const RuleContext& ctx, std::string id, std::string description,
              trace::ContactClass kind)
      : Rule(std::move(id), std::move(description), "mm"), cell_(*ctx.cell), kind_(kind) {
    summary_.error_limit = 0.0;
  }
  void OnSample(const trace::TraceSample& s) override {
    sample_line_ = s.source_line;
    if (!s.collision.checked) return;
    const trace::SampleCollision& r = s.collision;
    Counted();
    if (!r.error.empty()) {
      if (kind_ == trace::ContactClass::kRobotCell) {
        Record(FindingSeverity::kError, 0.0, 0.0, s.source_line, s.stitch, "fcl",
               "collision query failed: " + r.error, &s);
      }
      return;
    }
    if (s.source_line != line_) {
      line_ = s.source_line;
      seen_.clear();
    }
    for (const trace::Contact& c : r.contacts) {
      if (c.kind != kind_) continue;
      const double depth_mm = c.depth_m * 1000.0;
      Observe(depth_mm, s.source_line, s.stitch, &s);
      const std::string& a = BodyName(cell_, c.body_a);
      const std::string& b = BodyName(cell_, c.body_b);
      const std::string subject = a + "|" + b;
      if (!seen_.insert(subject).second) continue;
      Record(
          FindingSeverity::kError, depth_mm, 0.0, s.source_line, s.stitch, subject,
          a + " hits " + b + " at " + PointText(c.point_world_m) +
              (c.depth_measured ? " (world), depth " + std::to_string(depth_mm).substr(0, 5) + " mm"
                                : std::string(" (world), depth not measured (mesh)")),
          &s);
    }
  }

  // Carry: the pairs already recorded on the line, while it is the line being sampled.
  void SaveCarry(std::string& out) const override {
    const bool current = line_ == sample_line_ && line_ >= 0;
    detail::AppendBytes(out, current ? line_ : -1);
    if (!current) return;
    for (const std::string& pair : seen_) detail::AppendString(out, pair);
  }

 protected:
  void AbsorbExtra(const Rule& later) override {
    const auto& l = dynamic_cast<const ContactRule&>(later);
    if (l.sample_line_ < 0) return;
    line_ = l.line_;
    seen_ = l.seen_;
    sample_line_ = l.sample_line_;
  }

 private:
  const trace::CellDescription& cell_;  // config
  trace::ContactClass kind_;            // config
  int line_ = -1;                       // carry: the line seen_ is of
  std::set<std::string> seen_;          // carry: body pairs recorded on line_
  int sample_line_ = -1;                // carry: the line of the last sample
};

// Warns when the smallest distance between bodies that may not touch falls under the margin;
// one finding per line (its smallest clearance).
class ClearanceRule final : public Rule {
 public:
  explicit ClearanceRule(const RuleContext& ctx)
      : Rule("collision.clearance",
             "smallest distance between bodies that must not touch, under the margin (mm)", "mm"),
        cell_(*ctx.cell) {
    summary_.warning_limit = ctx.scene->limits.Value(scene::LimitKey::kClearanceWarningMm);
    worst_is_smallest_ = true;
  }
  void OnSample(const trace::TraceSample& s) override {
    sample_line_ = s.source_line;
    if (!s.collision.checked) return;
    const trace::SampleCollision& r = s.collision;
    Counted();
    if (!r.error.empty() || !r.contacts.empty()) return;  // the contact rules report those
    const double mm = r.min_clearance_m * 1000.0;
    if (r.min_clearance_m < 1e8) Plot(s.source_line, mm);
    if (!summary_.worst_value || mm < *summary_.worst_value) {
      summary_.worst_value = mm;
      summary_.worst_line = s.source_line;
      summary_.worst_stitch = s.stitch;
    }
    if (mm >= *summary_.warning_limit) return;
    if (s.source_line == line_ && mm >= line_worst_) return;
    const std::string pair = PairText(r);
    if (s.source_line != line_) {
      line_ = s.source_line;
      Record(FindingSeverity::kWarning, mm, *summary_.warning_limit, s.source_line, s.stitch, pair,
             pair + " only " + std::to_string(mm).substr(0, 5) + " mm apart", &s);
    } else if (!summary_.findings.empty() && summary_.findings.back().line == line_) {
      auto& f = summary_.findings.back();
      f.value = mm;
      f.subject = pair;
      f.message = pair + " only " + std::to_string(mm).substr(0, 5) + " mm apart";
    }
    line_worst_ = mm;
  }

  // Carry: the line's smallest clearance reported so far, while it is the line being sampled.
  void SaveCarry(std::string& out) const override {
    const bool current = line_ == sample_line_ && line_ >= 0;
    detail::AppendBytes(out, current ? line_ : -1);
    if (current) detail::AppendBytes(out, line_worst_);
  }

 protected:
  void AbsorbExtra(const Rule& later) override {
    const auto& l = dynamic_cast<const ClearanceRule&>(later);
    if (l.sample_line_ < 0) return;
    line_ = l.line_;
    line_worst_ = l.line_worst_;
    sample_line_ = l.sample_line_;
  }

 private:
  // "a|b" of the nearest pair ("" when nothing is within the world's cutoff).
  std::string PairText(const trace::SampleCollision& r) const {
    if (r.clearance_body_a < 0) return "";
    return BodyName(cell_, r.clearance_body_a) + "|" + BodyName(cell_, r.clearance_body_b);
  }

  const trace::CellDescription& cell_;  // config
  int line_ = -1;                       // carry: the last line with a finding
  double line_worst_ = 0.0;             // carry: its smallest clearance reported, mm
  int sample_line_ = -1;                // carry: the line of the last sample
};

}  // namespace

namespace {

// The collision.* rules run when the trace carries collision results (skipped with
// --no-collision).
RulePresence RunsWhenCollisionChecked(const RuleContext& ctx) {
  return ctx.cell->collision_checked ? RulePresence::Runs()
                                     : RulePresence::Skipped("--no-collision");
}

}  // namespace

RuleEntry CollisionHeadMoldRuleEntry() {
  return {"collision.head_mold", CloseUpFamily::kCollision, RunsWhenCollisionChecked,
          [](const RuleContext& ctx, detail::RuleMaking&) -> std::unique_ptr<Rule> {
            return std::make_unique<ContactRule>(ctx, "collision.head_mold",
                                                 "head or arm interfering with the mold, preform "
                                                 "or a constraint (penetration depth, mm)",
                                                 trace::ContactClass::kHeadPart);
          }};
}
RuleEntry CollisionRobotCellRuleEntry() {
  return {"collision.robot_cell", CloseUpFamily::kCollision, RunsWhenCollisionChecked,
          [](const RuleContext& ctx, detail::RuleMaking&) -> std::unique_ptr<Rule> {
            return std::make_unique<ContactRule>(ctx, "collision.robot_cell",
                                                 "arm, carriage or head interfering with the "
                                                 "rail, rotator, table, floor or another link "
                                                 "(penetration depth, mm)",
                                                 trace::ContactClass::kRobotCell);
          }};
}
RuleEntry CollisionClearanceRuleEntry() {
  return {"collision.clearance", CloseUpFamily::kCollision, RunsWhenCollisionChecked,
          detail::Make<ClearanceRule>};
}

}  // namespace stitchsim::verify
