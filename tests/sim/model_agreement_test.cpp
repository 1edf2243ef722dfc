// Two routes to one answer: our URDF forward kinematics against MuJoCo's on the MJCF cell.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "sim_test_support.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"

namespace stitchsim::sim {
namespace {

using testing::CellMjcfPath;
using testing::CellTest;
using testing::PositionError;
using testing::RandomJoints;
using testing::RotationError;

constexpr double kToleranceM = 1e-9;
constexpr double kToleranceRad = 1e-9;

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

// Documented assumptions the derived numbers rest on (docs/cell-model.md "Dynamics").
constexpr double kEffortMargin = 1.5;
constexpr double kLargestPartKg = 2000.0;  // on the rotator, as a point mass at 1 m radius
constexpr double kLargestPartRadiusM = 1.0;
constexpr double kServoBandwidthHz = 15.0;
constexpr double kServoDampingRatio = 1.0;

// The cell MJCF with the rated payload (a point mass at (0, lxy, lz) in the flange frame, so
// that its offset is horizontal at the zero pose) and optionally the largest part on the
// rotator, compiled from memory.
MjModelPtr LoadLoadedCell(const PayloadRating& rating, bool with_part, std::string& error) {
  std::string text = ReadFile(CellMjcfPath()).value_or("");
  const auto insert = [&text](const std::string& marker, const std::string& body) {
    const std::size_t at = text.find(marker);
    if (at != std::string::npos) text.replace(at, marker.size(), body);
    return at != std::string::npos;
  };
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "<body name=\"payload\" pos=\"0 %.17g %.17g\"><inertial pos=\"0 0 0\" "
                "mass=\"%.17g\" diaginertia=\"0 0 0\"/></body>",
                rating.lxy_m, rating.lz_m, rating.mass_kg);
  if (!insert("<!--STITCHSIM:HEAD-->", buffer)) error = "no head marker";
  std::snprintf(buffer, sizeof buffer,
                "<body name=\"part\" pos=\"%.17g 0 0.5\"><inertial pos=\"0 0 0\" "
                "mass=\"%.17g\" diaginertia=\"0 0 0\"/></body>",
                kLargestPartRadiusM, kLargestPartKg);
  if (with_part && !insert("<!--STITCHSIM:PART_ROTATOR-->", buffer)) error = "no part marker";
  if (!error.empty()) return nullptr;
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "loaded_cell.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(text.size())) != 0) {
    error = "VFS full";
    return nullptr;
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], text.data(), text.size());
  char mj_error[1000] = "";
  MjModelPtr m(mj_loadXML(name, vfs.get(), mj_error, sizeof mj_error));
  mj_deleteVFS(vfs.get());
  if (!m) error = mj_error;
  return m;
}

int Dof(const mjModel& m, int joint_index) {
  const std::string name(kJointNames[static_cast<std::size_t>(joint_index)]);
  const int id = mj_name2id(&m, mjOBJ_JOINT, name.c_str());
  return id < 0 ? -1 : m.jnt_dofadr[id];
}

