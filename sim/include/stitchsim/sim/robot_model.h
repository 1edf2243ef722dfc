#pragma once
// The cell's robot model: an immutable description loaded from the URDF (the single source of
// kinematic truth). Metres and radians throughout. Algorithms that use it are free functions
// in kinematics.h taking (const RobotModel&, ...).

#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/trace/joints.h"

namespace stitchsim::sim {

// The joint vector and its layout are trace types (the trace carries joints); sim's names for
// them.
using trace::ArmJointVector;
using trace::JointIndex;
using trace::JointVector;
using trace::kNumArmJoints;
using trace::kNumJoints;
using enum trace::JointIndex;

/// URDF names of the movable joints, in model order.
inline constexpr std::array<std::string_view, kNumJoints> kJointNames = {
    "rail_x", "a1", "a2", "a3", "a4", "a5", "a6", "rotator"};

/// URDF names of the links the kinematics needs besides the joints' links.
inline constexpr std::string_view kFlangeLinkName = "flange";
inline constexpr std::string_view kRotatorLinkName = "rotator";

enum class JointType { kPrismatic, kRevolute };

/// One movable joint as the URDF gives it.
struct JointInfo {
  std::string name;
  JointType type = JointType::kRevolute;
  std::string parent_link;
  std::string child_link;
  int child_link_index = -1;                                 // index into RobotModel::links()
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // parent link -> joint frame, q = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit vector in the joint (= child) frame
  double lower = 0.0;             // position limit: m (prismatic) or rad (revolute)
  double upper = 0.0;             // position limit: m (prismatic) or rad (revolute)
  double max_velocity = 0.0;      // URDF <limit velocity>: m/s or rad/s
  double effort = 0.0;            ///< URDF <limit effort>: N (prismatic) or N m; 0 = not given
  double max_acceleration = 0.0;  ///< <limit acceleration> (stitchsim extension): m/s^2 or
                                  ///< rad/s^2; 0 = not given
  double damping = 0.0;           ///< URDF <dynamics damping>: N s/m or N m s/rad; 0 = none
  int line = 0;                   // 1-based line of the <joint> element in the URDF; 0 if unknown
};

/// A link's mass properties (URDF <inertial>), link frame.
struct LinkInertial {
  double mass_kg = 0.0;
  Eigen::Vector3d com_m = Eigen::Vector3d::Zero();          ///< centre of mass, link frame
  Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();  ///< about the CoM, link axes
};

/// The arm's load diagram (URDF extension element <payload_rating>); mass 0 = not given.
struct PayloadRating {
  double mass_kg = 0.0;  ///< rated payload
  double lz_m = 0.0;     ///< CoM distance along the flange z at the rated payload
  double lxy_m = 0.0;    ///< CoM distance from the flange axis at the rated payload
};

/// One link. The world pose of a link is parent pose * origin * motion(q[joint]).
struct LinkInfo {
  std::string name;
  int parent_link = -1;      // index into RobotModel::links(); -1 for the root
  std::string parent_joint;  // URDF name of the joint to the parent; empty for the root
  int joint = -1;            // JointIndex of that joint when movable; -1 when fixed or root
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // parent link -> this link, q = 0
  std::optional<LinkInertial> inertial;  ///< URDF <inertial>; absent when the URDF gives none
};

/// Ortho-parallel arm geometry with a spherical wrist (Brandstoetter, Angerer, Hofbaur 2014),
/// derived from the URDF at load time. In the OPW frame the zero pose stands the arm upright:
/// a2 and a3 turn about +y, a1, a4 and a6 about +z, a5 about +y, and
///   wrist centre (frame 1) = (a1 + c2 sin t2 + a2 cos t23 + c3 sin t23, b,
///                             c1 + c2 cos t2 - a2 sin t23 + c3 cos t23),
///   flange = wrist centre + c4 * (flange z).
/// OPW angle i relates to URDF joint a(i+1) by  theta_i = sign[i] * q_i + offset_rad[i].
struct OpwGeometry {
  double a1_m = 0.0;  // a2 axis offset from the a1 axis, along base x
  double a2_m = 0.0;  // wrist-centre offset from the forearm line, along forearm x
  double b_m = 0.0;   // lateral (base y) offset of the arm plane
  double c1_m = 0.0;  // a2 axis height above the OPW base origin
  double c2_m = 0.0;  // a2 axis to a3 axis (upper arm)
  double c3_m = 0.0;  // a3 axis to wrist centre, along the forearm
  double c4_m = 0.0;  // wrist centre to flange origin
  std::array<double, kNumArmJoints> sign = {1, 1, 1, 1, 1, 1};        // +1 or -1
  std::array<double, kNumArmJoints> offset_rad = {0, 0, 0, 0, 0, 0};  // OPW angle at q = 0
  /// Pose of the OPW base frame (origin on the a1 axis, z along it) in the a1 parent link.
  Eigen::Isometry3d mount_to_base = Eigen::Isometry3d::Identity();
  /// Orientation of the URDF flange frame in the OPW flange frame (constant).
  Eigen::Matrix3d opw_flange_to_flange = Eigen::Matrix3d::Identity();
};

/// Immutable robot model: every link, the 8 movable joints in model order and the derived arm
/// geometry. Built only by LoadRobotModel / ParseRobotModel, which validate it.
class RobotModel {
 public:
  const std::string& name() const { return name_; }
  const std::string& source_file() const { return source_file_; }

