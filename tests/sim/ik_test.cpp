// Inverse kinematics: FK of every IK solution equals the target, the generating joints come
// back, and each failure mode gives its status. Plus the rail policy and the tool helper.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::sim {
namespace {

using testing::CellTest;
using testing::PositionError;
using testing::RandomJoints;
using testing::RotationError;

constexpr double kPoseToleranceM = 1e-9;  // 1e-6 mm
constexpr double kPoseToleranceRad = 1e-9;
constexpr double kJointToleranceRad = 1e-8;  // away from singularities

class sim_ik : public CellTest {
 protected:
  // sin of the OPW wrist angle and the elbow angle (t3 + atan2(a2, c3)) of joints q.
  double SinWrist(const JointVector& q) const {
    const OpwGeometry& g = model().opw();
    return std::sin(g.sign[4] * q(kA5) + g.offset_rad[4]);
  }
  double SinElbow(const JointVector& q) const {
    const OpwGeometry& g = model().opw();
    return std::sin(g.sign[2] * q(kA3) + g.offset_rad[2] + std::atan2(g.a2_m, g.c3_m));
  }

  JointVector Joints(double rail_m, double a1_deg, double a2_deg, double a3_deg, double a4_deg,
                     double a5_deg, double a6_deg) const {
    JointVector q;
    q << rail_m, a1_deg * kDeg, a2_deg * kDeg, a3_deg * kDeg, a4_deg * kDeg, a5_deg * kDeg,
        a6_deg * kDeg, 0.0;
    return q;
  }

