#pragma once
// A scene placed in the cell: where the part is, which tool is on the flange, and how a
// tool-point pose given in the part frame (millimetres) becomes rail + arm joints.

#include <Eigen/Geometry>
#include <optional>

#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/kinematics.h"
#include "stitchsim/sim/robot_model.h"
#include "stitchsim/trace/trace.h"

namespace stitchsim::sim {

class CollisionWorld;

/// Immutable: the robot, the head's tool frame, the part's mount and the rail policy.
struct CellSetup {
  const RobotModel* robot = nullptr;
  Eigen::Isometry3d flange_to_tool_m = Eigen::Isometry3d::Identity();
  scene::Mount mount = scene::Mount::kTable;
  Eigen::Isometry3d mount_to_part_m = Eigen::Isometry3d::Identity();
  double rail_offset_m = 0.0;  ///< rail policy: arm base minus tool target along the rail
  /// World pose of the part when it does not move (table mount), computed once.
  std::optional<Eigen::Isometry3d> fixed_part_world_m;
  IkOptions ik;
};

/// Builds the setup of `scene` on `robot` (the robot must outlive it).
CellSetup MakeCellSetup(const RobotModel& robot, const scene::Scene& scene);

/// World pose of the part frame (metres) with the rotator at `rotator_rad`.
Eigen::Isometry3d PartPoseWorld(const CellSetup& cell, double rotator_rad);

/// A pose for the arm to start from: the carriage at `rail_m`, arm folded over the part side
/// (a2 = -90, a3 = +90, a5 = +90 deg: flange pointing down), rotator at 0.
JointVector HomeJoints(const RobotModel& robot, double rail_m);

struct ToolPoseSolution {
  IkResult ik;         ///< status and joints (model order)
  RailPlacement rail;  ///< where the rail went and why
  Eigen::Isometry3d tool_world_m = Eigen::Isometry3d::Identity();  ///< the target, world
};

/// Solves rail + arm so the tool point sits at `tool_in_part` (translation in millimetres,
/// part frame). `programmed_rail_mm` (E word) overrides the rail policy; `previous` keeps
/// the solution continuous (home joints when null).
ToolPoseSolution SolveToolPose(const CellSetup& cell, const Eigen::Isometry3d& tool_in_part_mm,
                               double rotator_rad, std::optional<double> programmed_rail_mm,
                               const JointVector* previous);

/// Tool pose in the part frame (translation mm) for joints `q` (FK; inverse of the above).
Eigen::Isometry3d ToolPoseInPart(const CellSetup& cell, const JointVector& q);

/// The trace's description of the cell: joint names, limits and speeds from `robot`, and the
/// body table of `collision` (none, and collision_checked false, when it is null).
trace::CellDescription DescribeCell(const RobotModel& robot, const CollisionWorld* collision);

}  // namespace stitchsim::sim
