#include "stitchsim/sim/kinematics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>

#include "detail/opw.h"

namespace stitchsim::sim {
namespace {

using detail::kTwoPi;

// Pose of a link relative to its parent at joint value q (m or rad).
Eigen::Isometry3d LocalPose(const RobotModel& model, const LinkInfo& link, const JointVector& q) {
  Eigen::Isometry3d pose = link.origin;
  if (link.joint < 0) return pose;
  const JointInfo& joint = model.joint(link.joint);
  const double value = q(link.joint);
  if (joint.type == JointType::kRevolute) {
    pose.linear() = pose.linear() * Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
  } else {
    pose.translation() += pose.linear() * (joint.axis * value);
  }
  return pose;
}

std::string Degrees(double rad) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", rad * 180.0 / kPi);
  return buffer;
}

std::string Metres(double m) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", m);
  return buffer;
}

// The 2 pi equivalent of `value` nearest `reference` within [lower, upper]; nullopt if none.
std::optional<double> NearestEquivalentWithin(double value, double reference, double lower,
                                              double upper) {
  const double k_min = std::ceil((lower - value) / kTwoPi);
  const double k_max = std::floor((upper - value) / kTwoPi);
  if (k_min > k_max) return std::nullopt;
  const double k = std::clamp(std::round((reference - value) / kTwoPi), k_min, k_max);
  return value + k * kTwoPi;
}

Eigen::Isometry3d FlangeFix(const OpwGeometry& g) {
  Eigen::Isometry3d fix = Eigen::Isometry3d::Identity();
  fix.linear() = g.opw_flange_to_flange;
  return fix;
}

}  // namespace

LinkFrames MakeLinkFrames(const RobotModel& model) {
  LinkFrames frames;
  frames.world_pose.assign(model.links().size(), Eigen::Isometry3d::Identity());
  return frames;
}

void ForwardKinematics(const RobotModel& model, const JointVector& q, LinkFrames& out) {
  const std::vector<LinkInfo>& links = model.links();
  assert(out.world_pose.size() == links.size() && "LinkFrames not made for this model");
  out.world_pose[0] = Eigen::Isometry3d::Identity();
  for (std::size_t i = 1; i < links.size(); ++i) {
    const LinkInfo& link = links[i];
    out.world_pose[i] =
        out.world_pose[static_cast<std::size_t>(link.parent_link)] * LocalPose(model, link, q);
  }
}

Eigen::Isometry3d LinkPose(const RobotModel& model, const JointVector& q, int link) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int l : model.ChainTo(link)) {
    pose = pose * LocalPose(model, model.links()[static_cast<std::size_t>(l)], q);
  }
  return pose;
}

Eigen::Isometry3d FlangePose(const RobotModel& model, const JointVector& q) {
  return LinkPose(model, q, model.flange_link());
}

Eigen::Isometry3d RotatorPose(const RobotModel& model, const JointVector& q) {
  return LinkPose(model, q, model.rotator_link());
}

Eigen::Isometry3d ArmBasePose(const RobotModel& model, double rail_m) {
  JointVector q = JointVector::Zero();
  q(kRailX) = rail_m;  // the mount hangs from the rail alone (checked at load)
  return LinkPose(model, q, model.arm_mount_link()) * model.opw().mount_to_base;
}

ArmConfiguration ArmConfigurationOf(const RobotModel& model, const JointVector& q) {
  const OpwGeometry& g = model.opw();
  return detail::OpwConfiguration(g, detail::OpwFromUrdf(g, q.segment<kNumArmJoints>(kA1)));
}

ArmIkSolutions AllArmIkSolutions(const RobotModel& model,
                                 const Eigen::Isometry3d& flange_target_world, double rail_m,
                                 const ArmJointVector* hint) {
  const OpwGeometry& g = model.opw();
  const Eigen::Isometry3d base_to_flange =
      ArmBasePose(model, rail_m).inverse() * flange_target_world * FlangeFix(g).inverse();
  ArmJointVector hint_t;
  if (hint != nullptr) hint_t = detail::OpwFromUrdf(g, *hint);
  ArmIkSolutions out;
  detail::OpwInverse(g, base_to_flange, hint != nullptr ? &hint_t : nullptr, out);
  for (int i = 0; i < out.count; ++i) {
    ArmIkSolution& s = out.solution[static_cast<std::size_t>(i)];
    s.joints_rad = detail::UrdfFromOpw(g, s.joints_rad);
  }
  return out;
}

