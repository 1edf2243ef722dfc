#include "stitchsim/sim/mujoco_cell.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "detail/collision_mjcf.h"

namespace stitchsim::sim {

// The compiled model and where each of our names lives in it.
class MujocoModel {
 public:
  detail::MjModelPtr m;
  std::array<int, kNumJoints> qpos{};   ///< qpos address of each joint, model order
  std::array<int, kNumJoints> dof{};    ///< dof address
  std::array<int, kNumJoints> servo{};  ///< actuator id of servo_<joint>, -1 when absent
  std::array<ServoGains, kNumJoints> gains{};
  std::vector<int> link_body;  ///< MuJoCo body of each URDF link (0: the world)
  int tool_site = -1;
  int mount_body = 0;  ///< the table or the rotator
  Eigen::Isometry3d mount_to_part = Eigen::Isometry3d::Identity();
  bool servos = false;
};

struct MujocoData {
  struct Deleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  std::unique_ptr<mjData, Deleter> d;
  /// The frames MuJoCo's kinematics gave at the last few joint vectors: the executor and the
  /// collision world's subdivision ask about the same joints again within a few calls.
  struct Frames {
    JointVector q = JointVector::Constant(std::nan(""));
    std::vector<Eigen::Isometry3d> links;  ///< per URDF link, world, metres
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity(), part = Eigen::Isometry3d::Identity();
  };
  static constexpr std::size_t kCached = 8;
  std::array<Frames, kCached> cache;
  std::size_t current = 0, next = 0;
  JointVector q_ref = JointVector::Zero();    ///< the reference StepTo last moved to
  JointVector qd_ref = JointVector::Zero();   ///< and its velocity
  JointVector ref_now = JointVector::Zero();  ///< the reference at PhysicsTime()
};

namespace {

Eigen::Isometry3d PoseOf(const mjtNum* pos, const mjtNum* mat) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pos[0], pos[1], pos[2]);
  t.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(mat);
  return t;
}

std::string XmlNum(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The head spec's mass properties as an MJCF <inertial> (flange frame = the head root's).
std::string HeadInertialXml(const scene::HeadSpec& head) {
  if (!head.inertial) return {};
  const auto& in = *head.inertial;
  const Eigen::Matrix3d& I = in.inertia_kg_m2;
  return "<inertial pos=\"" + XmlNum(in.com_m.x()) + " " + XmlNum(in.com_m.y()) + " " +
         XmlNum(in.com_m.z()) + "\" mass=\"" + XmlNum(in.mass_kg) + "\" fullinertia=\"" +
         XmlNum(I(0, 0)) + " " + XmlNum(I(1, 1)) + " " + XmlNum(I(2, 2)) + " " + XmlNum(I(0, 1)) +
         " " + XmlNum(I(0, 2)) + " " + XmlNum(I(1, 2)) + "\"/>";
}

bool MapNames(MujocoModel& mm, const RobotModel& robot, const std::string& file,
              DiagnosticSink& sink) {
  const mjModel& m = *mm.m;
  bool ok = true;
  for (int j = 0; j < kNumJoints; ++j) {
    const std::string name(kJointNames[static_cast<std::size_t>(j)]);
    const int id = mj_name2id(&m, mjOBJ_JOINT, name.c_str());
    if (id < 0) {
      sink.Error("mujoco-model", {file, 0, 0}, "the MJCF has no joint '" + name + "'");
      ok = false;
      continue;
    }
    mm.qpos[j] = m.jnt_qposadr[id];
    mm.dof[j] = m.jnt_dofadr[id];
    mm.servo[j] = mj_name2id(&m, mjOBJ_ACTUATOR, ("servo_" + name).c_str());
  }
  mm.link_body.assign(robot.links().size(), 0);
  for (std::size_t i = 0; i < robot.links().size(); ++i) {
    const std::string& name = robot.links()[i].name;
    if (name == "world") continue;
    const int b = mj_name2id(&m, mjOBJ_BODY, name.c_str());
    if (b < 0) {
      sink.Error("mujoco-model", {file, 0, 0}, "the MJCF has no body for URDF link '" + name + "'");
      ok = false;
      continue;
    }
    mm.link_body[i] = b;
  }
  mm.tool_site = mj_name2id(&m, mjOBJ_SITE, "tool_point");
  if (mm.tool_site < 0) {
    sink.Error("mujoco-model", {file, 0, 0}, "the head MJCF has no site 'tool_point'");
    ok = false;
  }
  return ok;
}

void ReadServos(MujocoModel& mm) {
  const mjModel& m = *mm.m;
  mm.servos = true;
  for (int j = 0; j < kNumJoints; ++j) {
    const int a = mm.servo[j];
    if (a < 0) {
      mm.servos = false;
      continue;
    }
    ServoGains& g = mm.gains[static_cast<std::size_t>(j)];
    g.kp = m.actuator_gainprm[a * mjNGAIN];
    g.kv = -m.actuator_biasprm[a * mjNBIAS + 2];
    g.force_limit = m.actuator_forcelimited[a] ? m.actuator_forcerange[2 * a + 1] : 0.0;
  }
}

