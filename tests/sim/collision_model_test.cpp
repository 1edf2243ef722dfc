// The collision model is shared, the per-query data is not (docs/collision.md, "Model and
// data"): worlds made by Share() answer as the world they came from, also from two threads
// at once, in any order of queries. Real FCL and MuJoCo.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <thread>
#include <vector>

#include "sim_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/collision.h"

namespace stitchsim::sim {
namespace {

// Joints with the head over random points of the part, from 20 mm into it to 40 mm above,
// turned at random: clear poses, near misses and contacts.
std::vector<JointVector> PosesOverThePart(const CellSetup& cell, const geom::Surface& s,
                                          int count) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const geom::Domain2 dom = s.Domain();
  std::vector<JointVector> out;
  while (static_cast<int>(out.size()) < count) {
    const Eigen::Vector2d uv =
        dom.min + (dom.max - dom.min).cwiseProduct(Eigen::Vector2d(u01(rng), u01(rng)));
    const double yaw = 2 * kPi * u01(rng);
    const Eigen::Vector3d n = s.Normal(uv);
    const Eigen::Vector3d t = s.Jacobian(uv).col(0).normalized();
    const Eigen::Vector3d y = (std::cos(yaw) * t + std::sin(yaw) * n.cross(t)).normalized();
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
    tool.translation() = s.Point(uv) + (-20.0 + 60.0 * u01(rng)) * n;
    tool.linear().col(2) = n;
    tool.linear().col(1) = y;
    tool.linear().col(0) = y.cross(n);
    const ToolPoseSolution sol = SolveToolPose(cell, tool, 0.0, std::nullopt, nullptr);
    if (sol.ik.ok()) out.push_back(sol.ik.joints);
  }
  return out;
}

void ExpectSameResult(const CollisionResult& a, const CollisionResult& b, std::size_t pose) {
  ASSERT_EQ(a.contacts.size(), b.contacts.size()) << "pose " << pose;
  for (std::size_t k = 0; k < a.contacts.size(); ++k) {
    EXPECT_EQ(a.contacts[k].body_a, b.contacts[k].body_a) << "pose " << pose;
    EXPECT_EQ(a.contacts[k].body_b, b.contacts[k].body_b) << "pose " << pose;
    EXPECT_EQ(a.contacts[k].depth_m, b.contacts[k].depth_m) << "pose " << pose;
    EXPECT_EQ(a.contacts[k].point_world_m, b.contacts[k].point_world_m) << "pose " << pose;
  }
  EXPECT_EQ(a.min_clearance_m, b.min_clearance_m) << "pose " << pose;
  EXPECT_EQ(a.error, b.error) << "pose " << pose;
}

TEST(CollisionModelTest, SharedWorldsAnswerAsTheFirstFromTwoThreads) {
  DiagnosticSink sink;
  const auto scene = scene::LoadScene(
      std::filesystem::path(STITCHSIM_SOURCE_DIR) / "scenes" / "rs566_stringer_seam.yaml", sink);
  ASSERT_TRUE(scene) << testing::FormatAll(sink);
  const auto robot = LoadRobotModel(scene->cell_urdf, sink);
  ASSERT_TRUE(robot) << testing::FormatAll(sink);
  const auto world = CollisionWorld::Create(*scene, *robot, sink);
  ASSERT_TRUE(world) << testing::FormatAll(sink);
  const std::vector<JointVector> poses =
      PosesOverThePart(MakeCellSetup(*robot, *scene), *scene->surface, 300);

  std::vector<CollisionResult> expected;
  int with_contacts = 0;
  for (const JointVector& q : poses) {
    expected.push_back(world->Check(q, {}));
    with_contacts += expected.back().contacts.empty() ? 0 : 1;
  }
  EXPECT_GE(with_contacts, 30);
  EXPECT_LE(with_contacts, 270);

  // Both threads made before either starts (Share() touches the shared geometry's boxes).
  std::vector<std::unique_ptr<CollisionWorld>> shared;
  shared.push_back(world->Share());
  shared.push_back(world->Share());
  std::vector<std::vector<CollisionResult>> got(2, std::vector<CollisionResult>(poses.size()));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      for (std::size_t k = 0; k < poses.size(); ++k) {
        const std::size_t i = t == 0 ? k : poses.size() - 1 - k;  // the second one backwards
        got[t][i] = shared[t]->Check(poses[i], {});
      }
    });
  }
  for (auto& th : threads) th.join();
  for (std::size_t t = 0; t < 2; ++t) {
    for (std::size_t i = 0; i < poses.size(); ++i) ExpectSameResult(got[t][i], expected[i], i);
  }
  EXPECT_EQ(shared[0]->MaxPointTravel(poses[0], poses[1]),
            world->MaxPointTravel(poses[0], poses[1]));
}

}  // namespace
}  // namespace stitchsim::sim
