// Loading the cell URDF: the derived geometry, hand-checked poses, and bad URDFs that must give
// diagnostics with stable codes, never a crash.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sim_test_support.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"
#include "stitchsim/scene/head_spec.h"

namespace stitchsim::sim {
namespace {

using testing::CellTest;
using testing::CellUrdfPath;
using testing::FormatAll;
using testing::PositionError;
using testing::RotationError;

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

TEST_F(sim_robot_model, DynamicsReadBack) {
  EXPECT_DOUBLE_EQ(model().efforts()(kRailX), 7400.0);
  EXPECT_DOUBLE_EQ(model().efforts()(kA2), 78100.0);
  EXPECT_DOUBLE_EQ(model().joint(kA6).effort, 1040.0);
  EXPECT_DOUBLE_EQ(model().dampings()(kA4), 42.6);
  EXPECT_DOUBLE_EQ(model().joint(kRotator).damping, 260.0);
  EXPECT_DOUBLE_EQ(model().max_accelerations()(kRailX), 1.0);
  for (int i = 0; i < kNumJoints; ++i) {
    SCOPED_TRACE(model().joint(i).name);
    const double v = model().max_velocities()(i);
    // The documented rules: arm axes reach top speed in 0.5 s, the rotator 30 deg/s in 1 s;
    // damping * top speed = 5 % of the effort (3 significant digits, so within 1 %).
    if (i >= kA1 && i <= kA6) {
      EXPECT_NEAR(model().max_accelerations()(i), v / 0.5, 1e-12);
    }
    if (i == kRotator) {
      EXPECT_NEAR(model().max_accelerations()(i), 30.0 * kPi / 180.0, 1e-12);
    }
    EXPECT_GT(model().efforts()(i), 0.0);
    EXPECT_NEAR(model().dampings()(i) * v, 0.05 * model().efforts()(i),
                0.01 * 0.05 * model().efforts()(i));
  }
  const PayloadRating& rating = model().payload_rating();
  EXPECT_DOUBLE_EQ(rating.mass_kg, 420.0);
  EXPECT_DOUBLE_EQ(rating.lz_m, 0.35);
  EXPECT_DOUBLE_EQ(rating.lxy_m, 0.15);

  const LinkInfo& link_1 = model().links()[static_cast<std::size_t>(model().LinkIndex("link_1"))];
  ASSERT_TRUE(link_1.inertial.has_value());
  EXPECT_DOUBLE_EQ(link_1.inertial->mass_kg, 1000.0);
  EXPECT_LT((link_1.inertial->com_m - Eigen::Vector3d(0.135, 0, -0.216)).norm(), 1e-15);
  Eigen::Matrix3d expected;
  expected << 104.4, 0, -17.78, 0, 214.5, 0, -17.78, 0, 182.5;
  EXPECT_LT((link_1.inertial->inertia_kg_m2 - expected).norm(), 1e-12);
  double arm_kg = 0.0;
  for (const char* name :
       {"base_link", "link_1", "link_2", "link_3", "link_4", "link_5", "link_6"}) {
    const LinkInfo& link = model().links()[static_cast<std::size_t>(model().LinkIndex(name))];
    ASSERT_TRUE(link.inertial.has_value()) << name;
    arm_kg += link.inertial->mass_kg;
  }
  EXPECT_NEAR(arm_kg, 2515.0, 1e-9);  // the KR 420 R3330 class: about 2.5 t
  for (const char* name : {"carriage", "rotator"}) {
    EXPECT_TRUE(model().links()[static_cast<std::size_t>(model().LinkIndex(name))].inertial)
        << name;
  }
  for (const char* name : {"world", "rail", "flange", "table", "rotator_base"}) {
    EXPECT_FALSE(model().links()[static_cast<std::size_t>(model().LinkIndex(name))].inertial)
        << name;
  }
}

// Every bundled head lies within the arm's load diagram: mass, moment about a5 (the CoM's
// distance from the a5 axis, c4 + Lz along the flange axis) and about a6 (its distance from
// the flange axis), each against the rated payload at its rated distances.
TEST_F(sim_robot_model, BundledHeadsWithinLoadDiagram) {
  const PayloadRating& rated = model().payload_rating();
  const double c4 = model().opw().c4_m;  // a5 axis to flange
  const double rated_a5 = rated.mass_kg * std::hypot(c4 + rated.lz_m, rated.lxy_m);
  const double rated_a6 = rated.mass_kg * rated.lxy_m;  // both per g
  for (const char* name : {"rs535", "rs566", "afp"}) {
    SCOPED_TRACE(name);
    DiagnosticSink sink;
    const std::optional<scene::HeadSpec> head =
        scene::LoadHeadSpec(scene::ResolveHeadFile(name, {}), sink);
    ASSERT_TRUE(head && head->inertial) << FormatAll(sink);
    const scene::HeadInertial& in = *head->inertial;
    const double lz = in.com_m.z();
    const double lxy = in.com_m.head<2>().norm();
    EXPECT_LE(in.mass_kg, rated.mass_kg);
    EXPECT_LE(in.mass_kg * std::hypot(c4 + lz, lxy), rated_a5);
    EXPECT_LE(in.mass_kg * lxy, rated_a6);
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

// The cell text with every dynamics field removed: what URDFs written before them look like.
std::string WithoutDynamics(std::string text) {
  const auto erase_all = [&text](const std::string& open, const std::string& close) {
    for (std::size_t at = text.find(open); at != std::string::npos; at = text.find(open, at)) {
      const std::size_t end = text.find(close, at + open.size());
      EXPECT_NE(end, std::string::npos) << open;
      if (end == std::string::npos) return;
      text.erase(at, end + close.size() - at);
    }
  };
  erase_all("<inertial>\n", "</inertial>");  // not the mentions in comments
  erase_all("<dynamics damping=\"", "/>");
  erase_all(" acceleration=\"", "\"");
  erase_all("<payload_rating ", "/>");
  for (std::size_t at = text.find("effort=\""); at != std::string::npos;
       at = text.find("effort=\"", at + 1)) {
    text.replace(at, text.find('"', at + 8) + 1 - at, "effort=\"0\"");
  }
  return text;
}

TEST(sim_robot_model_bad, UrdfWithoutDynamicsStillLoads) {
  DiagnosticSink sink;
  const std::string text = WithoutDynamics(CellText());
  ASSERT_EQ(text.find("<inertial>\n"), std::string::npos);
  ASSERT_EQ(text.find("damping=\""), std::string::npos);
  const std::optional<RobotModel> model = ParseRobotModel(text, "old.urdf", sink);
  ASSERT_TRUE(model.has_value()) << FormatAll(sink);
  EXPECT_TRUE(sink.Diagnostics().empty()) << FormatAll(sink);
  EXPECT_TRUE(model->efforts().isZero());
  EXPECT_TRUE(model->max_accelerations().isZero());
  EXPECT_TRUE(model->dampings().isZero());
  EXPECT_EQ(model->payload_rating().mass_kg, 0.0);
  for (const LinkInfo& link : model->links()) EXPECT_FALSE(link.inertial.has_value()) << link.name;
}

TEST(sim_robot_model_bad, InertialOriginTurnsTheInertiaIntoLinkAxes) {
  DiagnosticSink sink;
  // The link_2 inertia given in axes turned 90 deg about z: ixx and iyy swap in the link frame.
  const std::string text =
      Replace(CellText(),
              "<origin xyz=\"0.867 0 0\" rpy=\"0 0 0\"/>\n      <mass value=\"500\"/>\n"
              "      <inertia ixx=\"17.64\" iyy=\"102.1\"",
              "<origin xyz=\"0.867 0 0\" rpy=\"0 0 1.5707963267948966\"/>\n      <mass "
              "value=\"500\"/>\n      <inertia ixx=\"102.1\" iyy=\"17.64\"");
  const std::optional<RobotModel> model = ParseRobotModel(text, "cell.urdf", sink);
  ASSERT_TRUE(model.has_value()) << FormatAll(sink);
  const LinkInfo& link = model->links()[static_cast<std::size_t>(model->LinkIndex("link_2"))];
  ASSERT_TRUE(link.inertial.has_value());
  EXPECT_NEAR(link.inertial->inertia_kg_m2(0, 0), 17.64, 1e-12);
  EXPECT_NEAR(link.inertial->inertia_kg_m2(1, 1), 102.1, 1e-12);
  EXPECT_NEAR(link.inertial->inertia_kg_m2(0, 1), 0.0, 1e-12);
  EXPECT_LT((link.inertial->com_m - Eigen::Vector3d(0.867, 0, 0)).norm(), 1e-15);
}

struct BadValue {
  std::string from;
  std::string to;
  std::string code;
  std::string element;  // the diagnostic points at this element's line
  std::string says;     // the message contains this
};

TEST(sim_robot_model_bad, BadDynamicsValuesGiveTheirCodes) {
  const std::string a2 = "<joint name=\"a2\"";
  const std::string link_3 = "<link name=\"link_3\">";
  const std::string rating = "<payload_rating ";
  const std::vector<BadValue> cases = {
      {"effort=\"78100\"", "effort=\"-1\"", "urdf-bad-limits", a2, ""},
      {"<dynamics damping=\"2980\"/>", "<dynamics damping=\"-5\"/>", "urdf-bad-limits", a2, ""},
      {"acceleration=\"2.6179938779914944\"", "acceleration=\"-1\"", "urdf-bad-limits", a2, ""},
      {"acceleration=\"2.6179938779914944\"", "acceleration=\"fast\"", "urdf-bad-limits", a2, ""},
      {"acceleration=\"2.6179938779914944\"", "acceleration=\"inf\"", "urdf-bad-limits", a2, ""},
      {"<mass value=\"420\"/>", "<mass value=\"-420\"/>", "urdf-bad-inertial", link_3, ""},
      {"<mass value=\"420\"/>", "<mass value=\"0\"/>", "urdf-bad-inertial", link_3, ""},
      {"ixx=\"13.56\"", "ixx=\"-13.56\"", "urdf-bad-inertial", link_3, "positive definite"},
      {"ixx=\"13.56\" iyy=\"81.89\" izz=\"80.35\" ixy=\"0\" ixz=\"4.928\"",
       "ixx=\"1\" iyy=\"1\" izz=\"3\" ixy=\"0\" ixz=\"0\"", "urdf-bad-inertial", link_3,
       "triangle inequality"},
      {"ixz=\"4.928\"", "ixz=\"60\"", "urdf-bad-inertial", link_3, "positive definite"},
      {"mass_kg=\"420\"", "mass_kg=\"-420\"", "urdf-bad-payload", rating, ""},
      {"mass_kg=\"420\"", "mass_kg=\"0\"", "urdf-bad-payload", rating, ""},
      {" lxy_m=\"0.15\"", "", "urdf-bad-payload", rating, ""},
      {"lz_m=\"0.35\"", "lz_m=\"nan\"", "urdf-bad-payload", rating, ""},
      {"lz_m=\"0.35\"", "lz_m=\"0.35\" lx_m=\"1\"", "urdf-bad-payload", rating, ""},
      {"<link name=\"world\"/>", "<link name=\"world\"/>\n  <payload_rating mass_kg=\"1\"/>",
       "urdf-bad-payload", "<payload_rating mass_kg=\"1\"/>", ""},
  };
  for (const BadValue& c : cases) {
    SCOPED_TRACE(c.to);
    DiagnosticSink sink;
    const std::string text = Replace(CellText(), c.from, c.to);
    EXPECT_FALSE(ParseRobotModel(text, "cell.urdf", sink).has_value());
    const Diagnostic* d = Find(sink, c.code);
    ASSERT_NE(d, nullptr) << FormatAll(sink);
    EXPECT_EQ(d->location.line, LineOf(text, c.element)) << FormatAll(sink);
    EXPECT_NE(d->message.find(c.says), std::string::npos) << d->message;
    EXPECT_EQ(sink.ErrorCount(), 1u) << FormatAll(sink);
  }
}

TEST(sim_robot_model_bad, CellTextParsesClean) {
  // The rewrite helpers above start from text that is itself valid.
  DiagnosticSink sink;
  EXPECT_TRUE(ParseRobotModel(CellText(), "cell.urdf", sink).has_value());
  EXPECT_TRUE(sink.Diagnostics().empty()) << FormatAll(sink);
}

}  // namespace
}  // namespace stitchsim::sim
