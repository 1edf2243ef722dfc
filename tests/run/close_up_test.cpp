// The close-up of a rule with a planted worst sample: kin.joint_limit with joint a5 beyond its
// limit frames the link a5 moves (named from MuJoCo's own joint-to-body table, the second
// route), the model posed at the sample's joints; a rule without a close-up family plans none.
#include "stitchsim/run/close_up.h"

#include <gtest/gtest.h>

#include "picture_test_support.h"
#include "stitchsim/render/scene_model.h"

namespace stitchsim::run {
namespace {

struct Model {
  render::MjModelPtr model;
  render::MjDataPtr data;
};

Model SceneModel(const LoadedScene& ls) {
  DiagnosticSink sink;
  Model m;
  m.model = render::LoadSceneModel(*ls.scene, sink);
  EXPECT_FALSE(sink.HasErrors());
  if (m.model) m.data.reset(mj_makeData(m.model.get()));
  return m;
}

CloseUpContext ContextOf(const testing::PlantedRun& run, const Model& m) {
  return {&run.ls,       run.process.get(), &run.cell,
          m.model.get(), m.data.get(),      &run.verifier->StitchMarks()};
}

TEST(CloseUp, JointLimitFramesTheLinkTheJointMoves) {
  auto run = testing::PlantJointLimit("flat_straight");
  ASSERT_NE(run, nullptr);
  const verify::Rule* rule = testing::RuleOf(*run, "kin.joint_limit");
  ASSERT_NE(rule, nullptr);
  ASSERT_EQ(rule->Summary().errors, 1);
  EXPECT_EQ(rule->CloseUp(), verify::CloseUpFamily::kKinematics);
  const verify::Finding* focus = FocusFinding(*rule);
  ASSERT_NE(focus, nullptr);
  EXPECT_EQ(focus->line, testing::kPlantedLine);
  EXPECT_EQ(focus->subject, "a5");
  EXPECT_NEAR(focus->value, testing::kPlantedExcessDeg, 1e-9);

  Model m = SceneModel(run->ls);
  ASSERT_NE(m.model, nullptr);
  const CloseUpContext ctx = ContextOf(*run, m);
  std::optional<CloseUpPlan> plan;
  std::string error;
  ASSERT_TRUE(PlanCloseUp(ctx, *rule, plan, error)) << error;
  ASSERT_TRUE(plan.has_value());
  EXPECT_EQ(plan->family, verify::CloseUpFamily::kKinematics);
  EXPECT_EQ(plan->joints, run->planted.joints);

  // Second route: the body MuJoCo's model hangs joint a5 on, and that body's geoms.
  const int joint = mj_name2id(m.model.get(), mjOBJ_JOINT, "a5");
  ASSERT_GE(joint, 0);
  const int body = m.model->jnt_bodyid[joint];
  const std::string body_name = mj_id2name(m.model.get(), mjOBJ_BODY, body);
  ASSERT_FALSE(plan->subjects.empty());
  EXPECT_EQ(plan->subjects.front().name, body_name);
  EXPECT_EQ(plan->subjects.front().geoms, render::GeomsOfBody(*m.model, body));
  EXPECT_FALSE(plan->subjects.front().geoms.empty());
  ASSERT_FALSE(plan->legend.empty());
  EXPECT_EQ(plan->legend.front().label, body_name + " (moved by joint a5)");
  // The model posed at the sample: a5's angle in the data is the planted one.
  EXPECT_DOUBLE_EQ(m.data->qpos[m.model->jnt_qposadr[joint]], run->planted.joints[trace::kA5]);

  // The shot shows the link: some of its pixels are the nearest thing in the picture.
  Shot shot;
  ASSERT_TRUE(ShootCloseUp(m.model.get(), m.data.get(), *plan, 160, 120, shot, error)) << error;
  ASSERT_EQ(shot.pixels.size(), plan->subjects.size());
  EXPECT_EQ(shot.pixels.front().name, body_name);
  EXPECT_GT(shot.pixels.front().visible, 0);
  EXPECT_LE(shot.pixels.front().visible, shot.pixels.front().alone);
  EXPECT_EQ(shot.image.width, 160);
  EXPECT_EQ(shot.image.height, 120);
}

TEST(CloseUp, ARuleWithoutAFamilyPlansNone) {
  auto run = testing::PlantJointLimit("flat_straight");
  ASSERT_NE(run, nullptr);
  // program.empty: the planted run makes no stitch, an error with no close-up.
  const verify::Rule* rule = testing::RuleOf(*run, "program.empty");
  ASSERT_NE(rule, nullptr);
  ASSERT_GT(rule->Summary().errors, 0);
  EXPECT_EQ(rule->CloseUp(), verify::CloseUpFamily::kNone);
  Model m = SceneModel(run->ls);
  ASSERT_NE(m.model, nullptr);
  const CloseUpContext ctx = ContextOf(*run, m);
  std::optional<CloseUpPlan> plan = CloseUpPlan{};
  std::string error;
  ASSERT_TRUE(PlanCloseUp(ctx, *rule, plan, error)) << error;
  EXPECT_FALSE(plan.has_value());
}

}  // namespace
}  // namespace stitchsim::run