// qpos, qvel and qacc from model-order joint vectors.
void SetState(const MujocoModel& mm, mjData& d, const JointVector& q, const JointVector& qd,
              const JointVector& qdd) {
  for (int j = 0; j < kNumJoints; ++j) {
    d.qpos[mm.qpos[j]] = q[j];
    d.qvel[mm.dof[j]] = qd[j];
    d.qacc[mm.dof[j]] = qdd[j];
  }
}

}  // namespace

MujocoCell::MujocoCell(std::shared_ptr<const MujocoModel> model)
    : model_(std::move(model)), data_(std::make_unique<MujocoData>()) {
  data_->d.reset(mj_makeData(model_->m.get()));
}

MujocoCell::~MujocoCell() = default;

std::unique_ptr<MujocoCell> MujocoCell::Create(const scene::Scene& scene, const RobotModel& robot,
                                               const CellSetup& cell, DiagnosticSink& sink) {
  auto mm = std::make_shared<MujocoModel>();
  // No geoms: the masses come from <inertial> (the MJCF says inertiafromgeom="false"), and
  // interference is FCL's, so the kinematics need not pose them.
  mm->m = detail::CompileCellWithHead(scene.cell_mjcf, scene.head.mjcf, sink,
                                      HeadInertialXml(scene.head), "mujoco-model", true);
  if (!mm->m) return nullptr;
  // Interference is FCL's: MuJoCo's contacts would push the arm off the bodies it touches.
  mm->m->opt.disableflags |= mjDSBL_CONTACT;
  const std::string file = scene.cell_mjcf.string();
  if (!MapNames(*mm, robot, file, sink)) return nullptr;
  ReadServos(*mm);
  const char* mount = cell.mount == scene::Mount::kRotator ? "rotator" : "table";
  mm->mount_body = mj_name2id(mm->m.get(), mjOBJ_BODY, mount);
  if (mm->mount_body < 0) {
    sink.Error("mujoco-model", {file, 0, 0}, std::string("the MJCF has no body '") + mount + "'");
    return nullptr;
  }
  mm->mount_to_part = cell.mount_to_part_m;
  return std::unique_ptr<MujocoCell>(new MujocoCell(std::move(mm)));
}

std::unique_ptr<MujocoCell> MujocoCell::Share() const {
  return std::unique_ptr<MujocoCell>(new MujocoCell(model_));
}

void MujocoCell::SetJoints(const JointVector& q) {
  MujocoData& data = *data_;
  for (std::size_t i = 0; i < MujocoData::kCached; ++i) {
    if (data.cache[i].q == q) {
      data.current = i;
      return;
    }
  }
  const mjModel& m = *model_->m;
  mjData& d = *data.d;
  for (int j = 0; j < kNumJoints; ++j) d.qpos[model_->qpos[j]] = q[j];
  mj_kinematics(&m, &d);
  MujocoData::Frames& f = data.cache[data.next];
  data.current = data.next;
  data.next = (data.next + 1) % MujocoData::kCached;
  f.q = q;
  f.links.resize(model_->link_body.size());
  for (std::size_t i = 0; i < f.links.size(); ++i) {
    const int b = model_->link_body[i];
    f.links[i] = PoseOf(d.xpos + 3 * b, d.xmat + 9 * b);
  }
  const int s = model_->tool_site, b = model_->mount_body;
  f.tool = PoseOf(d.site_xpos + 3 * s, d.site_xmat + 9 * s);
  f.part = PoseOf(d.xpos + 3 * b, d.xmat + 9 * b) * model_->mount_to_part;
}

Eigen::Isometry3d MujocoCell::ToolWorld() const { return data_->cache[data_->current].tool; }

Eigen::Isometry3d MujocoCell::LinkWorld(int link) const {
  return data_->cache[data_->current].links[static_cast<std::size_t>(link)];
}

Eigen::Isometry3d MujocoCell::PartWorld() const { return data_->cache[data_->current].part; }

void MujocoCell::LinkFramesOut(LinkFrames& out) const {
  const auto& links = data_->cache[data_->current].links;
  std::copy(links.begin(), links.end(), out.world_pose.begin());
}

Eigen::Isometry3d MujocoCell::ToolInPartMm() const {
  Eigen::Isometry3d t = PartWorld().inverse() * ToolWorld();
  t.translation() *= 1000.0;
  return t;
}