  /// Every link, parents before children (index 0 is the root, normally "world").
  const std::vector<LinkInfo>& links() const { return links_; }
  /// The movable joints in model order (see JointIndex).
  const std::array<JointInfo, kNumJoints>& joints() const { return joints_; }
  const JointInfo& joint(int index) const { return joints_[static_cast<std::size_t>(index)]; }

  /// Index of a link by URDF name, or -1.
  int LinkIndex(std::string_view link_name) const;
  /// Link indices from the root's child down to `link` (inclusive); the chain FK walks.
  const std::vector<int>& ChainTo(int link) const {
    return chains_[static_cast<std::size_t>(link)];
  }

  int flange_link() const { return flange_link_; }        // the "flange" link (z out of face)
  int rotator_link() const { return rotator_link_; }      // the "rotator" link (turntable top)
  int arm_mount_link() const { return arm_mount_link_; }  // parent link of a1 (base_link)

  const OpwGeometry& opw() const { return opw_; }

  /// Limits and speeds in model order: m, m/s for the rail; rad, rad/s otherwise.
  const JointVector& lower_limits() const { return lower_; }
  const JointVector& upper_limits() const { return upper_; }
  const JointVector& max_velocities() const { return max_velocity_; }
  /// Effort limits in model order: N for the rail, N m otherwise; 0 = not given.
  const JointVector& efforts() const { return effort_; }
  /// Acceleration limits in model order: m/s^2 for the rail, rad/s^2 otherwise; 0 = not given.
  const JointVector& max_accelerations() const { return max_acceleration_; }
  /// Viscous damping in model order: N s/m for the rail, N m s/rad otherwise; 0 = none.
  const JointVector& dampings() const { return damping_; }
  /// The arm's rated payload and load-diagram distances; mass 0 = not given.
  const PayloadRating& payload_rating() const { return payload_rating_; }

 private:
  friend class RobotModelBuilder;
  RobotModel() = default;

  std::string name_;
  std::string source_file_;
  std::vector<LinkInfo> links_;
  std::vector<std::vector<int>> chains_;
  std::array<JointInfo, kNumJoints> joints_;
  int flange_link_ = -1;
  int rotator_link_ = -1;
  int arm_mount_link_ = -1;
  OpwGeometry opw_;
  JointVector lower_ = JointVector::Zero();
  JointVector upper_ = JointVector::Zero();
  JointVector max_velocity_ = JointVector::Zero();
  JointVector effort_ = JointVector::Zero();
  JointVector max_acceleration_ = JointVector::Zero();
  JointVector damping_ = JointVector::Zero();
  PayloadRating payload_rating_;
};

/// Loads and validates a URDF file. Problems are reported to `sink` with stable codes
/// (urdf-missing-file, urdf-parse-error, urdf-missing-joint, urdf-missing-link,
/// urdf-wrong-joint-type, urdf-unsupported-joint, urdf-bad-limits, urdf-bad-axis,
/// urdf-bad-chain, urdf-not-opw, urdf-bad-inertial, urdf-bad-payload) and give nullopt; never
/// throws on bad input.
std::optional<RobotModel> LoadRobotModel(const std::filesystem::path& path, DiagnosticSink& sink);

/// As LoadRobotModel, from URDF text; `file_label` names it in diagnostics.
std::optional<RobotModel> ParseRobotModel(std::string_view urdf_text, std::string_view file_label,
                                          DiagnosticSink& sink);

}  // namespace stitchsim::sim
