// The AFP head's off-part axis weights (models/heads/afp.yaml, `sequence.axis_weights`) claim
// to be the reciprocal of each axis's top speed in the cell URDF (docs/sequence.md): checked
// against the URDF as read by the robot model, so editing one without the other fails.
#include <gtest/gtest.h>

#include <cmath>

#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"
#include "stitchsim/scene/head_spec.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::sim {
namespace {

TEST(SequenceWeights, AfpHeadWeightsAreTheReciprocalAxisSpeeds) {
  DiagnosticSink sink;
  const auto head = scene::LoadHeadSpec(scene::ResolveHeadFile("afp", {}), sink);
  ASSERT_TRUE(head.has_value());
  const auto robot = LoadRobotModel(DataDir() / "models" / "isaac_cell.urdf", sink);
  ASSERT_TRUE(robot.has_value());
  ASSERT_EQ(head->sequence.axis_weights.size(), static_cast<std::size_t>(trace::kNumJoints));
  for (int j = 0; j < trace::kNumJoints; ++j) {
    const JointInfo& info = robot->joint(j);
    const auto& w = head->sequence.axis_weights[static_cast<std::size_t>(j)];
    EXPECT_EQ(w.joint, info.name);
    // Speeds in m/s or rad/s; weights per mm or per degree.
    const double per_unit = info.type == JointType::kPrismatic ? info.max_velocity * 1000.0
                                                               : info.max_velocity * 180.0 / kPi;
    EXPECT_NEAR(w.weight * per_unit, 1.0, 1e-5) << info.name;
  }
}

}  // namespace
}  // namespace stitchsim::sim
