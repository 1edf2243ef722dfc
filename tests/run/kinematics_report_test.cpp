// `fk` / `ik` as data (run/kinematics_report.h): the IK of the tool pose FK reports for a set
// of joints finds those joints again (a second route through the cell: OPW against the URDF
// chain), and a joint past its limit is named in the limits table.
#include "stitchsim/run/kinematics_report.h"

#include <gtest/gtest.h>

#include <vector>

namespace stitchsim::run {
namespace {

LoadedScene Scene(const char* name) {
  DiagnosticSink sink;
  std::optional<LoadedScene> ls =
      LoadScene(std::string(STITCHSIM_SOURCE_DIR) + "/scenes/" + name, {}, sink);
  EXPECT_TRUE(ls.has_value());
  return std::move(*ls);
}

TEST(KinematicsReport, InverseKinematicsOfTheForwardPoseFindsTheJointsAgain) {
  const LoadedScene ls = Scene("flat_straight.yaml");
  const std::vector<double> joints = {1200, 10, -20, 30, 5, 40, 10, 0};
  const KinematicsReport fk = ForwardKinematics(ls, joints);
  EXPECT_TRUE(fk.json["within_limits"].get<bool>());
  const auto& tool = fk.json["tool_in_part"];
  std::vector<double> pose;
  for (int i = 0; i < 3; ++i) pose.push_back(tool["xyz_mm"][i].get<double>());
  for (int i = 0; i < 3; ++i) pose.push_back(tool["abc_deg"][i].get<double>());
  const KinematicsReport ik = InverseKinematics(ls, pose, joints[0], joints[7]);
  ASSERT_TRUE(ik.reached) << ik.json.dump(2);
  EXPECT_LT(ik.json["fk_check"]["position_error_mm"].get<double>(), 1e-6);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    EXPECT_NEAR(ik.json["joints"][j].get<double>(), joints[j], 1e-6) << "joint " << j;
  }
}

TEST(KinematicsReport, AJointPastItsLimitIsNamedAndAFarPoseIsUnreachable) {
  const LoadedScene ls = Scene("flat_straight.yaml");
  const KinematicsReport fk = ForwardKinematics(ls, {0, 0, 0, 0, 0, 400, 0, 0});
  EXPECT_FALSE(fk.json["within_limits"].get<bool>());
  int outside = 0;
  for (const auto& j : fk.json["joint_limits"]) outside += j["within_limits"].get<bool>() ? 0 : 1;
  EXPECT_EQ(outside, 1);
  EXPECT_EQ(fk.json["joint_limits"][5]["name"], "a5");
  const KinematicsReport ik = InverseKinematics(ls, {99000, 50, 20, 0, 0, 30}, std::nullopt, 0);
  EXPECT_FALSE(ik.reached);
  EXPECT_TRUE(ik.json["joints"].is_null());
}

}  // namespace
}  // namespace stitchsim::run
