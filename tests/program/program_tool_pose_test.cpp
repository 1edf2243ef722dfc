// The machine state -> tool pose conversion: two routes to one answer (the angles read back
// from the pose equal the programme's A B C), the dialect's Euler order, and no pose until
// all six axes are set.

#include <gtest/gtest.h>

#include "program_test_util.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::program {
namespace {

using testing::Describe;

// The state after the last block of `text`.
MachineState StateAfter(std::string_view text, const Dialect& dialect) {
  DiagnosticSink sink;
  const auto blocks = ParseString(text, dialect, "t.nc", sink);
  ModalState modal(dialect, "t.nc", sink);
  for (const Block& block : blocks) modal.Update(block);
  EXPECT_TRUE(sink.Diagnostics().empty()) << Describe(sink);
  return modal.State();
}

TEST(program_tool_pose, PoseReadsBackAsTheProgrammedWords) {
  const MachineState s = StateAfter("G21 G0 X10 Y-20 Z30.5 A12 B-34 C56\n", Dialect::Default());
  const auto pose = ToolPoseOf(s, EulerOrderOf(Dialect::Default()));
  ASSERT_TRUE(pose.has_value());
  EXPECT_TRUE(pose->translation().isApprox(Eigen::Vector3d(10, -20, 30.5)));
  const Eigen::Vector3d abc_deg =
      geom::EulerFromRotation(EulerOrderOf(Dialect::Default()), pose->linear()) * 180.0 / kPi;
  EXPECT_NEAR(abc_deg.x(), 12.0, 1e-9);
  EXPECT_NEAR(abc_deg.y(), -34.0, 1e-9);
  EXPECT_NEAR(abc_deg.z(), 56.0, 1e-9);
  // XYZ fixed axes: R = Rz(C) Ry(B) Rx(A).
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(56 * kPi / 180, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-34 * kPi / 180, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(12 * kPi / 180, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_TRUE(pose->linear().isApprox(expected, 1e-12));
}

TEST(program_tool_pose, FollowsTheDialectsEulerOrder) {
  Dialect zyx = Dialect::Default();
  zyx.euler_order = "ZYX";
  const MachineState s = StateAfter("G21 G0 X0 Y0 Z0 A30 B0 C0\n", zyx);
  const auto pose = ToolPoseOf(s, EulerOrderOf(zyx));
  ASSERT_TRUE(pose.has_value());
  // ZYX: A turns about z.
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(30 * kPi / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(pose->linear().isApprox(expected, 1e-12));
}

TEST(program_tool_pose, NoPoseUntilAllSixAxesAreSet) {
  const MachineState s = StateAfter("G21 G0 X1 Y2 Z3 A0 B0\n", Dialect::Default());
  EXPECT_FALSE(ToolPoseOf(s, EulerOrderOf(Dialect::Default())).has_value());
  EXPECT_FALSE(ToolPoseOf(MachineState{}, EulerOrderOf(Dialect::Default())).has_value());
}

}  // namespace
}  // namespace stitchsim::program
