// The exported cell, posed by the forward kinematics the HTML page runs (body offsets, a hinge
// turning about its axis through its anchor by q - ref, a slide moving along its axis), puts
// every geom where MuJoCo's mj_kinematics puts it; mesh thinning keeps a mesh's extent and
// meets its face budget.
#include "stitchsim/render/cell_export.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "stitchsim/render/scene_model.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::render {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Eigen::Vector3d V(const json& a) {
  return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()};
}
Eigen::Quaterniond Q(const json& a) {
  return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>(), a[3].get<double>()};
}

const std::array<std::string, 8> kJoints = {"rail_x", "a1", "a2", "a3",
                                            "a4",     "a5", "a6", "rotator"};

TEST(CellExportTest, PagePosingEqualsMujocoKinematicsForEveryGeom) {
  DiagnosticSink sink;
  auto scene = scene::LoadScene(fs::path(STITCHSIM_SOURCE_DIR) / "scenes/circle_8in.yaml", sink);
  ASSERT_NE(scene, nullptr);
  MjModelPtr model = LoadSceneModel(*scene, sink);
  ASSERT_NE(model, nullptr);
  CellExportOptions o;
  o.joints = kJoints;
  std::string error;
  const json cell = ExportCell(*model, o, error);
  ASSERT_FALSE(cell.is_null()) << error;
  ASSERT_EQ(cell["bodies"].size(), static_cast<std::size_t>(model->nbody - 1));
  MjDataPtr data(mj_makeData(model.get()));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-1.5, 1.5);
  std::vector<double> q(8);
  for (int j = 0; j < 8; ++j) {
    q[static_cast<std::size_t>(j)] = j == 0 ? 2.0 : angle(rng);
    const int id =
        mj_name2id(model.get(), mjOBJ_JOINT, kJoints[static_cast<std::size_t>(j)].c_str());
    data->qpos[model->jnt_qposadr[id]] = q[static_cast<std::size_t>(j)];
  }
  mj_kinematics(model.get(), data.get());
  std::vector<Eigen::Isometry3d> world;
  int geoms_checked = 0;
  for (std::size_t b = 0; b < cell["bodies"].size(); ++b) {
    const json& body = cell["bodies"][b];
    const int parent = body["parent"].get<int>();
    Eigen::Isometry3d t =
        parent < 0 ? Eigen::Isometry3d::Identity() : world[static_cast<std::size_t>(parent)];
    t.translate(V(body["pos"]));
    t.rotate(Q(body["quat"]).normalized());
    if (!body["joint"].is_null()) {
      const json& j = body["joint"];
      const double v = q[j["index"].get<std::size_t>()] - j["ref"].get<double>();
      const Eigen::Vector3d axis = V(j["axis"]).normalized(), anchor = V(j["pos"]);
      if (j["type"] == "hinge") {
        t.translate(anchor);
        t.rotate(Eigen::AngleAxisd(v, axis));
        t.translate(-anchor);
      } else {
        t.translate(v * axis);
      }
    }
    world.push_back(t);
    for (const json& g : body["geoms"]) {
      const int id = mj_name2id(model.get(), mjOBJ_GEOM, g["name"].get<std::string>().c_str());
      if (id < 0) continue;  // unnamed geoms: checked through their named neighbours
      const Eigen::Vector3d p = t * V(g["pos"]);
      const Eigen::Vector3d mj(data->geom_xpos[3 * id], data->geom_xpos[3 * id + 1],
                               data->geom_xpos[3 * id + 2]);
      EXPECT_LT((p - mj).norm(), 1e-9) << g["name"];
      ++geoms_checked;
    }
    // The body's own frame too.
    const int bid = static_cast<int>(b) + 1;
    const Eigen::Vector3d mj(data->xpos[3 * bid], data->xpos[3 * bid + 1], data->xpos[3 * bid + 2]);
    EXPECT_LT((t.translation() - mj).norm(), 1e-9) << body["name"];
  }
  EXPECT_GE(geoms_checked, 5);
  EXPECT_GE(cell["part_body"].get<int>(), 0);
  EXPECT_EQ(cell["bodies"][cell["part_body"].get<std::size_t>()]["name"], "part");
}

TEST(CellExportTest, ThinnedMeshMeetsItsBudgetAndKeepsItsExtent) {
  // A 200 x 200 grid of squares (80000 triangles) on z = x * y.
  const int n = 200;
  std::vector<float> v;
  std::vector<int> f;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const float x = static_cast<float>(i) / n, y = static_cast<float>(j) / n;
      v.insert(v.end(), {x, y, x * y});
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      f.insert(f.end(), {a, b, d, a, d, c});
    }
  }
  const ThinnedMesh same = ThinMesh(v.data(), static_cast<int>(v.size() / 3), f.data(),
                                    static_cast<int>(f.size() / 3), 100000);
  EXPECT_EQ(same.faces.size(), f.size());
  const ThinnedMesh t = ThinMesh(v.data(), static_cast<int>(v.size() / 3), f.data(),
                                 static_cast<int>(f.size() / 3), 5000);
  EXPECT_LE(t.faces.size() / 3, 5000u);
  EXPECT_GE(t.faces.size() / 3, 1000u);  // not thinned to nothing
  float lo = 1, hi = 0;
  for (std::size_t k = 0; k < t.vertices.size(); k += 3) {
    lo = std::min(lo, t.vertices[k]);
    hi = std::max(hi, t.vertices[k]);
    // Merged vertices are means of points on the surface: near it.
    EXPECT_NEAR(t.vertices[k + 2], t.vertices[k] * t.vertices[k + 1], 0.01f);
  }
  EXPECT_LT(lo, 0.02f);
  EXPECT_GT(hi, 0.98f);
  for (std::uint32_t idx : t.faces) EXPECT_LT(idx, t.vertices.size() / 3);
}

}  // namespace
}  // namespace stitchsim::render
