// `verify --snapshots`: per rule family, the close-up shows what it is about. Each picture is
// rendered again here as a segmentation from what snapshots.json records (joints, camera,
// see-through geoms), with the render library directly: every subject (both bodies of a
// collision, the needles, the joint's link, the constraint) covers at least 0.5 % of the
// picture below the title bar, and is not hidden (at most half of what it covers drawn alone
// is behind something else; the subjects are drawn see-through over each other). Also: every
// picture carries a title bar; the overview is always written; a missing font is bad input.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app_test_support.h"
#include "stitchsim/render/renderer.h"
#include "stitchsim/render/scene_model.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;
using testing::RunCli;
using testing::ScratchDir;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

std::string Scene(const std::string& name) {
  return (kSource / "scenes" / (name + ".yaml")).string();
}

// Plans a programme with `plan_args` (after `plan`), verifies it with --snapshots; returns
// the snapshot folder.
fs::path Snapshots(const std::string& tag, const std::string& plan_args, const std::string& scene,
                   int expect_exit = 1) {
  const fs::path nc = ScratchDir() / (tag + ".nc"), dir = ScratchDir() / (tag + "_snaps");
  const auto plan = RunCli("plan " + plan_args + " -o " + nc.string(), tag + "_plan");
  EXPECT_EQ(plan.exit_code, 0) << plan.err;
  const auto v = RunCli("verify " + nc.string() + " --scene " + Scene(scene) + " --quiet" +
                            " --snapshots " + dir.string(),
                        tag + "_verify");
  EXPECT_EQ(v.exit_code, expect_exit) << v.err << v.out;
  return dir;
}

// Verifies a hand-written programme with --snapshots.
fs::path SnapshotsOf(const std::string& tag, const std::string& text, const std::string& scene) {
  const fs::path nc = ScratchDir() / (tag + ".nc"), dir = ScratchDir() / (tag + "_snaps");
  std::ofstream(nc) << text;
  const auto v = RunCli("verify " + nc.string() + " --scene " + Scene(scene) + " --quiet" +
                            " --snapshots " + dir.string(),
                        tag + "_verify");
  EXPECT_EQ(v.exit_code, 1) << v.err << v.out;
  return dir;
}

nlohmann::json Manifest(const fs::path& dir) {
  std::ifstream in(dir / "snapshots.json");
  if (!in) return nlohmann::json::object();
  return nlohmann::json::parse(in, nullptr, false);
}

const nlohmann::json* Picture(const nlohmann::json& manifest, const std::string& rule) {
  if (!manifest.contains("pictures")) return nullptr;
  for (const auto& p : manifest.at("pictures")) {
    if (p.at("rule").get<std::string>() == rule) return &p;
  }
  return nullptr;
}

int GeomId(const mjModel& m, const std::string& name) {
  return mj_name2id(&m, mjOBJ_GEOM, name.c_str());
}

// Below the title bar (the top 10 % of the picture): the pixels `solo` (a subject drawn alone)
// covers, and of those the ones where `full` (the picture's segmentation) shows a geom that
// is no subject.
std::pair<long, long> Covered(const render::Segmentation& solo, const render::Segmentation& full,
                              const std::vector<int>& subjects) {
  long covered = 0, hidden = 0;
  for (int y = solo.height / 10; y < solo.height; ++y) {
    for (int x = 0; x < solo.width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * solo.width + x;
      if (solo.label[p] < 0) continue;
      ++covered;
      const int l = full.label[p];
      if (l < 0) continue;
      const int g = full.geoms[static_cast<std::size_t>(l)];
      if (g >= 0 && std::find(subjects.begin(), subjects.end(), g) == subjects.end()) ++hidden;
    }
  }
  return {covered, hidden};
}

