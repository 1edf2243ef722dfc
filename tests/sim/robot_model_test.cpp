// Loading the cell URDF: the derived geometry, hand-checked poses, and bad URDFs that must give
// diagnostics with stable codes, never a crash.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sim_test_support.h"
#include "stitchsim/common/files.h"

namespace stitchsim::sim {
namespace {

using testing::CellTest;
using testing::CellUrdfPath;
using testing::FormatAll;
using testing::PositionError;
using testing::RotationError;

constexpr double kPi = std::numbers::pi;

class sim_robot_model : public CellTest {};

TEST_F(sim_robot_model, JointsInModelOrderWithLimitsFromUrdf) {
  ASSERT_EQ(model().joints().size(), 8u);
  for (int i = 0; i < kNumJoints; ++i) {
    EXPECT_EQ(model().joint(i).name, kJointNames[static_cast<std::size_t>(i)]);
  }
  EXPECT_EQ(model().joint(kRailX).type, JointType::kPrismatic);
  EXPECT_DOUBLE_EQ(model().upper_limits()(kRailX), 11.1);
  EXPECT_DOUBLE_EQ(model().lower_limits()(kA2), -130.0 * kPi / 180.0);
  EXPECT_DOUBLE_EQ(model().upper_limits()(kA3), 144.0 * kPi / 180.0);
  EXPECT_DOUBLE_EQ(model().max_velocities()(kA6), 110.0 * kPi / 180.0);
  EXPECT_TRUE(model().joint(kA1).axis.isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(model().joint(kA4).axis.isApprox(-Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(model().joint(kA6).axis.isApprox(-Eigen::Vector3d::UnitX()));
  EXPECT_EQ(model().links()[0].name, "world");
  EXPECT_GE(model().LinkIndex("table"), 0);
  EXPECT_EQ(model().links()[static_cast<std::size_t>(model().arm_mount_link())].name, "base_link");
  EXPECT_EQ(model().LinkIndex("no_such_link"), -1);
}

TEST_F(sim_robot_model, DerivedOpwGeometryIsTheKr420) {
  const OpwGeometry& g = model().opw();
  EXPECT_NEAR(g.a1_m, 0.5, 1e-12);
  EXPECT_NEAR(g.a2_m, 0.055, 1e-12);  // wrist 0.055 below the forearm line when stretched
  EXPECT_NEAR(g.b_m, 0.0, 1e-12);
  EXPECT_NEAR(g.c1_m, 1.045, 1e-12);
  EXPECT_NEAR(g.c2_m, 1.3, 1e-12);
  EXPECT_NEAR(g.c3_m, 1.525, 1e-12);
  EXPECT_NEAR(g.c4_m, 0.29, 1e-12);
  const std::array<double, 6> sign = {-1, 1, 1, -1, 1, -1};
  const std::array<double, 6> offset = {0, kPi / 2, 0, 0, 0, 0};
  for (int i = 0; i < kNumArmJoints; ++i) {
    EXPECT_EQ(g.sign[static_cast<std::size_t>(i)], sign[static_cast<std::size_t>(i)]) << i;
    EXPECT_NEAR(g.offset_rad[static_cast<std::size_t>(i)], offset[static_cast<std::size_t>(i)],
                1e-12)
        << i;
  }
  EXPECT_TRUE(g.opw_flange_to_flange.isApprox(Eigen::Matrix3d::Identity(), 1e-12));
}

TEST_F(sim_robot_model, ZeroPoseByHand) {
  // Zero pose: arm stretched along base x, which the carriage turns to world +y.
  const Eigen::Isometry3d flange = FlangePose(model(), JointVector::Zero());
  EXPECT_LT((flange.translation() -
             Eigen::Vector3d(0.7, 0.5 + 1.3 + 1.525 + 0.29, 0.3 + 0.55 + 1.045 - 0.055))
                .norm(),
            1e-12);
  EXPECT_LT((flange.linear().col(2) - Eigen::Vector3d::UnitY()).norm(), 1e-12);  // z forward

  // Home (a2 = -90, a3 = +90 deg): upper arm up, forearm forward and level, the wrist centre
  // 0.055 below the forearm line.
  JointVector home = JointVector::Zero();
  home(kRailX) = 2.0;
  home(kA2) = -kPi / 2;
  home(kA3) = kPi / 2;
  const Eigen::Isometry3d at_home = FlangePose(model(), home);
  EXPECT_LT((at_home.translation() -
             Eigen::Vector3d(2.7, 0.5 + 1.525 + 0.29, 0.3 + 0.55 + 1.045 + 1.3 - 0.055))
                .norm(),
            1e-12);
  EXPECT_EQ(ArmConfigurationOf(model(), home),
            (ArmConfiguration{Shoulder::kFront, Elbow::kUp, Wrist::kNoFlip}));

  // a1 is about -z: a positive a1 turns the arm clockwise seen from above (+y towards +x).
  JointVector turned = home;
  turned(kA1) = 0.3;
  EXPECT_GT(FlangePose(model(), turned).translation().x(), at_home.translation().x());

  // The rotator turns about +z at (8.5, 2.6, 0.75).
  JointVector q = JointVector::Zero();
  q(kRotator) = kPi / 2;
  const Eigen::Isometry3d rotator = RotatorPose(model(), q);
  EXPECT_LT((rotator.translation() - Eigen::Vector3d(8.5, 2.6, 0.75)).norm(), 1e-12);
  EXPECT_LT((rotator.linear().col(0) - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  Eigen::Isometry3d mark = Eigen::Isometry3d::Identity();
  mark.translation() = Eigen::Vector3d(1.1, 0, 0);
  EXPECT_LT(
      (RotatorCarriedPose(model(), kPi / 2, mark).translation() - Eigen::Vector3d(8.5, 3.7, 0.75))
          .norm(),
      1e-12);
}

TEST_F(sim_robot_model, ArmBaseSitsOnTheA1Axis) {
  for (double rail : {0.0, 3.3, 11.1}) {
    const Eigen::Isometry3d base = ArmBasePose(model(), rail);
    EXPECT_LT((base.translation() - Eigen::Vector3d(0.7 + rail, 0, 0.85)).norm(), 1e-12);
    EXPECT_LT((base.linear().col(2) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
    EXPECT_LT((base.linear().col(0) - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  }
}

// --- Bad URDFs ------------------------------------------------------------------------------

std::string CellText() {
  const std::optional<std::string> text = ReadFile(CellUrdfPath());
  EXPECT_TRUE(text.has_value());
  return text.value_or("");
}

// Replaces the one occurrence of `from` in `text`.
std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "ambiguous: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

int LineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

bool HasCode(const DiagnosticSink& sink, std::string_view code) {
  return std::any_of(sink.Diagnostics().begin(), sink.Diagnostics().end(),
                     [&](const Diagnostic& d) { return d.code == code; });
}

const Diagnostic* Find(const DiagnosticSink& sink, std::string_view code) {
  for (const Diagnostic& d : sink.Diagnostics()) {
    if (d.code == code) return &d;
  }
  return nullptr;
}

TEST(sim_robot_model_bad, MissingFile) {
  DiagnosticSink sink;
  EXPECT_FALSE(LoadRobotModel("/no/such/dir/cell.urdf", sink).has_value());
  ASSERT_EQ(sink.ErrorCount(), 1u) << FormatAll(sink);
  EXPECT_EQ(sink.Diagnostics()[0].code, "urdf-missing-file");
  EXPECT_EQ(FormatDiagnostic(sink.Diagnostics()[0]).rfind("/no/such/dir/cell.urdf: error[", 0), 0u);
}

TEST(sim_robot_model_bad, MalformedXmlPointsAtTheLine) {
  DiagnosticSink sink;
  const std::string text = "<robot name=\"x\">\n  <link name=\"a\">\n</robot>\n";
  EXPECT_FALSE(ParseRobotModel(text, "bad.urdf", sink).has_value());
  const Diagnostic* d = Find(sink, "urdf-parse-error");
  ASSERT_NE(d, nullptr) << FormatAll(sink);
  EXPECT_EQ(d->location.file, "bad.urdf");
  EXPECT_GT(d->location.line, 0);
}

TEST(sim_robot_model_bad, EmptyAndNonRobotText) {
  for (const std::string text : {"", "not xml at all", "<mujoco model=\"x\"/>"}) {
    DiagnosticSink sink;
    EXPECT_FALSE(ParseRobotModel(text, "t.urdf", sink).has_value()) << text;
    EXPECT_TRUE(HasCode(sink, "urdf-parse-error")) << text << "\n" << FormatAll(sink);
  }
}

TEST(sim_robot_model_bad, UrdfdomRejectionIsCapturedNotPrinted) {
  DiagnosticSink sink;
  const std::string text =
      Replace(CellText(), "<child link=\"link_3\"/>", "<child link=\"no_such_link\"/>");
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(printed.empty()) << printed;
  EXPECT_TRUE(HasCode(sink, "urdf-parse-error")) << FormatAll(sink);
}

TEST(sim_robot_model_bad, MissingJoint) {
  DiagnosticSink sink;
  const std::string text = Replace(CellText(), "<joint name=\"rotator\" type=\"revolute\">",
                                   "<joint name=\"turntable\" type=\"revolute\">");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  const Diagnostic* d = Find(sink, "urdf-missing-joint");
  ASSERT_NE(d, nullptr) << FormatAll(sink);
  EXPECT_NE(d->message.find("rotator"), std::string::npos);
  EXPECT_TRUE(HasCode(sink, "urdf-unsupported-joint")) << FormatAll(sink);
}

TEST(sim_robot_model_bad, MissingFlangeLink) {
  DiagnosticSink sink;
  std::string text = Replace(CellText(), "<link name=\"flange\"/>", "<link name=\"tool0\"/>");
  text = Replace(text, "<child link=\"flange\"/>", "<child link=\"tool0\"/>");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  EXPECT_TRUE(HasCode(sink, "urdf-missing-link")) << FormatAll(sink);
}

TEST(sim_robot_model_bad, BadLimitsPointAtTheJoint) {
  DiagnosticSink sink;
  const std::string text =
      Replace(CellText(), "lower=\"-2.2689280275926285\" upper=\"0.3490658503988659\"",
              "lower=\"0.5\" upper=\"0.3490658503988659\"");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  const Diagnostic* d = Find(sink, "urdf-bad-limits");
  ASSERT_NE(d, nullptr) << FormatAll(sink);
  EXPECT_EQ(d->location.line, LineOf(text, "<joint name=\"a2\""));
  EXPECT_NE(FormatDiagnostic(*d).find("cell.urdf:" + std::to_string(d->location.line) +
                                      ": error[urdf-bad-limits]"),
            std::string::npos);
}

TEST(sim_robot_model_bad, ZeroVelocityLimit) {
  DiagnosticSink sink;
  const std::string text = Replace(CellText(), "velocity=\"1.0\"", "velocity=\"0\"");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  EXPECT_TRUE(HasCode(sink, "urdf-bad-limits")) << FormatAll(sink);
}

TEST(sim_robot_model_bad, WrongJointType) {
  DiagnosticSink sink;
  const std::string text = Replace(CellText(), "<joint name=\"rail_x\" type=\"prismatic\">",
                                   "<joint name=\"rail_x\" type=\"revolute\">");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  const Diagnostic* d = Find(sink, "urdf-wrong-joint-type");
  ASSERT_NE(d, nullptr) << FormatAll(sink);
  EXPECT_EQ(d->location.line, LineOf(text, "<joint name=\"rail_x\""));
}

TEST(sim_robot_model_bad, ArmJointsOutOfOrder) {
  DiagnosticSink sink;
  // a3 hung from link_1 instead of link_2: still a tree, no longer a serial arm.
  const std::string text =
      Replace(CellText(), "<parent link=\"link_2\"/>", "<parent link=\"link_1\"/>");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  EXPECT_TRUE(HasCode(sink, "urdf-bad-chain")) << FormatAll(sink);
}

TEST(sim_robot_model_bad, WristNotSpherical) {
  DiagnosticSink sink;
  // a5 lifted off the a4 axis: the wrist no longer has a centre.
  const std::string text =
      Replace(CellText(), "<child link=\"link_5\"/>\n    <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>",
              "<child link=\"link_5\"/>\n    <origin xyz=\"0 0 0.05\" rpy=\"0 0 0\"/>");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  const Diagnostic* d = Find(sink, "urdf-not-opw");
  ASSERT_NE(d, nullptr) << FormatAll(sink);
  EXPECT_EQ(d->location.line, LineOf(text, "<joint name=\"a5\""));
}

TEST(sim_robot_model_bad, ShoulderNotOrthoParallel) {
  DiagnosticSink sink;
  const std::string text =
      Replace(CellText(), "<child link=\"link_3\"/>\n    <origin xyz=\"1.3 0 0\" rpy=\"0 0 0\"/>",
              "<child link=\"link_3\"/>\n    <origin xyz=\"1.3 0 0\" rpy=\"0.1 0 0\"/>");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  EXPECT_TRUE(HasCode(sink, "urdf-not-opw")) << FormatAll(sink);
}

TEST(sim_robot_model_bad, ExtraMovableJoint) {
  DiagnosticSink sink;
  const std::string text =
      Replace(CellText(), "<joint name=\"world-table\" type=\"fixed\">",
              "<joint name=\"world-table\" type=\"prismatic\">\n    <axis xyz=\"0 0 1\"/>\n"
              "    <limit lower=\"0\" upper=\"1\" velocity=\"1\" effort=\"0\"/>");
  EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
  EXPECT_TRUE(HasCode(sink, "urdf-unsupported-joint")) << FormatAll(sink);
}

TEST(sim_robot_model_bad, CellTextParsesClean) {
  // The rewrite helpers above start from text that is itself valid.
  DiagnosticSink sink;
  EXPECT_TRUE(ParseRobotModel(CellText(), "cell.urdf", sink).has_value());
  EXPECT_TRUE(sink.Diagnostics().empty()) << FormatAll(sink);
}

}  // namespace
}  // namespace stitchsim::sim
