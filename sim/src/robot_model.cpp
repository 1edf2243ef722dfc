#include "stitchsim/sim/robot_model.h"

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <mutex>
#include <random>
#include <utility>

#include "detail/opw.h"
#include "detail/urdf_dynamics.h"
#include "stitchsim/common/files.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::sim {
namespace {

// Geometric tolerance for the OPW structure checks (metres, or unit-vector components).
constexpr double kGeometryTolerance = 1e-9;
// Largest flange error (metres / radians) the derived OPW geometry may make against the URDF.
constexpr double kOpwVerifyTolerance = 1e-9;

/// Source lines of the elements of a URDF, for diagnostics (urdfdom keeps none).
struct XmlLines {
  int robot = 0;
  std::map<std::string, int, std::less<>> joint;
  std::map<std::string, int, std::less<>> link;
  detail::UrdfExtensions extensions;  // what urdfdom drops
};

/// urdfdom reports through console_bridge; while parsing, collect its messages instead of
/// letting them reach stderr. console_bridge's handler is process-global, hence the lock.
class ConsoleCapture : public console_bridge::OutputHandler {
 public:
  ConsoleCapture() : lock_(Mutex()) { console_bridge::useOutputHandler(this); }
  ~ConsoleCapture() override { console_bridge::restorePreviousOutputHandler(); }
  ConsoleCapture(const ConsoleCapture&) = delete;
  ConsoleCapture& operator=(const ConsoleCapture&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      errors.push_back(text);
    } else if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
      warnings.push_back(text);
    }
  }

  std::vector<std::string> errors;
  std::vector<std::string> warnings;

 private:
  static std::mutex& Mutex() {
    static std::mutex mutex;
    return mutex;
  }
  std::lock_guard<std::mutex> lock_;
};

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return out;
}

int ExpectedJointIndex(std::string_view name) {
  for (int i = 0; i < kNumJoints; ++i) {
    if (kJointNames[static_cast<std::size_t>(i)] == name) return i;
  }
  return -1;
}

std::string_view UrdfTypeName(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    case urdf::Joint::FIXED:
      return "fixed";
    default:
      return "unknown";
  }
}

