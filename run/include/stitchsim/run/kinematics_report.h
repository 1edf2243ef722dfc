#pragma once
// `stitchsim fk` and `stitchsim ik` as data: the cell's kinematics at joint values or a tool
// pose, as the JSON the commands print, for people debugging a cell. Joints in model order
// [rail_x mm, a1..a6 deg, rotator deg]; tool poses in the part frame in the built-in
// dialect's convention (X Y Z mm, A B C deg).

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "stitchsim/run/loaded_scene.h"

namespace stitchsim::run {

/// Joint values `fk` takes: rail_x (mm), a1..a6 (deg), rotator (deg).
inline constexpr int kCliJointCount = 8;

/// What `fk` / `ik` print, and whether the cell reaches the pose (ik; fk always true).
struct KinematicsReport {
  nlohmann::ordered_json json;  ///< keys in the order printed: status first, details after
  bool reached = true;          ///< ik: a solution within the joint limits
};

/// Forward kinematics at `joints` (kCliJointCount finite values, CLI units): flange in the
/// world (mm), tool point in the part frame, configuration, each joint against its limits.
KinematicsReport ForwardKinematics(const LoadedScene& ls, const std::vector<double>& joints);

/// Inverse kinematics of the tool pose `pose` (X Y Z mm, A B C deg; part frame) with the rail
/// at `rail_mm` (nullopt: the cell's rail policy) and the rotator at `rotator_deg`: the IK's
/// status and reason, the rail, and (when a solution exists) the joints with an FK check.
KinematicsReport InverseKinematics(const LoadedScene& ls, const std::vector<double>& pose,
                                   std::optional<double> rail_mm, double rotator_deg);

}  // namespace stitchsim::run
