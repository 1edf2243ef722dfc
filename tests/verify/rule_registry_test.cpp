// The rule registry: every rule has an id, a factory and the close-up family the snapshot
// table gives its id (docs/report-format.md, written out here by hand); for every context the
// rules MakeRules makes and those SkippedRules names are, together, the rules that apply to
// the head, each once, in registry order; and two contexts' lists written out by hand.
#include "stitchsim/verify/rule_registry.h"

#include <gtest/gtest.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "verify_test_support.h"

namespace stitchsim::verify {
namespace {

bool StartsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

scene::HeadInertial FiveKilograms() {
  scene::HeadInertial h;
  h.mass_kg = 5.0;
  return h;
}

// The snapshot family table of docs/report-format.md, by id.
std::string DocumentedFamily(const std::string& id) {
  if (StartsWith(id, "collision.")) return "collision";
  if (StartsWith(id, "needle.")) return "needle";
  if (StartsWith(id, "stitch.")) return "stitch";
  if (StartsWith(id, "kin.") || StartsWith(id, "dyn.")) return "kinematics";
  if (StartsWith(id, "constraint.")) return "constraint";
  if (id == "afp.compaction" || id == "afp.steering_radius" || id == "afp.gap" ||
      id == "afp.overlap" || id == "afp.min_tow_length" || id == "afp.restart_distance" ||
      id == "afp.fiber_angle" || id == "afp.stagger")
    return "afp";
  return "";  // program.* and afp.coverage: no close-up
}

TEST(RuleRegistry, EveryRuleHasAnIdAFactoryAndTheDocumentedFamily) {
  std::set<std::string> ids;
  ASSERT_GE(RuleRegistry().size(), 29u);
  for (const RuleEntry& e : RuleRegistry()) {
    const std::string id = e.id;
    EXPECT_FALSE(id.empty());
    EXPECT_NE(id.find('.'), std::string::npos) << id;
    EXPECT_TRUE(ids.insert(id).second) << id << " registered twice";
    EXPECT_NE(e.presence, nullptr) << id;
    EXPECT_NE(e.make, nullptr) << id;
    EXPECT_EQ(CloseUpFamilyName(e.close_up), DocumentedFamily(id)) << id;
  }
}

// One context: a bundled scene, and the run conditions set by hand.
struct Context {
  testing::Loaded loaded;
  std::unique_ptr<process::ProcessModel> process;
  trace::CellDescription cell;
  std::optional<long> declared;
  RuleContext Rules() const { return {loaded.scene.get(), &cell, process.get(), declared}; }
};

Context MakeContext(const std::string& scene) {
  Context c;
  c.loaded = testing::Load(scene);
  c.process =
      std::make_unique<process::ProcessModel>(process::MakeProcessModel(*c.loaded.scene, 5.0));
  c.cell.lower_limits.setConstant(-10.0);
  c.cell.upper_limits.setConstant(10.0);
  c.cell.max_velocities.setConstant(10.0);
  return c;
}

// The rules of the registry that apply in `c`, worked out from the ids and the context alone
// (not from the entries' presence functions).
std::vector<std::string> ApplyingIds(const Context& c) {
  const scene::Scene& scene = *c.loaded.scene;
  const bool stitching = scene.head.IsStitching();
  std::vector<std::string> out;
  for (const RuleEntry& e : RuleRegistry()) {
    const std::string id = e.id;
    const bool stitch_only = StartsWith(id, "needle.") || StartsWith(id, "stitch.") ||
                             id == "program.empty" || id == "program.stitch_count";
    if (stitch_only && !stitching) continue;
    if (StartsWith(id, "afp.") && stitching) continue;
    if (id == "stitch.width" && c.process->needles.size() < 2) continue;
    if (id == "program.stitch_count" && !c.declared) continue;
    if (id == "dyn.tracking" && !c.cell.dynamic) continue;
    if (id == "constraint.crossing" && scene.constraints.empty()) continue;
    out.push_back(id);
  }
  return out;
}

std::vector<std::string> IdsOf(const std::vector<std::unique_ptr<Rule>>& rules) {
  std::vector<std::string> out;
  for (const auto& r : rules) out.push_back(r->Summary().id);
  return out;
}

std::vector<std::string> IdsOf(const std::vector<SkippedRule>& skipped) {
  std::vector<std::string> out;
  for (const auto& s : skipped) out.push_back(s.id);
  return out;
}

// The made and the skipped rules merged back into registry order.
std::vector<std::string> InRegistryOrder(const std::vector<std::string>& made,
                                         const std::vector<std::string>& skipped) {
  std::vector<std::string> out;
  std::size_t m = 0, s = 0;
  for (const RuleEntry& e : RuleRegistry()) {
    if (m < made.size() && made[m] == e.id) out.push_back(made[m++]);
    if (s < skipped.size() && skipped[s] == e.id) out.push_back(skipped[s++]);
  }
  // Anything left over was out of order or unknown: keep it so the comparison fails.
  out.insert(out.end(), made.begin() + static_cast<long>(m), made.end());
  out.insert(out.end(), skipped.begin() + static_cast<long>(s), skipped.end());
  return out;
}

TEST(RuleRegistry, MadeAndSkippedRulesAreTheApplyingOnesOnceEachInEveryContext) {
  int contexts = 0;
  for (const char* scene : {"flat_straight", "rs566_stringer_seam", "afp_panel"}) {
    Context c = MakeContext(scene);
    ASSERT_NE(c.loaded.scene, nullptr);
    const auto constraints = c.loaded.scene->constraints;
    const auto inertial = c.loaded.scene->head.inertial;
    for (int bits = 0; bits < 128; ++bits) {
      c.cell.timed = bits & 1;
      c.cell.collision_checked = bits & 2;
      c.cell.dynamic = bits & 4;
      c.cell.payload_rated_kg = bits & 8 ? 20.0 : 0.0;
      c.loaded.scene->head.inertial =
          bits & 16 ? std::optional<scene::HeadInertial>(FiveKilograms()) : std::nullopt;
      c.loaded.scene->constraints = bits & 32 ? constraints : decltype(constraints){};
      c.declared = bits & 64 ? std::optional<long>(12) : std::nullopt;
      const RuleContext ctx = c.Rules();
      const auto rules = MakeRules(ctx);
      const auto skipped = SkippedRules(ctx);
      const std::vector<std::string> made = IdsOf(rules), left_out = IdsOf(skipped);
      EXPECT_EQ(InRegistryOrder(made, left_out), ApplyingIds(c)) << scene << " context " << bits;
      // Each made rule carries its entry's family.
      for (const auto& rule : rules) {
        for (const RuleEntry& e : RuleRegistry()) {
          if (rule->Summary().id == e.id) {
            EXPECT_EQ(rule->CloseUp(), e.close_up) << e.id;
          }
        }
      }
      // Skipped for the reasons the reports give.
      for (const SkippedRule& s : skipped) {
        if (StartsWith(s.id, "collision.")) {
          EXPECT_FALSE(c.cell.collision_checked);
          EXPECT_EQ(s.reason, "--no-collision");
        } else if (s.id == "afp.min_tow_length") {
          EXPECT_EQ(s.reason,
                    "no minimum tow length given (limits: afp.min_tow_length: {min_mm: ...}, or "
                    "the head's cut_to_roller_mm)");
        } else if (s.id == "afp.restart_distance") {
          EXPECT_EQ(s.reason,
                    "no minimum restart distance given (limits: afp.restart_distance: {min_mm: "
                    "...}, or the head's min_restart_mm)");
        } else if (s.id == "afp.stagger") {
          EXPECT_TRUE(c.loaded.scene->laminates.empty());
          EXPECT_EQ(s.reason, "no laminate in the scene (laminates:)");
        } else if (s.id == "kin.acceleration" || s.id == "kin.torque") {
          EXPECT_FALSE(c.cell.timed);
          EXPECT_EQ(s.reason, "the trace has no timed trajectory");
        } else {
          EXPECT_EQ(s.id, "kin.payload");
          EXPECT_EQ(s.reason, (bits & 16) ? "the cell model gives no load diagram"
                                          : "the head spec gives no mass (`inertial:`)");
        }
      }
      ++contexts;
    }
    c.loaded.scene->constraints = constraints;
    c.loaded.scene->head.inertial = inertial;
  }
  EXPECT_EQ(contexts, 3 * 128);
}

TEST(RuleRegistry, TwoContextsListedByHand) {
  // A two-needle stitching head, untimed, no collision world, no load data, no constraints.
  Context stitch = MakeContext("flat_straight");
  ASSERT_EQ(stitch.process->needles.size(), 2u);
  stitch.loaded.scene->head.inertial.reset();
  const RuleContext sctx = stitch.Rules();
  EXPECT_EQ(IdsOf(MakeRules(sctx)),
            (std::vector<std::string>{
                "needle.rotation_in_preform", "needle.side_force", "needle.walk", "stitch.length",
                "stitch.width", "stitch.standoff", "stitch.normality", "kin.reach",
                "kin.joint_limit", "kin.singularity", "kin.config_flip", "kin.joint_speed",
                "program.sync", "program.empty", "program.line_sampling"}));
  const std::vector<SkippedRule> skipped = SkippedRules(sctx);
  EXPECT_EQ(IdsOf(skipped),
            (std::vector<std::string>{"kin.acceleration", "kin.torque", "kin.payload",
                                      "collision.head_mold", "collision.robot_cell",
                                      "collision.clearance"}));
  // An AFP head, timed, with a collision world, a head mass and a load diagram.
  Context afp = MakeContext("afp_panel");
  afp.cell.timed = true;
  afp.cell.collision_checked = true;
  afp.cell.payload_rated_kg = 20.0;
  afp.loaded.scene->head.inertial = FiveKilograms();
  afp.declared = 40;  // no program.stitch_count for a head that does not stitch
  // The head states its cutter-to-roller and restart distances: both rules run, after
  // afp.coverage.
  EXPECT_EQ(IdsOf(MakeRules(afp.Rules())), (std::vector<std::string>{"afp.steering_radius",
                                                                     "afp.gap",
                                                                     "afp.overlap",
                                                                     "afp.compaction",
                                                                     "afp.coverage",
                                                                     "afp.min_tow_length",
                                                                     "afp.restart_distance",
                                                                     "afp.fiber_angle",
                                                                     "kin.reach",
                                                                     "kin.joint_limit",
                                                                     "kin.singularity",
                                                                     "kin.config_flip",
                                                                     "kin.joint_speed",
                                                                     "kin.acceleration",
                                                                     "kin.torque",
                                                                     "kin.payload",
                                                                     "program.sync",
                                                                     "program.line_sampling",
                                                                     "collision.head_mold",
                                                                     "collision.robot_cell",
                                                                     "collision.clearance"}));
  // A head without them: skipped.
  afp.loaded.scene->head.afp.cut_to_roller_mm.reset();
  afp.loaded.scene->head.afp.min_restart_mm.reset();
  const RuleContext actx = afp.Rules();
  EXPECT_EQ(IdsOf(MakeRules(actx)),
            (std::vector<std::string>{
                "afp.steering_radius", "afp.gap", "afp.overlap", "afp.compaction", "afp.coverage",
                "afp.fiber_angle", "kin.reach", "kin.joint_limit", "kin.singularity",
                "kin.config_flip", "kin.joint_speed", "kin.acceleration", "kin.torque",
                "kin.payload", "program.sync", "program.line_sampling", "collision.head_mold",
                "collision.robot_cell", "collision.clearance"}));
  EXPECT_EQ(
      IdsOf(SkippedRules(actx)),
      (std::vector<std::string>{"afp.min_tow_length", "afp.restart_distance", "afp.stagger"}));
  // With a minimum tow length and restart distance given in the scene, they run again.
  afp.loaded.scene->limits.Set(scene::LimitKey::kAfpMinTowLengthMm, 100.0);
  afp.loaded.scene->limits.Set(scene::LimitKey::kAfpRestartDistanceMm, 80.0);
  const std::vector<std::string> with_minimum = IdsOf(MakeRules(afp.Rules()));
  ASSERT_GE(with_minimum.size(), 8u);
  EXPECT_EQ(with_minimum[4], "afp.coverage");
  EXPECT_EQ(with_minimum[5], "afp.min_tow_length");
  EXPECT_EQ(with_minimum[6], "afp.restart_distance");
  EXPECT_EQ(with_minimum[7], "afp.fiber_angle");
  EXPECT_EQ(IdsOf(SkippedRules(afp.Rules())), (std::vector<std::string>{"afp.stagger"}));
  // With a laminate, afp.stagger runs after afp.fiber_angle.
  afp.loaded.scene->laminates.emplace_back();
  const std::vector<std::string> with_laminate = IdsOf(MakeRules(afp.Rules()));
  ASSERT_GE(with_laminate.size(), 9u);
  EXPECT_EQ(with_laminate[8], "afp.stagger");
  EXPECT_TRUE(SkippedRules(afp.Rules()).empty());
}

}  // namespace
}  // namespace stitchsim::verify