namespace {

// The valid solution nearest the reference (best < 0: none within limits) and, for the
// joint-limit report, the nearest one ignoring limits. Weighted distance, axis by axis at its
// nearest in-limit 2 pi equivalent.
struct SolutionChoice {
  int best = -1;
  ArmJointVector best_joints = ArmJointVector::Zero();
  int nearest_invalid = -1;
  ArmJointVector nearest_invalid_joints = ArmJointVector::Zero();
};

SolutionChoice ChooseSolution(const RobotModel& model, const ArmIkSolutions& solutions,
                              const JointVector& reference, const IkOptions& options) {
  const JointVector& lower = model.lower_limits();
  const JointVector& upper = model.upper_limits();
  const double tol = options.limit_tolerance;
  SolutionChoice choice;
  double best_cost = std::numeric_limits<double>::infinity();
  double nearest_invalid_cost = std::numeric_limits<double>::infinity();
  for (int i = 0; i < solutions.count; ++i) {
    const ArmIkSolution& s = solutions.solution[static_cast<std::size_t>(i)];
    ArmJointVector joints;
    ArmJointVector unlimited;
    bool valid = true;
    double cost = 0.0;
    double unlimited_cost = 0.0;
    for (int j = 0; j < kNumArmJoints; ++j) {
      const int m = kA1 + j;
      const double scale = options.joint_weights(j) / model.max_velocities()(m);
      const double inf = std::numeric_limits<double>::infinity();
      unlimited(j) = *NearestEquivalentWithin(s.joints_rad(j), reference(m), -inf, inf);
      unlimited_cost += std::pow(scale * (unlimited(j) - reference(m)), 2);
      const std::optional<double> within =
          NearestEquivalentWithin(s.joints_rad(j), reference(m), lower(m) - tol, upper(m) + tol);
      if (!within) {
        valid = false;
        continue;
      }
      joints(j) = *within;
      cost += std::pow(scale * (joints(j) - reference(m)), 2);
    }
    if (valid && cost < best_cost) {
      choice.best = i;
      best_cost = cost;
      choice.best_joints = joints;
    }
    if (unlimited_cost < nearest_invalid_cost) {
      choice.nearest_invalid = i;
      nearest_invalid_cost = unlimited_cost;
      choice.nearest_invalid_joints = unlimited;
    }
  }
  return choice;
}

// kJointLimit: every solution violates a limit; the nearest one and its offending axes.
void ReportJointLimits(const RobotModel& model, const ArmIkSolutions& solutions,
                       const SolutionChoice& choice, const JointVector& reference, double tol,
                       IkResult& result) {
  const JointVector& lower = model.lower_limits();
  const JointVector& upper = model.upper_limits();
  const ArmIkSolution& s = solutions.solution[static_cast<std::size_t>(choice.nearest_invalid)];
  result.status = IkStatus::kJointLimit;
  result.joints.segment<kNumArmJoints>(kA1) = choice.nearest_invalid_joints;
  result.configuration = s.configuration;
  result.reason = "all " + std::to_string(solutions.count) +
                  " solutions violate joint limits; nearest (" + ToString(s.configuration) + "):";
  for (int j = 0; j < kNumArmJoints; ++j) {
    const int m = kA1 + j;
    if (!NearestEquivalentWithin(s.joints_rad(j), reference(m), lower(m) - tol, upper(m) + tol)) {
      result.reason += " " + std::string(kJointNames[static_cast<std::size_t>(m)]) + " " +
                       Degrees(choice.nearest_invalid_joints(j)) + " deg outside [" +
                       Degrees(lower(m)) + ", " + Degrees(upper(m)) + "]";
    }
  }
}

// The status of the chosen solution: kOk unless near a singularity or in another
// configuration than `previous`.
void ClassifyChosen(const RobotModel& model, const ArmIkSolutions& solutions,
                    const ArmIkSolution& chosen, const JointVector* previous,
                    const IkOptions& options, IkResult& result) {
  result.status = IkStatus::kOk;
  if (solutions.wrist_centre_radius_m < options.shoulder_singularity_m) {
    result.status = IkStatus::kShoulderSingularity;
    result.reason = "wrist centre " + Metres(solutions.wrist_centre_radius_m) +
                    " m from the a1 axis (threshold " + Metres(options.shoulder_singularity_m) +
                    " m)";
  } else if (std::abs(chosen.sin_wrist) < std::sin(options.wrist_singularity_rad)) {
    result.status = IkStatus::kWristSingularity;
    result.reason = "a4 and a6 nearly aligned: wrist angle " +
                    Degrees(std::asin(std::abs(chosen.sin_wrist))) + " deg from straight " +
                    "(threshold " + Degrees(options.wrist_singularity_rad) + " deg)";
  } else if (previous != nullptr) {
    const ArmConfiguration before = ArmConfigurationOf(model, *previous);
    if (!(before == chosen.configuration)) {
      result.status = IkStatus::kConfigFlip;
      result.reason = "configuration " + ToString(before) + " -> " + ToString(chosen.configuration);
    }
  }
}

}  // namespace