// The picture of `rule` in `dir`, rendered again as a segmentation: each subject with geoms,
// drawn alone, covers >= 0.5 % of the picture, and no more than half of that is covered by
// geoms that are no subject. Returns the names of the subjects checked.
std::vector<std::string> ExpectSubjectsVisible(const fs::path& dir, const std::string& rule,
                                               const std::string& scene_name) {
  const nlohmann::json manifest = Manifest(dir);
  const nlohmann::json* pic = Picture(manifest, rule);
  if (pic == nullptr) {
    ADD_FAILURE() << "no close-up of " << rule << " in " << manifest.dump();
    return {};
  }
  EXPECT_TRUE(fs::exists(dir / pic->at("file").get<std::string>()));
  DiagnosticSink sink;
  auto scene = scene::LoadScene(Scene(scene_name), sink);
  EXPECT_NE(scene, nullptr);
  if (!scene) return {};
  render::MjModelPtr model = render::LoadSceneModel(*scene, sink);
  model->vis.map.znear =
      static_cast<float>(pic->at("camera").at("znear_m").get<double>() / model->stat.extent);
  render::MjDataPtr data(mj_makeData(model.get()));
  const char* joints[] = {"rail_x", "a1", "a2", "a3", "a4", "a5", "a6", "rotator"};
  const auto q = pic->at("joints").get<std::vector<double>>();
  for (int j = 0; j < 8; ++j) {
    const int id = mj_name2id(model.get(), mjOBJ_JOINT, joints[j]);
    data->qpos[model->jnt_qposadr[id]] = q[static_cast<std::size_t>(j)];
  }
  mj_kinematics(model.get(), data.get());
  const int w = manifest.at("width").get<int>(), h = manifest.at("height").get<int>();
  std::string error;
  auto r = render::OffscreenRenderer::Create(model.get(), w, h, error);
  EXPECT_NE(r, nullptr) << error;
  if (!r) return {};
  render::CameraView view;
  const auto& cam = pic->at("camera");
  const auto at = cam.at("lookat_m").get<std::vector<double>>();
  view.lookat_m = Eigen::Vector3d(at[0], at[1], at[2]);
  view.distance_m = cam.at("distance_m").get<double>();
  view.azimuth_deg = cam.at("azimuth_deg").get<double>();
  view.elevation_deg = cam.at("elevation_deg").get<double>();
  render::DrawStyle style;
  for (const auto& n : pic->at("transparent_geoms")) {
    style.transparent.push_back(GeomId(*model, n.get<std::string>()));
  }
  const render::Segmentation seg = r->RenderSegmentation(data.get(), view, {}, style);
  std::vector<int> all_subjects;  // the subjects are drawn see-through: one may cover another
  for (const auto& s : pic->at("subjects")) {
    for (const auto& n : s.at("geoms"))
      all_subjects.push_back(GeomId(*model, n.get<std::string>()));
  }
  std::vector<std::string> checked;
  for (const auto& s : pic->at("subjects")) {
    std::vector<int> geoms;
    for (const auto& n : s.at("geoms")) geoms.push_back(GeomId(*model, n.get<std::string>()));
    if (geoms.empty()) continue;  // an overlay (the crossing marks): counted by verify itself
    render::DrawStyle alone;
    for (int g = 0; g < model->ngeom; ++g) {
      if (std::find(geoms.begin(), geoms.end(), g) == geoms.end()) alone.hidden.push_back(g);
    }
    const render::Segmentation solo = r->RenderSegmentation(data.get(), view, {}, alone);
    const auto [by_itself, hidden] = Covered(solo, seg, all_subjects);
    const std::string name = s.at("name").get<std::string>();
    EXPECT_GE(by_itself, w * h / 200) << rule << ": " << name << " covers too little";
    EXPECT_LE(2 * hidden, by_itself) << rule << ": " << name << " is hidden";
    EXPECT_GE(s.at("alone_pixels").get<long>(), w * h / 200) << rule << ": " << name;
    checked.push_back(name);
  }
  return checked;
}