JointVector MujocoCell::InverseDynamics(const JointVector& q, const JointVector& qd,
                                        const JointVector& qdd) {
  const mjModel& m = *model_->m;
  mjData& d = *data_->d;
  SetState(*model_, d, q, qd, qdd);
  // What mj_inverse gives on this model (no constraints, springs or friction loss), for
  // half its cost: the recursive Newton-Euler pass (M qacc + gravity, Coriolis, centrifugal)
  // on the rigid bodies, plus each joint's armature (the rotors' inertia, which MuJoCo keeps
  // on the mass matrix's diagonal) and its viscous damping. A test holds the two equal.
  mj_kinematics(&m, &d);
  mj_comPos(&m, &d);
  mj_comVel(&m, &d);
  mj_rne(&m, &d, 1, d.qfrc_inverse);
  JointVector tau;
  for (int j = 0; j < kNumJoints; ++j) {
    const int v = model_->dof[j];
    tau[j] = d.qfrc_inverse[v] + m.dof_armature[v] * qdd[j] + m.dof_damping[v] * qd[j];
  }
  return tau;
}

JointVector MujocoCell::InverseDynamicsReference(const JointVector& q, const JointVector& qd,
                                                 const JointVector& qdd) {
  const mjModel& m = *model_->m;
  mjData& d = *data_->d;
  SetState(*model_, d, q, qd, qdd);
  mj_inverse(&m, &d);
  JointVector tau;
  for (int j = 0; j < kNumJoints; ++j) tau[j] = d.qfrc_inverse[model_->dof[j]];
  return tau;
}

bool MujocoCell::HasServos() const { return model_->servos; }

const ServoGains& MujocoCell::Servo(int joint) const {
  return model_->gains[static_cast<std::size_t>(joint)];
}

void MujocoCell::ResetPhysics(const JointVector& q) {
  const mjModel& m = *model_->m;
  mjData& d = *data_->d;
  mj_resetData(&m, &d);
  for (int j = 0; j < kNumJoints; ++j) d.qpos[model_->qpos[j]] = q[j];
  mj_forward(&m, &d);
  data_->q_ref = q;
  data_->qd_ref = JointVector::Zero();
  data_->ref_now = q;
}

void MujocoCell::StepTo(double t_end, const JointVector& q_ref, const JointVector& qd_ref) {
  const mjModel& m = *model_->m;
  mjData& d = *data_->d;
  const double dt = m.opt.timestep;
  const JointVector q0 = data_->q_ref, v0 = data_->qd_ref;
  const double t0 = d.time;
  const double h = t_end - t0;
  // The reference between the two samples: the cubic Hermite through both positions and
  // velocities (the time law's), and its velocity.
  const auto reference = [&](double t, JointVector& velocity) -> JointVector {
    if (!(h > 1e-12)) {
      velocity = qd_ref;
      return q_ref;
    }
    const double u = std::clamp((t - t0) / h, 0.0, 1.0), u2 = u * u, u3 = u2 * u;
    velocity = ((6 * u2 - 6 * u) * q0 + (3 * u2 - 4 * u + 1) * h * v0 + (6 * u - 6 * u2) * q_ref +
                (3 * u2 - 2 * u) * h * qd_ref) /
               h;
    return (2 * u3 - 3 * u2 + 1) * q0 + (u3 - 2 * u2 + u) * h * v0 + (3 * u2 - 2 * u3) * q_ref +
           (u3 - u2) * h * qd_ref;
  };
  JointVector velocity;
  while (d.time + 0.5 * dt <= t_end) {
    mj_step1(&m, &d);  // positions and velocities: qfrc_bias (gravity, Coriolis) is current
    const JointVector ref = reference(d.time, velocity);  // at the state's own time
    for (int j = 0; j < kNumJoints; ++j) {
      const int a = model_->servo[j];
      if (a < 0) continue;
      const ServoGains& g = model_->gains[static_cast<std::size_t>(j)];
      if (!(g.kp > 0.0)) continue;
      // Position servo with velocity and bias feedforward: force = kp (ref - q) +
      // kv (v_ref - qdot) + bias(q, qdot), the actuator's range clamping the sum.
      d.ctrl[a] = ref[j] + (g.kv * velocity[j] + d.qfrc_bias[model_->dof[j]]) / g.kp;
    }
    mj_step2(&m, &d);
  }
  data_->q_ref = q_ref;
  data_->qd_ref = qd_ref;
  data_->ref_now = reference(d.time, velocity);
}

JointVector MujocoCell::ReferenceNow() const { return data_->ref_now; }

double MujocoCell::PhysicsTime() const { return data_->d->time; }

JointVector MujocoCell::PhysicsJoints() const {
  JointVector q;
  for (int j = 0; j < kNumJoints; ++j) q[j] = data_->d->qpos[model_->qpos[j]];
  return q;
}

double MujocoCell::Armature(int joint) const { return model_->m->dof_armature[model_->dof[joint]]; }

double MujocoCell::Timestep() const { return model_->m->opt.timestep; }

}  // namespace stitchsim::sim
