// `stitchsim render` on every bundled scene: a real PNG, not blank, with the robot, the
// head, the mold and the path in view (pixel coverage from a segmentation render of the
// same view).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stitchsim/render/renderer.h"
#include "stitchsim/render/scene_model.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::render {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kBinary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";

int RunCli(const std::string& args) {
  const std::string cmd = kBinary.string() + " " + args + " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class RenderEveryScene : public ::testing::TestWithParam<std::string> {};

TEST_P(RenderEveryScene, PngShowsRobotHeadMoldAndPath) {
  const std::string name = GetParam();
  const fs::path out = fs::temp_directory_path() / ("stitchsim_render_" + name);
  fs::create_directories(out);
  const fs::path png = out / "overview.png";
  const fs::path cov = out / "coverage.json";
  fs::remove(png);
  ASSERT_EQ(RunCli("render --scene " + (kSource / "scenes" / (name + ".yaml")).string() + " -o " +
                   png.string() + " --width 800 --height 600 --coverage-json " + cov.string()),
            0);
  Image img;
  std::string err;
  ASSERT_TRUE(ReadPng(png, img, err)) << err;
  EXPECT_EQ(img.width, 800);
  EXPECT_EQ(img.height, 600);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(cov));
  EXPECT_GT(j["rgb_stddev"].get<double>(), 10.0) << "blank image";
  const auto& px = j["pixels"];
  auto count = [&](const char* k) { return px.contains(k) ? px[k].get<long>() : 0L; };
  const long total = 800L * 600L;
  EXPECT_GT(count("robot"), total / 50) << j.dump();
  EXPECT_GT(count("head"), 300) << j.dump();
  EXPECT_GT(count("mold") + count("preform"), 500) << j.dump();
  EXPECT_GT(count("path"), 5) << j.dump();
  EXPECT_GT(count("rail"), total / 50) << j.dump();
  EXPECT_LT(count("background"), total / 2) << j.dump();
}