  void ExpectReaches(const JointVector& q, const Eigen::Isometry3d& target) const {
    const Eigen::Isometry3d reached = FlangePose(model(), q);
    EXPECT_LT(PositionError(reached, target), kPoseToleranceM);
    EXPECT_LT(RotationError(reached, target), kPoseToleranceRad);
  }
};

TEST_F(sim_ik, TenThousandRandomPosesRoundTrip) {
  std::mt19937_64 rng(7);
  const IkOptions options;
  const double wrist_margin = std::sin(2.0 * options.wrist_singularity_rad);
  int accepted = 0;
  int solutions_checked = 0;
  double worst_m = 0.0;
  double worst_rad = 0.0;
  double worst_joint_rad = 0.0;
  while (accepted < 10000) {
    const JointVector q = RandomJoints(model(), rng);
    if (std::abs(SinWrist(q)) < wrist_margin || std::abs(SinElbow(q)) < 1e-3) continue;
    const Eigen::Isometry3d target = FlangePose(model(), q);
    const ArmIkSolutions all = AllArmIkSolutions(model(), target, q(kRailX));
    if (all.wrist_centre_radius_m < 2.0 * options.shoulder_singularity_m) continue;
    ++accepted;
    ASSERT_GE(all.count, 4) << "sample " << accepted;

    // Every returned solution reaches the target.
    int nearest = -1;
    double nearest_distance = 1e300;
    for (int i = 0; i < all.count; ++i) {
      const ArmIkSolution& s = all.solution[static_cast<std::size_t>(i)];
      JointVector qi = q;
      qi.segment<kNumArmJoints>(kA1) = s.joints_rad;
      const Eigen::Isometry3d reached = FlangePose(model(), qi);
      const double error_m = PositionError(reached, target);
      const double error_rad = RotationError(reached, target);
      worst_m = std::max(worst_m, error_m);
      worst_rad = std::max(worst_rad, error_rad);
      ASSERT_LT(error_m, kPoseToleranceM) << "sample " << accepted << " solution " << i;
      ASSERT_LT(error_rad, kPoseToleranceRad) << "sample " << accepted << " solution " << i;
      EXPECT_EQ(ArmConfigurationOf(model(), qi), s.configuration);
      ++solutions_checked;
      double distance = 0.0;
      for (int j = 0; j < kNumArmJoints; ++j) {
        distance += std::abs(std::remainder(s.joints_rad(j) - q(kA1 + j), 2.0 * kPi));
      }
      if (distance < nearest_distance) {
        nearest_distance = distance;
        nearest = i;
      }
    }
    // The solution nearest the generating joints is the generating joints (mod 2 pi).
    EXPECT_LT(nearest_distance, kJointToleranceRad) << "sample " << accepted;
    EXPECT_EQ(all.solution[static_cast<std::size_t>(nearest)].configuration,
              ArmConfigurationOf(model(), q));

    // SolveIk from the generating joints gives them back exactly, 2 pi branch included.
    const IkResult result = SolveIk(model(), target, q(kRailX), &q, options);
    ASSERT_EQ(result.status, IkStatus::kOk) << result.reason << " sample " << accepted;
    const double joint_error = (result.joints - q).cwiseAbs().maxCoeff();
    worst_joint_rad = std::max(worst_joint_rad, joint_error);
    ASSERT_LT(joint_error, kJointToleranceRad) << "sample " << accepted;
    ExpectReaches(result.joints, target);
  }
  RecordProperty("solutions_checked", solutions_checked);
  RecordProperty("worst_position_error_m", testing::Sci(worst_m));
  RecordProperty("worst_rotation_error_rad", testing::Sci(worst_rad));
  RecordProperty("worst_joint_error_rad", testing::Sci(worst_joint_rad));
}

TEST_F(sim_ik, WithoutPreviousPicksAValidSolutionNearTheReference) {
  std::mt19937_64 rng(11);
  int ok = 0;
  for (int n = 0; n < 2000; ++n) {
    const JointVector q = RandomJoints(model(), rng);
    const Eigen::Isometry3d target = FlangePose(model(), q);
    const IkResult result = SolveIk(model(), target, q(kRailX), nullptr);
    ASSERT_NE(result.status, IkStatus::kUnreachable);
    ASSERT_NE(result.status, IkStatus::kJointLimit) << result.reason;
    ASSERT_NE(result.status, IkStatus::kConfigFlip) << "no previous, no flip";
    ExpectReaches(result.joints, target);
    EXPECT_TRUE((result.joints.array() >= model().lower_limits().array() - 1e-9).all());
    EXPECT_TRUE((result.joints.array() <= model().upper_limits().array() + 1e-9).all());
    EXPECT_EQ(result.configuration, ArmConfigurationOf(model(), result.joints));
    ok += result.ok() ? 1 : 0;
  }
  EXPECT_GT(ok, 1900);
}

TEST_F(sim_ik, EquivalentsBeyondPiAreKept) {
  // a1 near its +185 deg end, a4 and a6 past a full turn: previous keeps those branches.
  const JointVector q = Joints(4.0, 182.0, -70.0, 100.0, 300.0, 50.0, -320.0);
  const Eigen::Isometry3d target = FlangePose(model(), q);
  const IkResult result = SolveIk(model(), target, q(kRailX), &q);
  ASSERT_EQ(result.status, IkStatus::kOk) << result.reason;
  EXPECT_LT((result.joints - q).cwiseAbs().maxCoeff(), kJointToleranceRad);
  // A previous one turn away pulls a6 to the other branch.
  JointVector previous = q;
  previous(kA6) += 2.0 * kPi;
  const IkResult other = SolveIk(model(), target, q(kRailX), &previous);
  ASSERT_EQ(other.status, IkStatus::kOk) << other.reason;
  EXPECT_NEAR(other.joints(kA6), q(kA6) + 2.0 * kPi, kJointToleranceRad);
}

TEST_F(sim_ik, UnreachableTarget) {
  const JointVector q = Joints(5.0, 0, -90, 90, 0, 45, 0);
  Eigen::Isometry3d target = FlangePose(model(), q);
  target.translation().y() += 4.0;  // far beyond the 2.8 m arm
  const IkResult result = SolveIk(model(), target, q(kRailX), &q);
  EXPECT_EQ(result.status, IkStatus::kUnreachable);
  EXPECT_FALSE(result.reason.empty());
  EXPECT_EQ(AllArmIkSolutions(model(), target, q(kRailX)).count, 0);
  EXPECT_EQ(result.joints, q) << "joints stay at previous";
}

TEST_F(sim_ik, TargetOnlyReachableBeyondALimit) {
  // a2 = +30 deg is past its +20 deg limit; the other branches break a2 or cannot reach.
  const JointVector q = Joints(5.0, 17, 30, 60, 11, 40, 6);
  const Eigen::Isometry3d target = FlangePose(model(), q);
  ASSERT_GT(AllArmIkSolutions(model(), target, q(kRailX)).count, 0);
  const IkResult result = SolveIk(model(), target, q(kRailX), nullptr);
  EXPECT_EQ(result.status, IkStatus::kJointLimit) << result.reason;
  EXPECT_NE(result.reason.find("a2"), std::string::npos) << result.reason;
  ExpectReaches(result.joints, target);  // reported solution is exact, just out of limits

  // Within limits (a2 = +15 deg) it solves.
  const JointVector inside = Joints(5.0, 17, 15, 60, 11, 40, 6);
  EXPECT_EQ(SolveIk(model(), FlangePose(model(), inside), 5.0, &inside).status, IkStatus::kOk);
}

TEST_F(sim_ik, RailOutsideItsLimits) {
  const JointVector q = Joints(5.0, 0, -90, 90, 0, 45, 0);
  const IkResult result = SolveIk(model(), FlangePose(model(), q), 11.5, &q);
  EXPECT_EQ(result.status, IkStatus::kJointLimit);
  EXPECT_NE(result.reason.find("rail_x"), std::string::npos) << result.reason;
}

TEST_F(sim_ik, WristSingularity) {
  const JointVector q = Joints(5.0, 10, -80, 95, 30, 0.2, -20);
  const Eigen::Isometry3d target = FlangePose(model(), q);
  const IkResult result = SolveIk(model(), target, q(kRailX), &q);
  EXPECT_EQ(result.status, IkStatus::kWristSingularity) << result.reason;
  ExpectReaches(result.joints, target);
  // Exactly straight: a4 + a6 is all that is fixed; a4 stays at the previous value.
  const JointVector straight = Joints(5.0, 10, -80, 95, 30, 0, -20);
  const IkResult exact = SolveIk(model(), FlangePose(model(), straight), 5.0, &straight);
  EXPECT_EQ(exact.status, IkStatus::kWristSingularity);
  EXPECT_LT((exact.joints - straight).cwiseAbs().maxCoeff(), kJointToleranceRad);
  // The threshold is a parameter.
  IkOptions tight;
  tight.wrist_singularity_rad = 0.1 * kDeg;
  EXPECT_EQ(SolveIk(model(), target, q(kRailX), &q, tight).status, IkStatus::kOk);
}

TEST_F(sim_ik, ShoulderSingularity) {
  // Upper arm vertical, forearm bent back so the wrist centre sits on the a1 axis.
  const OpwGeometry& g = model().opw();
  const double k = std::hypot(g.a2_m, g.c3_m);
  const double t3 = -std::asin(g.a1_m / k) - std::atan2(g.a2_m, g.c3_m);
  JointVector q = Joints(5.0, 0, -90, 0, 20, 60, 0);
  q(kA3) = g.sign[2] * (t3 - g.offset_rad[2]);
  const Eigen::Isometry3d target = FlangePose(model(), q);
  EXPECT_LT(AllArmIkSolutions(model(), target, 5.0).wrist_centre_radius_m, 1e-9);
  const IkResult result = SolveIk(model(), target, q(kRailX), &q);
  EXPECT_EQ(result.status, IkStatus::kShoulderSingularity) << result.reason;
  ExpectReaches(result.joints, target);
  EXPECT_NEAR(result.joints(kA1), q(kA1), 1e-9) << "a1 held at previous on the axis";
}

TEST_F(sim_ik, ConfigurationFlip) {
  // Previous: elbow down. Target: a3 = 130 deg, whose elbow-down twin needs a3 < -100 deg and
  // whose back-shoulder solutions break a2: only elbow up remains.
  const JointVector previous = Joints(5.0, 0, -40, -40, 0, 45, 0);
  ASSERT_EQ(ArmConfigurationOf(model(), previous),
            (ArmConfiguration{Shoulder::kFront, Elbow::kDown, Wrist::kNoFlip}));
  const JointVector q = Joints(5.0, 0, -60, 130, 0, 45, 0);
  const Eigen::Isometry3d target = FlangePose(model(), q);
  const IkResult result = SolveIk(model(), target, q(kRailX), &previous);
  EXPECT_EQ(result.status, IkStatus::kConfigFlip) << result.reason;
  EXPECT_EQ(result.configuration.elbow, Elbow::kUp);
  EXPECT_NE(result.reason.find("front/down/noflip -> front/up/"), std::string::npos)
      << result.reason;
  ExpectReaches(result.joints, target);
  // From an elbow-up previous the same target is no flip.
  EXPECT_EQ(SolveIk(model(), target, q(kRailX), &q).status, IkStatus::kOk);
}

TEST_F(sim_ik, CrossingStraightWristFlipsIt) {
  // a5 from +3 to -3 deg with a4, a6 held: the nearest solution is on the flip branch.
  const JointVector previous = Joints(5.0, 5, -80, 90, 40, 3, -30);
  const JointVector q = Joints(5.0, 5, -80, 90, 40, -3, -30);
  const IkResult result = SolveIk(model(), FlangePose(model(), q), 5.0, &previous);
  ASSERT_EQ(result.status, IkStatus::kConfigFlip) << result.reason;
  EXPECT_EQ(result.configuration.wrist, Wrist::kFlip);
  EXPECT_LT((result.joints - q).cwiseAbs().maxCoeff(), kJointToleranceRad);
}

TEST_F(sim_ik, ToolTargetToFlangeTarget) {
  // A head 0.45 m long, tool point on its axis, tool z pointing back at the head.
  Eigen::Isometry3d flange_to_tool = Eigen::Isometry3d::Identity();
  flange_to_tool.translation() = Eigen::Vector3d(0.02, 0.0, 0.45);
  flange_to_tool.linear() = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  // Tool point on the table, tool z up (surface normal towards the head).
  const int table = model().LinkIndex("table");
  ASSERT_GE(table, 0);
  Eigen::Isometry3d tool_target = LinkPose(model(), JointVector::Zero(), table);
  tool_target.translation() += Eigen::Vector3d(0.3, -0.2, 0.05);
  tool_target.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();

  const RailPlacement rail = RailForTarget(model(), tool_target);
  EXPECT_FALSE(rail.clamped);
  const Eigen::Isometry3d flange_target = FlangeTargetForTool(tool_target, flange_to_tool);
  const IkResult result = SolveIk(model(), flange_target, rail.rail_m, nullptr);
  ASSERT_TRUE(result.ok()) << ToString(result.status) << ": " << result.reason;
  const Eigen::Isometry3d tool = FlangePose(model(), result.joints) * flange_to_tool;
  EXPECT_LT(PositionError(tool, tool_target), kPoseToleranceM);
  EXPECT_LT(RotationError(tool, tool_target), kPoseToleranceRad);
}

TEST_F(sim_ik, RailPolicy) {
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  target.translation() = Eigen::Vector3d(5.0, 2.6, 1.0);
  // Default: arm base (a1 axis) directly opposite the target.
  RailPlacement placement = RailForTarget(model(), target);
  EXPECT_NEAR(ArmBasePose(model(), placement.rail_m).translation().x(), 5.0, 1e-12);
  EXPECT_NEAR(placement.rail_m, 4.3, 1e-12);
  EXPECT_FALSE(placement.clamped);
  EXPECT_FALSE(placement.programmed);

  // A preferred offset along the rail.
  RailPolicy behind;
  behind.base_offset_along_rail_m = -1.0;
  EXPECT_NEAR(ArmBasePose(model(), RailForTarget(model(), target, behind).rail_m).translation().x(),
              4.0, 1e-12);

  // Clamped at both rail ends.
  target.translation().x() = 20.0;
  placement = RailForTarget(model(), target);
  EXPECT_DOUBLE_EQ(placement.rail_m, model().upper_limits()(kRailX));
  EXPECT_TRUE(placement.clamped);
  target.translation().x() = -3.0;
  placement = RailForTarget(model(), target);
  EXPECT_DOUBLE_EQ(placement.rail_m, model().lower_limits()(kRailX));
  EXPECT_TRUE(placement.clamped);

  // A programmed rail value (E word) is honoured as given, even outside the limits.
  RailPolicy programmed;
  programmed.programmed_rail_m = 7.25;
  placement = RailForTarget(model(), target, programmed);
  EXPECT_DOUBLE_EQ(placement.rail_m, 7.25);
  EXPECT_TRUE(placement.programmed);
  EXPECT_FALSE(placement.clamped);
  programmed.programmed_rail_m = 12.0;
  EXPECT_DOUBLE_EQ(RailForTarget(model(), target, programmed).rail_m, 12.0);
}

}  // namespace
}  // namespace stitchsim::sim