// Every picture has a title bar: its top rows differ from the scene below (dark band).
void ExpectTitleBar(const fs::path& png) {
  render::Image img;
  std::string err;
  ASSERT_TRUE(render::ReadPng(png, img, err)) << err;
  long dark = 0, bright_text = 0;
  const int band = img.height / 40;  // inside the bar
  for (int y = 0; y < band; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const auto* p = &img.rgb[(static_cast<std::size_t>(y) * img.width + x) * 3];
      if (p[0] < 60 && p[1] < 60 && p[2] < 60) ++dark;
    }
  }
  for (int y = 0; y < img.height / 12; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const auto* p = &img.rgb[(static_cast<std::size_t>(y) * img.width + x) * 3];
      if (p[0] > 200 && p[1] > 200 && p[2] > 200) ++bright_text;
    }
  }
  EXPECT_GT(dark, band * img.width / 2) << png;
  EXPECT_GT(bright_text, 200) << png << ": no text in the title bar";
}

TEST(Snapshots, RailHitShowsTheHeadBodyAndTheRail) {
  const fs::path dir = Snapshots(
      "rail", "stitch --scene " + Scene("rail_hit") + " --path row --mode coupled", "rail_hit");
  const auto seen = ExpectSubjectsVisible(dir, "collision.robot_cell", "rail_hit");
  EXPECT_EQ(seen, (std::vector<std::string>{"head:head_body", "rail"}));
  ExpectTitleBar(dir / "collision.robot_cell.png");
  ExpectTitleBar(dir / "overview.png");
  const nlohmann::json manifest = Manifest(dir);
  const nlohmann::json* pic = Picture(manifest, "collision.robot_cell");
  ASSERT_NE(pic, nullptr);
  bool depth = false;
  for (const auto& l : pic->at("legend")) depth = depth || l.get<std::string>() == "depth 16.3 mm";
  EXPECT_TRUE(depth) << pic->at("legend").dump();
}

TEST(Snapshots, ConcaveCylinderShowsTheFeedModuleInTheMold) {
  const fs::path dir = Snapshots(
      "concave", "afp --scene " + Scene("concave_cylinder_small") + " --lay-angle 45 --incline 0",
      "concave_cylinder_small");
  const auto seen = ExpectSubjectsVisible(dir, "collision.head_mold", "concave_cylinder_small");
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], "head:feed_module");
  ExpectTitleBar(dir / "collision.head_mold.png");
  ExpectTitleBar(dir / "overview.png");
  // The laminate's thickness map (the course's ply is not one of the scene's: it lays no
  // thickness, and afp.fiber_angle does not judge it, so no angle map).
  ExpectTitleBar(dir / "laminate_thickness.png");
  EXPECT_FALSE(fs::exists(dir / "laminate_fiber_angle.png"));
}

TEST(Snapshots, CoupledCircleShowsTheNeedles) {
  const fs::path dir = Snapshots(
      "circle", "stitch --scene " + Scene("circle_8in") + " --mode coupled", "circle_8in");
  for (const char* rule : {"needle.side_force", "needle.rotation_in_preform"}) {
    const auto seen = ExpectSubjectsVisible(dir, rule, "circle_8in");
    EXPECT_EQ(seen, (std::vector<std::string>{"needles", "presser foot"})) << rule;
    ExpectTitleBar(dir / (std::string(rule) + ".png"));
  }
  const nlohmann::json manifest = Manifest(dir);
  const nlohmann::json* pic = Picture(manifest, "needle.side_force");
  ASSERT_NE(pic, nullptr);
  bool magnified = false;
  for (const auto& l : pic->at("legend")) {
    magnified =
        magnified || l.get<std::string>().find("drift after the walk, x") != std::string::npos;
  }
  EXPECT_TRUE(magnified) << pic->at("legend").dump();
}