// Every bundled scene (scenes/*.yaml).
std::vector<std::string> BundledScenes() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(kSource / "scenes")) {
    if (e.path().extension() == ".yaml") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Scenes, RenderEveryScene, ::testing::ValuesIn(BundledScenes()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

TEST(Render, HeadViewIsAClosePicture) {
  const fs::path png = fs::temp_directory_path() / "stitchsim_render_head.png";
  const fs::path cov = fs::temp_directory_path() / "stitchsim_render_head.json";
  ASSERT_EQ(RunCli("render --scene " + (kSource / "scenes/circle_8in.yaml").string() +
                   " --view head -o " + png.string() +
                   " --width 640 --height 480 --coverage-json " + cov.string()),
            0);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(cov));
  EXPECT_GT(j["pixels"]["head"].get<long>(), 640L * 480L / 20) << j.dump();
}

TEST(Render, BadInputExitsTwoAndWritesNothing) {
  const fs::path png = fs::temp_directory_path() / "stitchsim_render_bad.png";
  fs::remove(png);
  EXPECT_EQ(RunCli("render --scene /nonexistent.yaml -o " + png.string()), 2);
  EXPECT_EQ(RunCli("render --scene " + (kSource / "scenes/circle_8in.yaml").string() + " -o " +
                   png.string() + " --width 0"),
            2);
  EXPECT_EQ(RunCli("render --scene " + (kSource / "scenes/circle_8in.yaml").string() + " -o " +
                   png.string() + " --view sideways"),
            2);
  EXPECT_FALSE(fs::exists(png));
}

TEST(SceneModel, ComposedModelCompilesForEveryHead) {
  for (const char* head : {"rs535", "rs566", "afp"}) {
    const fs::path p =
        fs::temp_directory_path() / (std::string("stitchsim_head_") + head + ".yaml");
    std::ofstream(p) << "stitchsim_scene: 1\nname: h\nunits: mm\nhead: " << head
                     << "\npart: {mount: rotator}\nsurface: {type: plane, size: [500, 500]}\n"
                        "paths: [{name: a, type: line, from: [0, 0], to: [100, 0]}]\n";
    DiagnosticSink sink;
    auto scene = scene::LoadScene(p, sink);
    ASSERT_NE(scene, nullptr);
    MjModelPtr m = LoadSceneModel(*scene, sink);
    for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
    ASSERT_NE(m, nullptr);
    // The head's tool_point site equals the head spec's tool frame (flange frame).
    const int site = mj_name2id(m.get(), mjOBJ_SITE, "tool_point");
    ASSERT_GE(site, 0);
    const Eigen::Vector3d pos(m->site_pos[3 * site], m->site_pos[3 * site + 1],
                              m->site_pos[3 * site + 2]);
    const Eigen::Quaterniond q(m->site_quat[4 * site], m->site_quat[4 * site + 1],
                               m->site_quat[4 * site + 2], m->site_quat[4 * site + 3]);
    EXPECT_LT((pos - scene->head.flange_to_tool_m.translation()).norm(), 1e-9) << head;
    EXPECT_LT(
        Eigen::AngleAxisd(q.toRotationMatrix().transpose() * scene->head.flange_to_tool_m.linear())
            .angle(),
        1e-9)
        << head;
    // The part rides on the rotator body.
    const int part = mj_name2id(m.get(), mjOBJ_BODY, "part");
    ASSERT_GE(part, 0);
    EXPECT_EQ(std::string(mj_id2name(m.get(), mjOBJ_BODY, m->body_parentid[part])), "rotator");
  }
}

// A head spec's envelope holds for its MJCF geometry: every geom reaching lower than
// height_mm above the tool point lies within radius_mm of the tool z axis.
TEST(SceneModel, HeadEnvelopeContainsTheLowGeometry) {
  int heads = 0;
  for (const char* head : {"rs535", "rs566", "afp"}) {
    DiagnosticSink sink;
    const auto spec =
        scene::LoadHeadSpec(kSource / "models/heads" / (std::string(head) + ".yaml"), sink);
    ASSERT_TRUE(spec) << head;
    if (!spec->envelope) continue;
    ++heads;
    char error[512] = {0};
    MjModelPtr m(mj_loadXML(spec->mjcf.string().c_str(), nullptr, error, sizeof(error)));
    ASSERT_NE(m, nullptr) << error;
    MjDataPtr d(mj_makeData(m.get()));
    mj_kinematics(m.get(), d.get());
    const Eigen::Isometry3d tool_inv = spec->flange_to_tool_m.inverse();
    int low = 0;
    for (int g = 0; g < m->ngeom; ++g) {
      const Eigen::Vector3d c(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1],
                              d->geom_xpos[3 * g + 2]);
      Eigen::Matrix3d r;
      for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = d->geom_xmat[9 * g + i];
      const Eigen::Vector3d sz(m->geom_size[3 * g], m->geom_size[3 * g + 1],
                               m->geom_size[3 * g + 2]);
      // Points whose hull bounds the geom, plus a radius to add around each.
      std::vector<Eigen::Vector3d> pts;
      double pad = 0.0;
      if (m->geom_type[g] == mjGEOM_BOX) {
        for (int k = 0; k < 8; ++k) {
          pts.push_back(c + r * Eigen::Vector3d((k & 1) ? sz.x() : -sz.x(),
                                                (k & 2) ? sz.y() : -sz.y(),
                                                (k & 4) ? sz.z() : -sz.z()));
        }
      } else if (m->geom_type[g] == mjGEOM_CAPSULE || m->geom_type[g] == mjGEOM_CYLINDER) {
        pts = {c + r * Eigen::Vector3d(0, 0, sz.y()), c - r * Eigen::Vector3d(0, 0, sz.y())};
        pad = sz.x();
      } else {
        ASSERT_EQ(m->geom_type[g], mjGEOM_SPHERE) << head;
        pts = {c};
        pad = sz.x();
      }
      double lowest = 1e9, widest = 0.0;
      for (const auto& p : pts) {
        const Eigen::Vector3d t = tool_inv * p * 1000.0;  // tool frame, mm
        lowest = std::min(lowest, t.z() - pad * 1000.0);
        widest = std::max(widest, t.head<2>().norm() + pad * 1000.0);
      }
      if (lowest >= spec->envelope->height_mm - 1e-9) continue;
      ++low;
      EXPECT_LE(widest, spec->envelope->radius_mm)
          << head << " geom " << mj_id2name(m.get(), mjOBJ_GEOM, g) << " reaches " << widest
          << " mm from the tool axis at " << lowest << " mm above the tool point";
    }
    EXPECT_GE(low, 2) << head;  // the foot and the needles at least
  }
  EXPECT_GE(heads, 1);
}

}  // namespace
}  // namespace stitchsim::render