IkResult SolveIk(const RobotModel& model, const Eigen::Isometry3d& flange_target_world,
                 double rail_m, const JointVector* previous, const IkOptions& options) {
  const JointVector& reference = previous != nullptr ? *previous : options.reference;
  const JointVector& lower = model.lower_limits();
  const JointVector& upper = model.upper_limits();
  const double tol = options.limit_tolerance;

  IkResult result;
  result.joints = reference;
  result.joints(kRailX) = rail_m;
  result.configuration = ArmConfigurationOf(model, result.joints);
  if (!(rail_m >= lower(kRailX) - tol && rail_m <= upper(kRailX) + tol)) {
    result.status = IkStatus::kJointLimit;
    result.reason = "rail_x " + Metres(rail_m) + " m outside [" + Metres(lower(kRailX)) + ", " +
                    Metres(upper(kRailX)) + "] m";
    return result;
  }

  const ArmJointVector reference_arm = reference.segment<kNumArmJoints>(kA1);
  const ArmIkSolutions solutions =
      AllArmIkSolutions(model, flange_target_world, rail_m, previous ? &reference_arm : nullptr);
  if (solutions.count == 0) {
    result.status = IkStatus::kUnreachable;
    result.reason =
        "wrist centre out of reach: " +
        Metres(std::min(solutions.shoulder_to_wrist_front_m, solutions.shoulder_to_wrist_back_m)) +
        " m from the a2 axis, the arm spans " + Metres(solutions.min_reach_m) + ".." +
        Metres(solutions.max_reach_m) + " m";
    return result;
  }

  const SolutionChoice choice = ChooseSolution(model, solutions, reference, options);
  if (choice.best < 0) {
    ReportJointLimits(model, solutions, choice, reference, tol, result);
    return result;
  }
  const ArmIkSolution& chosen = solutions.solution[static_cast<std::size_t>(choice.best)];
  result.joints.segment<kNumArmJoints>(kA1) = choice.best_joints;
  result.configuration = chosen.configuration;
  ClassifyChosen(model, solutions, chosen, previous, options, result);
  return result;
}

Eigen::Isometry3d FlangeTargetForTool(const Eigen::Isometry3d& tool_target_world,
                                      const Eigen::Isometry3d& flange_to_tool) {
  return tool_target_world * flange_to_tool.inverse();
}

RailPlacement RailForTarget(const RobotModel& model, const Eigen::Isometry3d& tool_target_world,
                            const RailPolicy& policy) {
  RailPlacement placement;
  if (policy.programmed_rail_m) {
    placement.rail_m = *policy.programmed_rail_m;
    placement.programmed = true;
    return placement;
  }
  // The a1 axis moves along `direction` by one metre per metre of rail.
  const Eigen::Vector3d base_at_zero = ArmBasePose(model, 0.0).translation();
  const Eigen::Vector3d direction = ArmBasePose(model, 1.0).translation() - base_at_zero;
  const double along =
      (tool_target_world.translation() - base_at_zero).dot(direction) / direction.squaredNorm();
  const double wanted = along + policy.base_offset_along_rail_m / direction.norm();
  const double lower = model.lower_limits()(kRailX);
  const double upper = model.upper_limits()(kRailX);
  placement.rail_m = std::clamp(wanted, lower, upper);
  placement.clamped = placement.rail_m != wanted;
  return placement;
}

Eigen::Isometry3d RotatorCarriedPose(const RobotModel& model, double rotator_rad,
                                     const Eigen::Isometry3d& rotator_to_frame) {
  JointVector q = JointVector::Zero();
  q(kRotator) = rotator_rad;  // the rotator link rides on the rotator joint alone
  return RotatorPose(model, q) * rotator_to_frame;
}

}  // namespace stitchsim::sim