// Relative difference, for numbers rounded to 3 significant digits.
double Relative(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

class sim_model_agreement : public CellTest {
 protected:
  void SetUp() override {
    CellTest::SetUp();
    if (HasFatalFailure()) return;
    char error[1000] = "";
    mj_.reset(mj_loadXML(CellMjcfPath().c_str(), nullptr, error, sizeof error));
    ASSERT_NE(mj_, nullptr) << error;
    data_.reset(mj_makeData(mj_.get()));
    ASSERT_NE(data_, nullptr);
    for (int i = 0; i < kNumJoints; ++i) {
      const std::string name(kJointNames[static_cast<std::size_t>(i)]);
      joint_id_[i] = mj_name2id(mj_.get(), mjOBJ_JOINT, name.c_str());
      ASSERT_GE(joint_id_[i], 0) << "MJCF lacks joint " << name;
    }
  }

  MjModelPtr mj_;
  MjDataPtr data_;
  int joint_id_[kNumJoints] = {};
};

TEST_F(sim_model_agreement, JointTypesAxesRangesAndAnchorsMatch) {
  for (int i = 0; i < kNumJoints; ++i) {
    const JointInfo& joint = model().joint(i);
    const int id = joint_id_[i];
    SCOPED_TRACE(joint.name);
    EXPECT_EQ(mj_->jnt_type[id], joint.type == JointType::kPrismatic ? mjJNT_SLIDE : mjJNT_HINGE);
    const Eigen::Vector3d axis(mj_->jnt_axis[3 * id], mj_->jnt_axis[3 * id + 1],
                               mj_->jnt_axis[3 * id + 2]);
    EXPECT_LT((axis - joint.axis).norm(), 1e-12);
    const Eigen::Vector3d anchor(mj_->jnt_pos[3 * id], mj_->jnt_pos[3 * id + 1],
                                 mj_->jnt_pos[3 * id + 2]);
    EXPECT_LT(anchor.norm(), 1e-12) << "URDF joints sit at their child link origin";
    EXPECT_EQ(mj_->jnt_limited[id], 1);
    EXPECT_NEAR(mj_->jnt_range[2 * id], joint.lower, 1e-12);
    EXPECT_NEAR(mj_->jnt_range[2 * id + 1], joint.upper, 1e-12);
    // The joint must move the body that carries the URDF child link's name.
    const int body = mj_->jnt_bodyid[id];
    EXPECT_EQ(std::string(mj_id2name(mj_.get(), mjOBJ_BODY, body)), joint.child_link);
  }
  EXPECT_EQ(mj_->njnt, kNumJoints) << "MJCF has joints the URDF lacks";
}

TEST_F(sim_model_agreement, EveryLinkFrameMatchesMujocoBodyPose) {
  const std::vector<LinkInfo>& links = model().links();
  std::vector<int> body_id(links.size());
  for (std::size_t i = 0; i < links.size(); ++i) {
    body_id[i] = mj_name2id(mj_.get(), mjOBJ_BODY, links[i].name.c_str());
    ASSERT_GE(body_id[i], 0) << "MJCF lacks body " << links[i].name;
  }
  EXPECT_EQ(static_cast<std::size_t>(mj_->nbody), links.size()) << "MJCF has extra bodies";

  std::mt19937_64 rng(42);
  LinkFrames frames = MakeLinkFrames(model());
  double worst_m = 0.0;
  double worst_rad = 0.0;
  for (int sample = 0; sample < 1000; ++sample) {
    const JointVector q = RandomJoints(model(), rng);
    for (int i = 0; i < kNumJoints; ++i) data_->qpos[mj_->jnt_qposadr[joint_id_[i]]] = q(i);
    mj_kinematics(mj_.get(), data_.get());
    ForwardKinematics(model(), q, frames);
    for (std::size_t i = 0; i < links.size(); ++i) {
      const int b = body_id[i];
      Eigen::Isometry3d mujoco = Eigen::Isometry3d::Identity();
      mujoco.translation() =
          Eigen::Vector3d(data_->xpos[3 * b], data_->xpos[3 * b + 1], data_->xpos[3 * b + 2]);
      mujoco.linear() =
          Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data_->xmat + 9 * b);
      const double error_m = PositionError(frames.world_pose[i], mujoco);
      const double error_rad = RotationError(frames.world_pose[i], mujoco);
      worst_m = std::max(worst_m, error_m);
      worst_rad = std::max(worst_rad, error_rad);
      ASSERT_LT(error_m, kToleranceM) << links[i].name << " sample " << sample;
      ASSERT_LT(error_rad, kToleranceRad) << links[i].name << " sample " << sample;
      // The single-link routes agree with the all-links pass.
      if (static_cast<int>(i) == model().flange_link()) {
        ASSERT_LT(PositionError(FlangePose(model(), q), frames.world_pose[i]), 1e-12);
      }
      if (static_cast<int>(i) == model().rotator_link()) {
        ASSERT_LT(PositionError(RotatorPose(model(), q), frames.world_pose[i]), 1e-12);
      }
    }
  }
  RecordProperty("worst_position_error_m", testing::Sci(worst_m));
  RecordProperty("worst_rotation_error_rad", testing::Sci(worst_rad));
}

