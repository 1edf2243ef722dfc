// The run model made from a bundled scene (what it holds, beside what the scene and robot say)
// and a run's data made from it (its own working states, the options pointed at them).
#include "stitchsim/run/run_model.h"

#include <gtest/gtest.h>

#include "run_test_support.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::run {
namespace {

using testing::Bundled;

TEST(RunModel, HoldsTheCellTheRulesAndThePrototypes) {
  LoadedScene loaded = Bundled("flat_straight");
  const scene::Scene* scene = loaded.scene.get();
  DiagnosticSink sink;
  RunOptions options;
  auto model =
      MakeRunModel(std::move(loaded), program::Dialect::Default(), 4.0, 120L, options, sink);
  ASSERT_TRUE(model) << testing::AllDiagnostics(sink);
  EXPECT_EQ(model->loaded.scene.get(), scene);  // moved in, not copied
  // The cell description: the robot's joints in model order, by name, with its limits.
  ASSERT_EQ(model->description.joint_names.size(), static_cast<std::size_t>(sim::kNumJoints));
  for (int j = 0; j < sim::kNumJoints; ++j) {
    EXPECT_EQ(model->description.joint_names[j], std::string(sim::kJointNames[j]));
    EXPECT_EQ(model->description.upper_limits[j], model->loaded.robot->joints()[j].upper);
  }
  EXPECT_TRUE(model->description.timed);
  EXPECT_FALSE(model->description.dynamic);
  ASSERT_TRUE(model->collision);
  EXPECT_TRUE(model->description.collision_checked);
  EXPECT_EQ(model->description.bodies, model->collision->BodyNames());
  ASSERT_TRUE(model->mujoco);
  // The rules' context points into the model; the process model is at the length given.
  const verify::RuleContext ctx = model->Rules();
  EXPECT_EQ(ctx.scene, scene);
  EXPECT_EQ(ctx.cell, &model->description);
  EXPECT_EQ(ctx.process, model->process.get());
  EXPECT_EQ(ctx.declared_stitches, std::optional<long>(120));
  EXPECT_DOUBLE_EQ(model->stitch_length_mm, 4.0);
  // The executor's options: the scene's, with no working state of their own.
  EXPECT_EQ(model->execute.collision, nullptr);
  EXPECT_EQ(model->execute.mujoco, nullptr);
  EXPECT_EQ(model->timing.settle_time_s, model->execute.settle_time_s);
}

TEST(RunModel, NoCollisionLeavesTheWorldOutAndTheCollisionRulesUnchecked) {
  DiagnosticSink sink;
  RunOptions options;
  options.no_collision = true;
  auto model = MakeRunModel(Bundled("flat_straight"), program::Dialect::Default(), 5.0,
                            std::nullopt, options, sink);
  ASSERT_TRUE(model) << testing::AllDiagnostics(sink);
  EXPECT_EQ(model->collision, nullptr);
  EXPECT_FALSE(model->description.collision_checked);
  EXPECT_TRUE(model->description.bodies.empty());
  EXPECT_EQ(model->Rules().declared_stitches, std::nullopt);
  const RunData data = MakeRunData(*model);
  EXPECT_EQ(data.collision, nullptr);
  EXPECT_EQ(data.execute.collision, nullptr);
}

TEST(RunData, HasItsOwnWorkingStatesAndPointsTheOptionsAtThem) {
  DiagnosticSink sink;
  RunOptions options;
  options.dynamics = true;
  auto model = MakeRunModel(Bundled("flat_straight"), program::Dialect::Default(), 5.0,
                            std::nullopt, options, sink);
  ASSERT_TRUE(model) << testing::AllDiagnostics(sink);
  EXPECT_TRUE(model->description.dynamic);
  EXPECT_TRUE(model->execute.solve_every_sample);
  const RunData a = MakeRunData(*model);
  const RunData b = MakeRunData(*model);
  ASSERT_TRUE(a.kinematics && a.timing && a.physics && a.physics_poses && a.collision);
  EXPECT_NE(a.kinematics.get(), model->mujoco.get());
  EXPECT_NE(a.kinematics.get(), b.kinematics.get());
  EXPECT_NE(a.collision.get(), b.collision.get());
  EXPECT_EQ(a.execute.mujoco, a.kinematics.get());
  EXPECT_EQ(a.execute.collision, a.collision.get());
  EXPECT_EQ(a.execute.stitch_rate_per_min, model->execute.stitch_rate_per_min);
}

}  // namespace
}  // namespace stitchsim::run