std::string Num(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace

/// Builds and validates a RobotModel; friend of RobotModel.
class RobotModelBuilder {
 public:
  RobotModelBuilder(std::string_view file_label, DiagnosticSink& sink)
      : file_(file_label), sink_(sink) {}

  std::optional<RobotModel> Build(std::string_view urdf_text) {
    const std::string text(urdf_text);
    if (!ReadLines(text)) return std::nullopt;
    urdf::ModelInterfaceSharedPtr urdf = ParseWithUrdfdom(text);
    if (!urdf) return std::nullopt;

    model_.name_ = urdf->getName();
    model_.source_file_ = file_;
    const std::size_t errors_before = sink_.ErrorCount();
    CollectLinksAndJoints(*urdf);
    if (sink_.ErrorCount() != errors_before) return std::nullopt;
    if (!CheckChains()) return std::nullopt;
    if (!DeriveOpw()) return std::nullopt;
    if (!VerifyOpw()) return std::nullopt;
    return std::move(model_);
  }

 private:
  SourceLocation At(int line) const { return {file_, line, 0}; }
  int JointLine(int index) const { return model_.joints_[static_cast<std::size_t>(index)].line; }
  int LineOfJoint(const std::string& name) const {
    auto it = lines_.joint.find(name);
    return it == lines_.joint.end() ? 0 : it->second;
  }

  bool ReadLines(const std::string& text) {
    TiXmlDocument doc;
    doc.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
    if (doc.Error()) {
      sink_.Error("urdf-parse-error", {file_, doc.ErrorRow(), doc.ErrorCol()},
                  std::string("malformed XML: ") + doc.ErrorDesc());
      return false;
    }
    const TiXmlElement* robot = doc.RootElement();
    if (robot == nullptr || robot->ValueStr() != "robot") {
      sink_.Error("urdf-parse-error", At(robot != nullptr ? robot->Row() : 0),
                  "the root element must be <robot>");
      return false;
    }
    lines_.robot = robot->Row();
    for (const TiXmlElement* e = robot->FirstChildElement(); e != nullptr;
         e = e->NextSiblingElement()) {
      detail::CollectUrdfExtensions(*e, lines_.extensions);
      const char* name = e->Attribute("name");
      if (name == nullptr) continue;
      if (e->ValueStr() == "joint") lines_.joint.emplace(name, e->Row());
      if (e->ValueStr() == "link") lines_.link.emplace(name, e->Row());
    }
    return true;
  }

  urdf::ModelInterfaceSharedPtr ParseWithUrdfdom(const std::string& text) {
    urdf::ModelInterfaceSharedPtr urdf;
    std::vector<std::string> errors;
    std::vector<std::string> warnings;
    {
      ConsoleCapture capture;
      try {
        urdf = urdf::parseURDF(text);
      } catch (const std::exception& e) {
        capture.errors.emplace_back(e.what());
      }
      errors = std::move(capture.errors);
      warnings = std::move(capture.warnings);
    }
    for (const std::string& w : warnings) sink_.Warning("urdf-parser-warning", At(LineOf(w)), w);
    if (urdf) return urdf;
    std::string message = errors.empty() ? "urdfdom rejected the model" : "urdfdom: ";
    for (std::size_t i = 0; i < errors.size(); ++i) message += (i > 0 ? "; " : "") + errors[i];
    sink_.Error("urdf-parse-error", At(errors.empty() ? lines_.robot : LineOf(errors.front())),
                message);
    return nullptr;
  }

  // urdfdom names the offending element as "[name]" in most messages.
  int LineOf(const std::string& message) const {
    const std::size_t open = message.find('[');
    const std::size_t close = message.find(']', open == std::string::npos ? 0 : open);
    if (open == std::string::npos || close == std::string::npos) return lines_.robot;
    const std::string name = message.substr(open + 1, close - open - 1);
    if (auto it = lines_.joint.find(name); it != lines_.joint.end()) return it->second;
    if (auto it = lines_.link.find(name); it != lines_.link.end()) return it->second;
    return lines_.robot;
  }

  void CollectLinksAndJoints(const urdf::ModelInterface& urdf) {
    std::array<bool, kNumJoints> seen{};
    // Breadth first from the root, so parents come before children.
    std::vector<urdf::LinkConstSharedPtr> queue = {urdf.getRoot()};
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const urdf::LinkConstSharedPtr& link = queue[head];
      LinkInfo info;
      info.name = link->name;
      const auto line = lines_.link.find(link->name);
      info.inertial =
          detail::ReadLinkInertial(*link, At(line == lines_.link.end() ? 0 : line->second), sink_);
      if (const urdf::JointConstSharedPtr& joint = link->parent_joint; joint) {
        info.parent_joint = joint->name;
        info.parent_link = model_.LinkIndex(joint->parent_link_name);
        info.origin = ToIsometry(joint->parent_to_joint_origin_transform);
        info.joint = CollectJoint(*joint, static_cast<int>(head), seen);
      }
      model_.links_.push_back(std::move(info));
      for (const urdf::LinkSharedPtr& child : link->child_links) queue.push_back(child);
    }
    for (int i = 0; i < kNumJoints; ++i) {
      if (!seen[static_cast<std::size_t>(i)]) {
        sink_.Error("urdf-missing-joint", At(lines_.robot),
                    "the cell needs a joint named '" +
                        std::string(kJointNames[static_cast<std::size_t>(i)]) + "'");
      }
    }
    model_.payload_rating_ = detail::ReadPayloadRating(lines_.extensions, file_, sink_);
    model_.flange_link_ = RequireLink(kFlangeLinkName);
    model_.rotator_link_ = RequireLink(kRotatorLinkName);
    model_.chains_.resize(model_.links_.size());
    for (std::size_t i = 1; i < model_.links_.size(); ++i) {
      const int parent = model_.links_[i].parent_link;
      if (parent > 0) model_.chains_[i] = model_.chains_[static_cast<std::size_t>(parent)];
      model_.chains_[i].push_back(static_cast<int>(i));
    }
  }

  int RequireLink(std::string_view name) {
    const int index = model_.LinkIndex(name);
    if (index < 0) {
      sink_.Error("urdf-missing-link", At(lines_.robot),
                  "the cell needs a link named '" + std::string(name) + "'");
    }
    return index;
  }

  // Returns the JointIndex of a movable joint, -1 for a fixed one; reports problems.
  int CollectJoint(const urdf::Joint& joint, int child_link, std::array<bool, kNumJoints>& seen) {
    const int line = LineOfJoint(joint.name);
    const int index = ExpectedJointIndex(joint.name);
    if (index < 0) {
      if (joint.type != urdf::Joint::FIXED) {
        sink_.Error("urdf-unsupported-joint", At(line),
                    "joint '" + joint.name + "' is " + std::string(UrdfTypeName(joint.type)) +
                        "; only rail_x, a1..a6 and rotator may move, every other joint is fixed");
      }
      return -1;
    }
    seen[static_cast<std::size_t>(index)] = true;
    const int expected_type = index == kRailX ? urdf::Joint::PRISMATIC : urdf::Joint::REVOLUTE;
    if (joint.type != expected_type) {
      sink_.Error("urdf-wrong-joint-type", At(line),
                  "joint '" + joint.name + "' must be " + std::string(UrdfTypeName(expected_type)) +
                      ", not " + std::string(UrdfTypeName(joint.type)));
      return -1;
    }
    JointInfo& info = model_.joints_[static_cast<std::size_t>(index)];
    info.name = joint.name;
    info.type = index == kRailX ? JointType::kPrismatic : JointType::kRevolute;
    info.parent_link = joint.parent_link_name;
    info.child_link = joint.child_link_name;
    info.child_link_index = child_link;
    info.origin = ToIsometry(joint.parent_to_joint_origin_transform);
    info.line = line;

    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!axis.allFinite() || axis.norm() < 1e-12) {
      sink_.Error("urdf-bad-axis", At(line), "joint '" + joint.name + "' has no usable axis");
    } else {
      info.axis = axis.normalized();
    }

    const auto acceleration = lines_.extensions.joint_acceleration.find(joint.name);
    detail::ReadJointDynamics(joint,
                              acceleration == lines_.extensions.joint_acceleration.end()
                                  ? nullptr
                                  : &acceleration->second,
                              At(line), sink_, info);
    if (!joint.limits) {
      sink_.Error("urdf-bad-limits", At(line), "joint '" + joint.name + "' has no <limit>");
      return index;
    }
    info.lower = joint.limits->lower;
    info.upper = joint.limits->upper;
    info.max_velocity = joint.limits->velocity;
    if (!std::isfinite(info.lower) || !std::isfinite(info.upper) || !(info.lower < info.upper)) {
      sink_.Error("urdf-bad-limits", At(line),
                  "joint '" + joint.name + "' needs lower < upper (got " + Num(info.lower) + ", " +
                      Num(info.upper) + ")");
    }
    if (!std::isfinite(info.max_velocity) || !(info.max_velocity > 0.0)) {
      sink_.Error("urdf-bad-limits", At(line),
                  "joint '" + joint.name + "' needs a positive velocity limit (got " +
                      Num(info.max_velocity) + ")");
    }
    return index;
  }

  // Movable joints met on the way from the root to `link`, in order.
  std::vector<int> MovableJointsTo(int link) const {
    std::vector<int> out;
    for (int l : model_.ChainTo(link)) {
      const int joint = model_.links_[static_cast<std::size_t>(l)].joint;
      if (joint >= 0) out.push_back(joint);
    }
    return out;
  }

  bool CheckChains() {
    bool ok = true;
    const std::vector<int> arm = {kRailX, kA1, kA2, kA3, kA4, kA5, kA6};
    if (MovableJointsTo(model_.flange_link_) != arm) {
      sink_.Error("urdf-bad-chain", At(LineOf("[" + std::string(kFlangeLinkName) + "]")),
                  "the flange must hang from rail_x, a1, a2, a3, a4, a5, a6 in that order, "
                  "with only fixed joints between them");
      ok = false;
    }
    if (MovableJointsTo(model_.rotator_link_) != std::vector<int>{kRotator}) {
      sink_.Error("urdf-bad-chain", At(JointLine(kRotator)),
                  "the rotator link must ride on the rotator joint alone");
      ok = false;
    }
    if (!ok) return false;
    for (auto& info : model_.joints_) {
      const auto index = static_cast<std::size_t>(&info - model_.joints_.data());
      model_.lower_(static_cast<Eigen::Index>(index)) = info.lower;
      model_.upper_(static_cast<Eigen::Index>(index)) = info.upper;
      model_.max_velocity_(static_cast<Eigen::Index>(index)) = info.max_velocity;
      model_.effort_(static_cast<Eigen::Index>(index)) = info.effort;
      model_.max_acceleration_(static_cast<Eigen::Index>(index)) = info.max_acceleration;
      model_.damping_(static_cast<Eigen::Index>(index)) = info.damping;
    }
    model_.arm_mount_link_ = model_.LinkIndex(model_.joint(kA1).parent_link);
    return true;
  }

  bool NotOpw(int joint, const std::string& why) {
    sink_.Error("urdf-not-opw", At(JointLine(joint)),
                "the arm must be ortho-parallel with a spherical wrist: " + why);
    return false;
  }

  // The arm at the URDF zero pose: a point on each axis and its direction, and the flange
  // position; in the mount frame (the a1 parent), later in the OPW base frame.
  struct ArmAxes {
    std::array<Eigen::Vector3d, kNumArmJoints> p;
    std::array<Eigen::Vector3d, kNumArmJoints> d;
    Eigen::Vector3d flange;
  };

  static double SignOf(double v) { return v >= 0.0 ? 1.0 : -1.0; }

  // The axes in the mount frame, and the flange's orientation there.
  ArmAxes AxesInMount(Eigen::Matrix3d& flange_rotation) const {
    LinkFrames frames = MakeLinkFrames(model_);
    ForwardKinematics(model_, JointVector::Zero(), frames);
    const Eigen::Isometry3d mount_inv =
        frames.world_pose[static_cast<std::size_t>(model_.arm_mount_link_)].inverse();
    ArmAxes m;
    for (int j = 0; j < kNumArmJoints; ++j) {
      const JointInfo& joint = model_.joint(kA1 + j);
      const Eigen::Isometry3d frame =
          mount_inv * frames.world_pose[static_cast<std::size_t>(joint.child_link_index)];
      m.p[static_cast<std::size_t>(j)] = frame.translation();
      m.d[static_cast<std::size_t>(j)] = frame.linear() * joint.axis;
    }
    const Eigen::Isometry3d flange_in_mount =
        mount_inv * frames.world_pose[static_cast<std::size_t>(model_.flange_link_)];
    m.flange = flange_in_mount.translation();
    flange_rotation = flange_in_mount.linear();
    return m;
  }

  // Base frame: z along a1 (the upright sense), origin on a1 level with the mount origin,
  // x towards the a2 axis. Sets g.mount_to_base, a1_m and the signs of a1..a3.
  bool DeriveBaseFrame(const ArmAxes& m, OpwGeometry& g) {
    const double tol = kGeometryTolerance;
    const auto& p = m.p;
    const auto& d = m.d;
    const Eigen::Vector3d z_b = d[0].z() >= 0.0 ? d[0] : Eigen::Vector3d(-d[0]);
    g.sign[0] = SignOf(d[0].dot(z_b));
    const Eigen::Vector3d origin_b = p[0] - p[0].dot(z_b) * z_b;
    if (std::abs(d[1].dot(z_b)) > tol) return NotOpw(kA2, "a2 is not perpendicular to a1");
    Eigen::Vector3d to_a2 = p[1] - origin_b;
    to_a2 -= to_a2.dot(z_b) * z_b;
    to_a2 -= to_a2.dot(d[1]) * d[1];
    Eigen::Vector3d x_b;
    if (to_a2.norm() > tol) {
      g.a1_m = to_a2.norm();
      x_b = to_a2 / g.a1_m;
    } else {
      g.a1_m = 0.0;
      x_b = d[1].cross(z_b).normalized();
    }
    const Eigen::Vector3d y_b = z_b.cross(x_b);
    g.sign[1] = SignOf(d[1].dot(y_b));
    if (std::abs(d[2].dot(y_b)) < 1.0 - tol) return NotOpw(kA3, "a3 is not parallel to a2");
    g.sign[2] = SignOf(d[2].dot(y_b));
    Eigen::Matrix3d r_b;
    r_b << x_b, y_b, z_b;
    g.mount_to_base = Eigen::Isometry3d::Identity();
    g.mount_to_base.linear() = r_b;
    g.mount_to_base.translation() = origin_b;
    return true;
  }

  // Spherical wrist: a4 and a5 meet at the wrist centre, a6 passes through it (base frame).
  bool WristCentre(const ArmAxes& b, Eigen::Vector3d& wrist) {
    const double tol = kGeometryTolerance;
    const auto& pb = b.p;
    const auto& db = b.d;
    const Eigen::Vector3d w0 = pb[3] - pb[4];
    const double cross = db[3].dot(db[4]);
    const double denom = 1.0 - cross * cross;
    if (denom < tol) return NotOpw(kA5, "a5 is parallel to a4");
    const double s4 = (cross * db[4].dot(w0) - db[3].dot(w0)) / denom;
    const double s5 = (db[4].dot(w0) - cross * db[3].dot(w0)) / denom;
    const Eigen::Vector3d on4 = pb[3] + s4 * db[3];
    const Eigen::Vector3d on5 = pb[4] + s5 * db[4];
    if ((on4 - on5).norm() > tol) return NotOpw(kA5, "a4 and a5 do not intersect");
    wrist = 0.5 * (on4 + on5);
    const Eigen::Vector3d from6 = wrist - pb[5];
    if ((from6 - from6.dot(db[5]) * db[5]).norm() > tol) {
      return NotOpw(kA6, "a6 misses the a4/a5 wrist centre");
    }
    if (std::abs(db[3].y()) > tol) return NotOpw(kA4, "a4 leaves the plane of a2 and a3");
    return true;
  }

  // Forearm (a3 axis to the wrist centre, its z along a4) and the wrist angles at the zero
  // pose: c3, a2, b, c4, the signs of a4..a6 and the OPW angles t23, t4, t5 at q = 0.
  bool DeriveForearmAndWrist(const ArmAxes& b, const Eigen::Vector3d& wrist, OpwGeometry& g,
                             double& t23_zero, double& t4_zero, double& t5_zero) {
    const double tol = kGeometryTolerance;
    const auto& db = b.d;
    const Eigen::Vector3d forearm = wrist - b.p[2];
    const Eigen::Vector3d f4 = forearm.dot(db[3]) >= 0.0 ? db[3] : Eigen::Vector3d(-db[3]);
    g.sign[3] = SignOf(db[3].dot(f4));
    t23_zero = std::atan2(f4.x(), f4.z());
    const Eigen::Matrix3d r_forearm = detail::RotY(t23_zero);
    g.c3_m = forearm.dot(r_forearm.col(2));
    g.a2_m = forearm.dot(r_forearm.col(0));
    g.b_m = wrist.y();
    const Eigen::Vector3d d5 = r_forearm.transpose() * db[4];
    if (std::abs(d5.z()) > tol) return NotOpw(kA5, "a5 is not perpendicular to a4");
    g.sign[4] = d5.y() >= -tol ? 1.0 : -1.0;
    const Eigen::Vector3d e5 = g.sign[4] * d5;
    t4_zero = std::atan2(-e5.x(), e5.y());
    const Eigen::Matrix3d r_4 = r_forearm * detail::RotZ(t4_zero);
    if (std::abs((r_4.transpose() * db[5]).y()) > tol) {
      return NotOpw(kA6, "a6 is not perpendicular to a5");
    }
    const Eigen::Vector3d to_flange = b.flange - wrist;
    Eigen::Vector3d f6 = to_flange.dot(db[5]) >= 0.0 ? db[5] : Eigen::Vector3d(-db[5]);
    g.c4_m = to_flange.dot(f6);
    if (g.c4_m <= tol && (r_4.transpose() * f6).z() < 0.0) f6 = -f6;
    if ((to_flange - g.c4_m * f6).norm() > tol) {
      return NotOpw(kA6, "the flange origin is off the a6 axis");
    }
    g.sign[5] = SignOf(db[5].dot(f6));
    const Eigen::Vector3d f6_in_4 = r_4.transpose() * f6;
    t5_zero = std::atan2(f6_in_4.x(), f6_in_4.z());
    return true;
  }

  // Reads the OPW parameters off the URDF zero pose, in the a1 parent (mount) frame.
  bool DeriveOpw() {
    Eigen::Matrix3d flange_rotation = Eigen::Matrix3d::Identity();
    const ArmAxes m = AxesInMount(flange_rotation);
    OpwGeometry g;
    if (!DeriveBaseFrame(m, g)) return false;
    // Everything in the base frame from here on.
    const Eigen::Matrix3d r_b = g.mount_to_base.linear();
    const Eigen::Vector3d origin_b = g.mount_to_base.translation();
    ArmAxes b;
    for (std::size_t j = 0; j < b.p.size(); ++j) {
      b.p[j] = r_b.transpose() * (m.p[j] - origin_b);
      b.d[j] = r_b.transpose() * m.d[j];
    }
    b.flange = r_b.transpose() * (m.flange - origin_b);
    g.c1_m = b.p[1].z();
    const Eigen::Vector3d upper_arm = b.p[2] - b.p[1];
    g.c2_m = std::hypot(upper_arm.x(), upper_arm.z());
    if (g.c2_m < kGeometryTolerance) return NotOpw(kA3, "a3 lies on the a2 axis");
    const double t2_zero = std::atan2(upper_arm.x(), upper_arm.z());
    Eigen::Vector3d wrist = Eigen::Vector3d::Zero();
    if (!WristCentre(b, wrist)) return false;
    double t23_zero = 0.0, t4_zero = 0.0, t5_zero = 0.0;
    if (!DeriveForearmAndWrist(b, wrist, g, t23_zero, t4_zero, t5_zero)) return false;
    g.offset_rad = {0.0, t2_zero, t23_zero - t2_zero, t4_zero, t5_zero, 0.0};
    for (double& offset : g.offset_rad) offset += 0.0;  // no "-0" in printed parameters
    ArmJointVector t_zero;
    t_zero << g.offset_rad[0], g.offset_rad[1], g.offset_rad[2], g.offset_rad[3], g.offset_rad[4],
        g.offset_rad[5];
    g.opw_flange_to_flange =
        detail::OpwForward(g, t_zero).linear().transpose() * r_b.transpose() * flange_rotation;
    model_.opw_ = g;
    return true;
  }

  // Two routes to one answer: the OPW forward kinematics must reproduce the URDF chain.
  bool VerifyOpw() {
    std::mt19937 rng(20240611u);
    double worst_m = 0.0;
    double worst_rad = 0.0;
    for (int sample = 0; sample < 64; ++sample) {
      JointVector q;
      for (int i = 0; i < kNumJoints; ++i) {
        std::uniform_real_distribution<double> in_limits(model_.lower_(i), model_.upper_(i));
        q(i) = in_limits(rng);
      }
      const Eigen::Isometry3d urdf = FlangePose(model_, q);
      const ArmJointVector t = detail::OpwFromUrdf(model_.opw_, q.segment<kNumArmJoints>(kA1));
      Eigen::Isometry3d opw = ArmBasePose(model_, q(kRailX)) * detail::OpwForward(model_.opw_, t);
      opw.linear() = opw.linear() * model_.opw_.opw_flange_to_flange;
      worst_m = std::max(worst_m, (urdf.translation() - opw.translation()).norm());
      worst_rad =
          std::max(worst_rad, Eigen::AngleAxisd(urdf.linear().transpose() * opw.linear()).angle());
    }
    if (worst_m > kOpwVerifyTolerance || worst_rad > kOpwVerifyTolerance) {
      sink_.Error("urdf-not-opw", At(JointLine(kA1)),
                  "the derived OPW geometry misses the URDF flange by " + Num(worst_m) + " m / " +
                      Num(worst_rad) + " rad");
      return false;
    }
    return true;
  }

  std::string file_;
  DiagnosticSink& sink_;
  XmlLines lines_;
  RobotModel model_;
};

int RobotModel::LinkIndex(std::string_view link_name) const {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == link_name) return static_cast<int>(i);
  }
  return -1;
}

std::optional<RobotModel> ParseRobotModel(std::string_view urdf_text, std::string_view file_label,
                                          DiagnosticSink& sink) {
  return RobotModelBuilder(file_label, sink).Build(urdf_text);
}

std::optional<RobotModel> LoadRobotModel(const std::filesystem::path& path, DiagnosticSink& sink) {
  const std::optional<std::string> text = ReadFile(path);
  if (!text) {
    sink.Error("urdf-missing-file", {path.string(), 0, 0},
               "cannot read URDF file '" + path.string() + "'");
    return std::nullopt;
  }
  return ParseRobotModel(*text, path.string(), sink);
}

}  // namespace stitchsim::sim