TEST_F(sim_model_agreement, InertialsMatchUrdf) {
  int with_inertial = 0;
  for (const LinkInfo& link : model().links()) {
    SCOPED_TRACE(link.name);
    const int b = mj_name2id(mj_.get(), mjOBJ_BODY, link.name.c_str());
    ASSERT_GE(b, 0);
    if (!link.inertial) {
      EXPECT_EQ(mj_->body_mass[b], 0.0) << "mass in the MJCF that the URDF lacks";
      continue;
    }
    ++with_inertial;
    const LinkInertial& in = *link.inertial;
    EXPECT_LE(Relative(mj_->body_mass[b], in.mass_kg), 1e-9);
    const Eigen::Vector3d ipos(mj_->body_ipos[3 * b], mj_->body_ipos[3 * b + 1],
                               mj_->body_ipos[3 * b + 2]);
    EXPECT_LE((ipos - in.com_m).norm(), 1e-9 * in.com_m.norm() + 1e-15);
    // MuJoCo keeps the principal moments and the principal axes' orientation: turn them back.
    const double* q = mj_->body_iquat + 4 * b;
    const Eigen::Matrix3d r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
    const Eigen::Vector3d moments(mj_->body_inertia[3 * b], mj_->body_inertia[3 * b + 1],
                                  mj_->body_inertia[3 * b + 2]);
    const Eigen::Matrix3d full = r * moments.asDiagonal() * r.transpose();
    EXPECT_LE((full - in.inertia_kg_m2).norm(), 1e-9 * in.inertia_kg_m2.norm())
        << "MuJoCo:\n"
        << full << "\nURDF:\n"
        << in.inertia_kg_m2;
  }
  EXPECT_EQ(with_inertial, 9) << "carriage, base_link, link_1..link_6, rotator";
}

TEST_F(sim_model_agreement, DampingArmatureAndServosMatchUrdf) {
  ASSERT_EQ(mj_->nu, kNumJoints) << "one servo per joint";
  for (int i = 0; i < kNumJoints; ++i) {
    const JointInfo& joint = model().joint(i);
    SCOPED_TRACE(joint.name);
    const int dof = mj_->jnt_dofadr[joint_id_[i]];
    EXPECT_EQ(mj_->dof_damping[dof], joint.damping);
    EXPECT_GT(mj_->dof_armature[dof], 0.0) << "reflected drive inertia";
    const std::string servo = "servo_" + joint.name;
    const int a = mj_name2id(mj_.get(), mjOBJ_ACTUATOR, servo.c_str());
    ASSERT_GE(a, 0) << "MJCF lacks actuator " << servo;
    EXPECT_EQ(mj_->actuator_trntype[a], mjTRN_JOINT);
    EXPECT_EQ(mj_->actuator_trnid[2 * a], joint_id_[i]);
    EXPECT_EQ(mj_->actuator_forcelimited[a], 1);
    EXPECT_GT(joint.effort, 0.0);
    EXPECT_EQ(mj_->actuator_forcerange[2 * a], -joint.effort);
    EXPECT_EQ(mj_->actuator_forcerange[2 * a + 1], joint.effort);
    EXPECT_EQ(mj_->actuator_ctrllimited[a], 0);
    EXPECT_EQ(mj_->actuator_gaintype[a], mjGAIN_FIXED);
    EXPECT_EQ(mj_->actuator_biastype[a], mjBIAS_AFFINE);
    // A position servo: force = KP (ctrl - q) - KV qdot.
    const double* gain = mj_->actuator_gainprm + mjNGAIN * a;
    const double* bias = mj_->actuator_biasprm + mjNBIAS * a;
    EXPECT_GT(gain[0], 0.0);
    EXPECT_EQ(bias[0], 0.0);
    EXPECT_EQ(bias[1], -gain[0]);
    EXPECT_LT(bias[2], 0.0);
  }
  EXPECT_EQ(mj_->opt.gravity[2], -9.81);
  EXPECT_EQ(mj_->opt.timestep, 0.001);
}

