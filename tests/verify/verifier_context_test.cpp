// The verifier over hand-made traces, linking verify alone (no simulator): its rules keep
// references into the verifier's own copy of the RuleContext, so a context passed as a
// temporary is fine (it was a dangling reference before: the sanitizer build caught it).
#include <gtest/gtest.h>

#include <filesystem>

#include "stitchsim/scene/scene.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::verify {
namespace {

std::unique_ptr<scene::Scene> LoadScene(const std::string& name) {
  DiagnosticSink sink;
  auto s = scene::LoadScene(
      std::filesystem::path(STITCHSIM_SOURCE_DIR) / "scenes" / (name + ".yaml"), sink);
  EXPECT_NE(s, nullptr);
  return s;
}

// A needle window in which the head yaws 0.01 rad: side force on the insertion needle.
void YawingWindow(Verifier& v) {
  for (int i = 0; i <= 10; ++i) {
    trace::TraceSample s;
    s.source_line = 42;
    s.stitch = 1;
    s.drive_advancing = true;
    s.needles_in = true;
    s.event = i == 0 ? trace::SampleEvent::kNeedleEntry
                     : (i == 10 ? trace::SampleEvent::kNeedleExit : trace::SampleEvent::kNone);
    s.tool_part.linear() =
        Eigen::AngleAxisd(0.01 * i / 10, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    v.OnSample(s);
  }
}

const RuleSummary* RuleOf(const Report& r, const std::string& id) {
  for (const auto& s : r.rules) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

TEST(VerifierContext, AVerifierMadeFromATemporaryContextRuns) {
  const auto scene = LoadScene("flat_straight");
  ASSERT_TRUE(scene);
  const process::ProcessModel model = process::MakeProcessModel(*scene, 5.0);
  trace::CellDescription cell;
  cell.lower_limits.setConstant(-3.0);
  cell.upper_limits.setConstant(3.0);
  cell.max_velocities.setConstant(1.0);
  Verifier v(RuleContext{scene.get(), &cell, &model}, false);
  // Overwrite the stack where the temporary lived before the rules read their context.
  volatile char scrub[256];
  for (auto& c : scrub) c = static_cast<char>(0xff);
  YawingWindow(v);
  Report r;
  v.Finish(r);
  const RuleSummary* side = RuleOf(r, "needle.side_force");
  ASSERT_NE(side, nullptr);
  EXPECT_EQ(side->checked, static_cast<long>(model.needles.size()));
  EXPECT_GT(*side->worst_value, 0.0);
  // No collision check in the trace: the collision rules are listed as skipped; no timed
  // trajectory in it either (kin.acceleration, kin.torque), nor a load diagram (kin.payload).
  EXPECT_EQ(RuleOf(r, "collision.head_mold"), nullptr);
  EXPECT_EQ(r.skipped.size(), 6u);
}

// The collision rules read the trace: a contact written into a sample is a finding naming the
// bodies from the trace's body table.
TEST(VerifierContext, CollisionRulesReadContactsFromTheTrace) {
  const auto scene = LoadScene("flat_straight");
  ASSERT_TRUE(scene);
  const process::ProcessModel model = process::MakeProcessModel(*scene, 5.0);
  trace::CellDescription cell;
  cell.upper_limits.setConstant(3.0);
  cell.lower_limits.setConstant(-3.0);
  cell.max_velocities.setConstant(1.0);
  cell.collision_checked = true;
  cell.bodies = {"head:body", "rail", "link_3"};
  Verifier v(RuleContext{scene.get(), &cell, &model}, false);
  trace::TraceSample s;
  s.source_line = 9;
  s.has_joints = true;
  s.collision.checked = true;
  s.collision.min_clearance_m = 0.004;
  s.collision.clearance_body_a = 2;
  s.collision.clearance_body_b = 1;
  v.OnSample(s);
  s.source_line = 10;
  s.collision.contacts.push_back({trace::ContactClass::kRobotCell, 0, 1, 0.002, true, {1, 0, 0}});
  v.OnSample(s);
  Report r;
  v.Finish(r);
  const RuleSummary* cell_rule = RuleOf(r, "collision.robot_cell");
  ASSERT_NE(cell_rule, nullptr);
  ASSERT_EQ(cell_rule->errors, 1);
  EXPECT_EQ(cell_rule->findings.front().line, 10);
  EXPECT_EQ(cell_rule->findings.front().subject, "head:body|rail");
  const RuleSummary* clearance = RuleOf(r, "collision.clearance");
  ASSERT_NE(clearance, nullptr);
  ASSERT_EQ(clearance->warnings, 1);
  EXPECT_EQ(clearance->findings.front().line, 9);
  EXPECT_EQ(clearance->findings.front().subject, "link_3|rail");
  // A hand-made trace: no timed trajectory, no load diagram in its cell description.
  ASSERT_EQ(r.skipped.size(), 3u);
  EXPECT_EQ(r.skipped[0].id, "kin.acceleration");
  EXPECT_EQ(r.skipped[1].id, "kin.torque");
  EXPECT_EQ(r.skipped[2].id, "kin.payload");
}

}  // namespace
}  // namespace stitchsim::verify
