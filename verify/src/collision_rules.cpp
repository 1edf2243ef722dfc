// Collision rules: the scene's FCL world queried at every trace sample that carries joints
// (line ends, the coarse IK grid and, when the executor was given the world, the extra samples
// that keep consecutive checks closer than the measured clearance).
#include <cstdio>
#include <set>
#include <utility>

#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

std::string PointText(const Eigen::Vector3d& p_m) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.0f, %.0f, %.0f) mm", p_m.x() * 1000.0, p_m.y() * 1000.0,
                p_m.z() * 1000.0);
  return buf;
}

bool Checkable(const sim::TraceSample& s) {
  return s.has_joints && s.ik_status != sim::IkStatus::kUnreachable &&
         s.ik_status != sim::IkStatus::kJointLimit;
}

// One finding per line (Rule::Record merges the body pairs of a line: the deepest stays); a
// pair is recorded at its first contact on the line.
class ContactRule final : public Rule {
 public:
  ContactRule(const RuleContext& ctx, std::string id, std::string description,
              sim::ContactClass kind)
      : Rule(std::move(id), std::move(description), "mm"), world_(ctx.collision), kind_(kind) {
    summary_.error_limit = 0.0;
  }
  void OnSample(const sim::TraceSample& s) override {
    if (!Checkable(s)) return;
    sim::CollisionOptions options;
    options.compute_clearance = true;  // shares the cached query with collision.clearance
    const sim::CollisionResult r = world_->Check(s.joints, options);
    Counted();
    if (!r.error.empty()) {
      if (kind_ == sim::ContactClass::kRobotCell) {
        Record(FindingSeverity::kError, 0.0, 0.0, s.source_line, s.stitch, "fcl",
               "collision query failed: " + r.error, &s);
      }
      return;
    }
    if (s.source_line != line_) {
      line_ = s.source_line;
      seen_.clear();
    }
    for (const sim::Contact& c : r.contacts) {
      if (c.kind != kind_) continue;
      const double depth_mm = c.depth_m * 1000.0;
      Observe(depth_mm, s.source_line, s.stitch, &s);
      const std::string subject = c.body_a + "|" + c.body_b;
      if (!seen_.insert(subject).second) continue;
      Record(
          FindingSeverity::kError, depth_mm, 0.0, s.source_line, s.stitch, subject,
          c.body_a + " hits " + c.body_b + " at " + PointText(c.point_world_m) +
              (c.depth_measured ? " (world), depth " + std::to_string(depth_mm).substr(0, 5) + " mm"
                                : std::string(" (world), depth not measured (mesh)")),
          &s);
    }
  }

 private:
  sim::CollisionWorld* world_;
  sim::ContactClass kind_;
  int line_ = -1;
  std::set<std::string> seen_;
};

// Warns when the smallest distance between bodies that may not touch falls under the margin;
// one finding per line (its smallest clearance).
class ClearanceRule final : public Rule {
 public:
  explicit ClearanceRule(const RuleContext& ctx)
      : Rule("collision.clearance",
             "smallest distance between bodies that must not touch, under the margin (mm)", "mm"),
        world_(ctx.collision) {
    summary_.warning_limit = ctx.scene->limits.Value(scene::LimitKey::kClearanceWarningMm);
  }
  void OnSample(const sim::TraceSample& s) override {
    if (!Checkable(s)) return;
    sim::CollisionOptions options;
    const sim::CollisionResult r = world_->Check(s.joints, options);
    Counted();
    if (!r.error.empty() || !r.contacts.empty()) return;  // the contact rules report those
    const double mm = r.min_clearance_m * 1000.0;
    if (!summary_.worst_value || mm < *summary_.worst_value) {
      summary_.worst_value = mm;
      summary_.worst_line = s.source_line;
      summary_.worst_stitch = s.stitch;
    }
    if (mm >= *summary_.warning_limit) return;
    if (s.source_line == line_ && mm >= line_worst_) return;
    if (s.source_line != line_) {
      line_ = s.source_line;
      Record(FindingSeverity::kWarning, mm, *summary_.warning_limit, s.source_line, s.stitch,
             r.min_clearance_pair,
             r.min_clearance_pair + " only " + std::to_string(mm).substr(0, 5) + " mm apart", &s);
    } else if (!summary_.findings.empty() && summary_.findings.back().line == line_) {
      auto& f = summary_.findings.back();
      f.value = mm;
      f.subject = r.min_clearance_pair;
      f.message = r.min_clearance_pair + " only " + std::to_string(mm).substr(0, 5) + " mm apart";
    }
    line_worst_ = mm;
  }

 private:
  sim::CollisionWorld* world_;
  int line_ = -1;
  double line_worst_ = 0.0;
};

}  // namespace

std::unique_ptr<Rule> MakeCollisionHeadMoldRule(const RuleContext& ctx) {
  return std::make_unique<ContactRule>(ctx, "collision.head_mold",
                                       "head or arm interfering with the mold, preform or a "
                                       "constraint (penetration depth, mm)",
                                       sim::ContactClass::kHeadPart);
}

std::unique_ptr<Rule> MakeCollisionRobotCellRule(const RuleContext& ctx) {
  return std::make_unique<ContactRule>(ctx, "collision.robot_cell",
                                       "arm, carriage or head interfering with the rail, rotator, "
                                       "table, floor or another link (penetration depth, mm)",
                                       sim::ContactClass::kRobotCell);
}

std::unique_ptr<Rule> MakeCollisionClearanceRule(const RuleContext& ctx) {
  return std::make_unique<ClearanceRule>(ctx);
}

}  // namespace stitchsim::verify