// Effort = 1.5 x the largest generalised force that holds the joint and accelerates it from
// rest at its acceleration limit, with the rated payload at full horizontal reach (the zero
// pose). MuJoCo's inverse dynamics gives it; the rail's is checked by hand as well.
TEST_F(sim_model_agreement, EffortLimitsFollowFromRatedPayload) {
  const PayloadRating& rating = model().payload_rating();
  ASSERT_GT(rating.mass_kg, 0.0);
  std::string error;
  MjModelPtr m = LoadLoadedCell(rating, /*with_part=*/true, error);
  ASSERT_NE(m, nullptr) << error;
  m->opt.disableflags |= mjDSBL_CONSTRAINT;  // free motion: no limit or contact forces
  MjDataPtr d(mj_makeData(m.get()));
  double moving_kg = 0.0;  // carriage .. payload, from the URDF
  for (const LinkInfo& link : model().links()) {
    if (link.inertial && link.name != "rotator") moving_kg += link.inertial->mass_kg;
  }
  moving_kg += rating.mass_kg;
  for (int i = 0; i < kNumJoints; ++i) {
    const JointInfo& joint = model().joint(i);
    SCOPED_TRACE(joint.name);
    const int dof = Dof(*m, i);
    ASSERT_GE(dof, 0);
    ASSERT_GT(joint.max_acceleration, 0.0);
    double largest = 0.0;
    for (const double sign : {-1.0, 1.0}) {
      mju_zero(d->qpos, m->nq);
      d->qpos[m->jnt_qposadr[mj_name2id(m.get(), mjOBJ_JOINT, "rail_x")]] = 3.0;  // mid rail
      mju_zero(d->qvel, m->nv);
      mju_zero(d->qacc, m->nv);
      d->qacc[dof] = sign * joint.max_acceleration;
      mj_inverse(m.get(), d.get());
      largest = std::max(largest, std::abs(d->qfrc_inverse[dof]));
    }
    const double effort = kEffortMargin * largest;
    EXPECT_LE(Relative(joint.effort, effort), 0.01)
        << "URDF " << joint.effort << ", derived " << effort;
    RecordProperty("derived_effort_" + joint.name, testing::Sci(effort));
    if (i == kRailX) {
      const double by_hand =
          kEffortMargin * (moving_kg + m->dof_armature[dof]) * joint.max_acceleration;
      EXPECT_NEAR(effort, by_hand, 1e-9 * by_hand);
    }
    if (i == kRotator) {
      const LinkInertial& turntable =
          *model().links()[static_cast<std::size_t>(model().rotator_link())].inertial;
      const double inertia = turntable.inertia_kg_m2(2, 2) + m->dof_armature[dof] +
                             kLargestPartKg * kLargestPartRadiusM * kLargestPartRadiusM;
      EXPECT_NEAR(effort, kEffortMargin * inertia * joint.max_acceleration, 1e-9 * effort);
    }
  }
}

// KP = I w^2, KV = 2 zeta I w, I = the joint's diagonal of the mass matrix (armature included)
// at home with the rated payload at the flange.
TEST_F(sim_model_agreement, ServoGainsFollowFromMassMatrix) {
  std::string error;
  MjModelPtr m = LoadLoadedCell(model().payload_rating(), /*with_part=*/false, error);
  ASSERT_NE(m, nullptr) << error;
  MjDataPtr d(mj_makeData(m.get()));
  const double deg = kDeg;
  JointVector home = JointVector::Zero();
  home(kRailX) = 3.0;
  home(kA2) = -90.0 * deg;
  home(kA3) = 90.0 * deg;
  home(kA5) = 90.0 * deg;
  for (int i = 0; i < kNumJoints; ++i) {
    const std::string name(kJointNames[static_cast<std::size_t>(i)]);
    d->qpos[m->jnt_qposadr[mj_name2id(m.get(), mjOBJ_JOINT, name.c_str())]] = home(i);
  }
  mj_forward(m.get(), d.get());
  std::vector<mjtNum> mass(static_cast<std::size_t>(m->nv * m->nv));
  mj_fullM(m.get(), mass.data(), d->qM);
  const double w = 2.0 * kPi * kServoBandwidthHz;
  for (int i = 0; i < kNumJoints; ++i) {
    const JointInfo& joint = model().joint(i);
    SCOPED_TRACE(joint.name);
    const int dof = Dof(*m, i);
    const double inertia = mass[static_cast<std::size_t>(dof * m->nv + dof)];
    const std::string servo = "servo_" + joint.name;
    const int a = mj_name2id(mj_.get(), mjOBJ_ACTUATOR, servo.c_str());
    ASSERT_GE(a, 0);
    const double kp = mj_->actuator_gainprm[mjNGAIN * a];
    const double kv = -mj_->actuator_biasprm[mjNBIAS * a + 2];
    EXPECT_LE(Relative(kp, inertia * w * w), 0.01) << "I_eff " << inertia;
    EXPECT_LE(Relative(kv, 2.0 * kServoDampingRatio * inertia * w), 0.01) << "I_eff " << inertia;
    RecordProperty("effective_inertia_" + joint.name, testing::Sci(inertia));
  }
}

}  // namespace
}  // namespace stitchsim::sim
