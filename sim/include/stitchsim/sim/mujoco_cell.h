#pragma once
// The cell as MuJoCo runs it: models/isaac_cell.xml with the scene's head bolted to the flange
// (its mass properties from the head spec), compiled once, and one working state (mjData) per
// caller. Three uses, as MuJoCo's own model/data split intends:
// - kinematics: qpos from solved joints, mj_kinematics, every frame the rules use read back
//   (the tool point, the links the collision world places, the part on its mount);
// - inverse dynamics: mj_inverse on a timed trajectory gives the joint torques;
// - physics: the position servos (one actuator per joint) tracking a reference, stepped by
//   mj_step1/mj_step2 with the controller's feedforward in between.
// Contacts are off in this model: interference is the FCL collision world's business.

#include <Eigen/Geometry>
#include <memory>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/kinematics.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::sim {

class MujocoModel;  // immutable: the compiled mjModel and the name maps (sim/src/)
struct MujocoData;  // one caller's mjData and caches

/// The servo of one joint as the MJCF gives it (actuator `servo_<joint>`): force = kp (ctrl -
/// q) - kv qdot, clamped to +-force_limit.
struct ServoGains {
  double kp = 0.0;           ///< N/m or N m/rad
  double kv = 0.0;           ///< N s/m or N m s/rad
  double force_limit = 0.0;  ///< N or N m (the actuator's forcerange)
};

class MujocoCell {
 public:
  ~MujocoCell();
  /// Composes and compiles the cell with the scene's head (inertial from the head spec when it
  /// gives one); `cell` gives the part's mount. Diagnostics: mujoco-model (compile errors, a
  /// joint or link of the URDF the MJCF lacks, no tool_point site in the head).
  static std::unique_ptr<MujocoCell> Create(const scene::Scene& scene, const RobotModel& robot,
                                            const CellSetup& cell, DiagnosticSink& sink);
  /// Another working state on the same compiled model (another thread).
  std::unique_ptr<MujocoCell> Share() const;

  // Kinematics ----------------------------------------------------------------------------
  /// qpos = q (model order), mj_kinematics, the frames below read out. The frames of the last
  /// 8 joint vectors are kept: asking again about one of them is free.
  void SetJoints(const JointVector& q);
  /// After SetJoints: world poses, metres.
  Eigen::Isometry3d ToolWorld() const;          ///< the head's tool_point site
  Eigen::Isometry3d LinkWorld(int link) const;  ///< RobotModel::links() index
  Eigen::Isometry3d PartWorld() const;          ///< the part frame on its mount
  void LinkFramesOut(LinkFrames& out) const;    ///< every link (out from MakeLinkFrames)
  /// Tool pose in the part frame, translation in millimetres (the trace's tool_part).
  Eigen::Isometry3d ToolInPartMm() const;

  // Dynamics ------------------------------------------------------------------------------
  /// Joint forces (model order: N for the rail, N m) that move the cell with q, qd, qdd:
  /// what mj_inverse gives on this model (inertia with armature, gravity, Coriolis and
  /// centrifugal, joint damping), computed by the Newton-Euler pass at about half its cost.
  JointVector InverseDynamics(const JointVector& q, const JointVector& qd, const JointVector& qdd);
  /// The same by mj_inverse itself (tests hold the two equal).
  JointVector InverseDynamicsReference(const JointVector& q, const JointVector& qd,
                                       const JointVector& qdd);
  /// The servos; false (and a diagnostic) when the MJCF lacks one.
  bool HasServos() const;
  const ServoGains& Servo(int joint) const;
  /// The joint's armature (reflected rotor inertia: kg for the rail, kg m^2), from the MJCF.
  double Armature(int joint) const;
  /// Physics: the cell at rest at q, time 0.
  void ResetPhysics(const JointVector& q);
  /// Steps the physics by whole timesteps up to `t_end` (s), the servo reference moving from
  /// its last position and velocity to `q_ref`, `qd_ref` on the cubic Hermite through them
  /// (its velocity fed forward),
  /// gravity and Coriolis fed forward from the model (what a controller's dynamic model does),
  /// inertia not (the servo's lag). The physics lands within half a timestep of t_end; the
  /// reference at the time it reached is ReferenceNow() (compare poses at equal times).
  void StepTo(double t_end, const JointVector& q_ref, const JointVector& qd_ref);
  JointVector ReferenceNow() const;
  double PhysicsTime() const;
  JointVector PhysicsJoints() const;
  double Timestep() const;

 private:
  MujocoCell(std::shared_ptr<const MujocoModel> model);
  std::shared_ptr<const MujocoModel> model_;
  std::unique_ptr<MujocoData> data_;
};

}  // namespace stitchsim::sim
