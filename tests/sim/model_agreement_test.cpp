// Two routes to one answer: our URDF forward kinematics against MuJoCo's on the MJCF cell.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <memory>
#include <random>
#include <string>

#include "sim_test_support.h"

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

  std::unique_ptr<mjModel, MjModelDeleter> mj_;
  std::unique_ptr<mjData, MjDataDeleter> data_;
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

}  // namespace
}  // namespace stitchsim::sim