TEST(Snapshots, StringerSeamShowsTheNeedleInTheStringerAndTheCrossing) {
  const fs::path dir =
      Snapshots("seam", "stitch --scene " + Scene("rs566_stringer_seam") + " --path seam",
                "rs566_stringer_seam");
  const auto seen = ExpectSubjectsVisible(dir, "collision.head_mold", "rs566_stringer_seam");
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[1], "constraint:stringer");
  ExpectTitleBar(dir / "collision.head_mold.png");
  // The seam also stitches into the stringer's footprint: the crossing from above.
  EXPECT_EQ(ExpectSubjectsVisible(dir, "constraint.crossing", "rs566_stringer_seam"),
            (std::vector<std::string>{"constraint:stringer"}));
  ExpectTitleBar(dir / "constraint.crossing.png");
  const nlohmann::json manifest = Manifest(dir);
  const nlohmann::json* crossing = Picture(manifest, "constraint.crossing");
  ASSERT_NE(crossing, nullptr);
  const auto& marks = crossing->at("subjects").at(1);
  EXPECT_EQ(marks.at("name").get<std::string>(), "crossing stitches");
  EXPECT_GE(marks.at("pixels").get<long>(), 100) << marks.dump();
}

constexpr const char* kFlatHead = "%\nG21 G90\nT1 M6\nG0 X0 Y0 Z0 A0 B0 C-90 U0 V0\nM10\n";

// The head tipped up past what a5 can reach (verify_test's programme): link_5 in view; the
// rail driven past its travel: the carriage.
TEST(Snapshots, JointLimitShowsTheJointsLink) {
  const fs::path dir = SnapshotsOf(
      "kin", std::string(kFlatHead) + "G1 X5 U5 V5 F1500\nG1 X10 A0 B150 C-90 U10 V10\nM30\n%\n",
      "flat_straight");
  EXPECT_EQ(ExpectSubjectsVisible(dir, "kin.joint_limit", "flat_straight"),
            (std::vector<std::string>{"link_5"}));
  ExpectTitleBar(dir / "kin.joint_limit.png");
  const fs::path rail = SnapshotsOf(
      "kin_rail", std::string(kFlatHead) + "G1 X5 U5 V5 F1500\nG1 X10 E15000 U10 V10\nM30\n%\n",
      "flat_straight");
  EXPECT_EQ(ExpectSubjectsVisible(rail, "kin.joint_limit", "flat_straight"),
            (std::vector<std::string>{"carriage"}));
}

TEST(Snapshots, PassingRunStillWritesTheOverview) {
  const fs::path dir = Snapshots(
      "pass", "stitch --scene " + Scene("flat_straight") + " --mode decoupled", "flat_straight", 0);
  EXPECT_TRUE(fs::exists(dir / "overview.png"));
  ExpectTitleBar(dir / "overview.png");
  EXPECT_TRUE(Manifest(dir).at("pictures").empty());
}

TEST(Snapshots, MissingFontIsBadInput) {
  const fs::path nc = ScratchDir() / "font.nc";
  ASSERT_EQ(
      RunCli("plan stitch --scene " + Scene("flat_straight") + " -o " + nc.string(), "font_plan")
          .exit_code,
      0);
  const std::string env = "STITCHSIM_FONT_DIR=" + (ScratchDir() / "no_fonts").string() + " ";
  const fs::path binary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";
  const fs::path err = ScratchDir() / "font_err.txt";
  const int status =
      std::system((env + binary.string() + " verify " + nc.string() + " --scene " +
                   Scene("flat_straight") + " --quiet --snapshots " +
                   (ScratchDir() / "font_snaps2").string() + " >/dev/null 2>" + err.string())
                      .c_str());
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2);
  const std::string text = testing::ReadText(err);
  EXPECT_NE(text.find("io-missing-file"), std::string::npos) << text;
  EXPECT_NE(text.find("DejaVuSans"), std::string::npos) << text;
}

}  // namespace
}  // namespace stitchsim::app
