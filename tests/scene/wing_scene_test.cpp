// The `wing` surface kind of a scene: the seed 002 wing read through the scene loader equals
// the geom loft, and bad input is reported at the scene entry's file:line (exit 2 from the
// command line).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "../geom/seed_wing.h"
#include "scene_test_support.h"
#include "stitchsim/common/files.h"
#include "stitchsim/geom/naca.h"
#include "stitchsim/geom/wing_surface.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;

fs::path Folder(const std::string& name) { return testing::Folder("wing_scene", name); }
using testing::Load;
using testing::Loaded;
using testing::ReadAll;
using testing::RunCli;
using testing::Write;

const std::string kPaths = "paths: [{name: a, type: line, from: [10, 10], to: [60, 10]}]\n";

// Scene head (5 lines); the surface map starts on line 6, `root` on 8, `tip` on 9, `span`
// on 10.
std::string SceneText(const std::string& units, const std::string& root, const std::string& tip,
                      const std::string& span, const std::string& extra = "") {
  return "stitchsim_scene: 1\nname: wing\nunits: " + units +
         "\nhead: afp\npart: {mount: table}\nsurface:\n  type: wing\n  root: " + root +
         "\n  tip: " + tip + "\n  span: " + span + "\n" + extra + kPaths;
}

std::string SeedScene(const std::string& extra = "") {
  return SceneText("mm", "{naca: \"23014\", chord: 2258.1}", "{naca: \"23012\", chord: 1130.3}",
                   "7310.1", extra);
}

TEST(WingScene, TheSeedWingIsTheLoftOfItsSections) {
  const fs::path dir = Folder("seed");
  Write(dir / "s.yaml", SeedScene());
  const Loaded r = Load(dir / "s.yaml");
  ASSERT_TRUE(r.scene) << r.message;
  ASSERT_TRUE(r.scene->surface);
  EXPECT_EQ(r.scene->surface->Kind(), "wing");
  std::string error;
  const std::optional<geom::Wing> wing = geom::Wing::Make(geom::testing::SeedWingSpec(), error);
  ASSERT_TRUE(wing) << error;
  const Eigen::Vector2d len = r.scene->surface->Domain().max;
  for (int i = 0; i <= 20; ++i) {
    for (const double eta : {0.0, 0.5, 1.0}) {
      const double s = i / 20.0;
      const Eigen::Vector3d p = r.scene->surface->Point({len.x() * s, len.y() * eta});
      EXPECT_LT((p - wing->Point(s, eta)).norm(), 0.01) << s << " " << eta;
    }
  }
}

// Issue 26 item 7: a ply's reference origin projects onto the skin it lies over, whatever the
// ply before it projected onto. Two plies near the trailing edge at mid-span (the skins 13 mm
// apart there), origins 10 mm out from the upper and then the lower skin: the second
// projection, started from the first's foot on the upper skin, stopped there (its local
// minimum 23 mm away was nearer than the coarse grid's nearest point) and the lower ply took
// the upper skin's normal, projecting its reference away from the wing. Second route: the
// closed-form loft's outward normal (naca.h); a ply's projection is minus its foot's normal.
TEST(WingScene, PlyReferenceProjectsOntoTheSkinItLiesOver) {
  std::string error;
  const std::optional<geom::Wing> wing = geom::Wing::Make(geom::testing::SeedWingSpec(), error);
  ASSERT_TRUE(wing) << error;
  constexpr double kUpperS = 0.05, kLowerS = 0.95, kEta = 0.5, kOut = 10.0;
  const auto origin = [&](double s) {
    const Eigen::Vector3d o = wing->Point(s, kEta) + kOut * wing->Normal(s, kEta);
    char buf[120];
    std::snprintf(buf, sizeof(buf), "[%.6f, %.6f, %.6f]", o.x(), o.y(), o.z());
    return std::string(buf);
  };
  const auto ply = [&](const std::string& name, double s) {
    return "  - name: " + name + "\n    angle_deg: 0\n    reference: {origin: " + origin(s) +
           ", direction: [0, 1, 0]}\n    boundary_uv: [[100, 3000], [300, 3000], [300, 4000], "
           "[100, 4000]]\n";
  };
  const fs::path dir = Folder("ply_skins");
  Write(dir / "s.yaml", SeedScene("  skin: full\n") + "plies:\n" + ply("upper_te", kUpperS) +
                            ply("lower_te", kLowerS));
  const Loaded r = Load(dir / "s.yaml");
  ASSERT_TRUE(r.scene) << r.message;
  ASSERT_EQ(r.scene->plies.size(), 2u);
  EXPECT_GT(r.scene->plies[0].projection.dot(-wing->Normal(kUpperS, kEta)), 0.999);
  EXPECT_GT(r.scene->plies[1].projection.dot(-wing->Normal(kLowerS, kEta)), 0.999)
      << r.scene->plies[1].projection.transpose();
}

TEST(WingScene, UnitsAnglesAndSkinAreRead) {
  const fs::path dir = Folder("options");
  // Inches and a string length with its own unit; the upper skin only, swept and twisted.
  Write(dir / "s.yaml",
        SceneText("in", "{naca: \"23014\", chord: 88.9}", "{naca: \"2412\", chord: \"1 m\"}", "200",
                  "  sweep_deg: 10\n  dihedral_deg: 3\n  twist_deg: 2\n  skin: upper\n"
                  "  trailing_edge: open\n"));
  const Loaded r = Load(dir / "s.yaml");
  ASSERT_TRUE(r.scene) << r.message;
  geom::WingSpec spec;
  spec.root_code = "23014";
  spec.root_chord_mm = 88.9 * 25.4;
  spec.tip_code = "2412";
  spec.tip_chord_mm = 1000;
  spec.span_mm = 200 * 25.4;
  spec.sweep_rad = 10 * kPi / 180;
  spec.dihedral_rad = 3 * kPi / 180;
  spec.washout_rad = 2 * kPi / 180;
  spec.trailing_edge = geom::TrailingEdge::kOpen;
  std::string error;
  const std::optional<geom::Wing> wing = geom::Wing::Make(spec, error);
  ASSERT_TRUE(wing) << error;
  const Eigen::Vector2d len = r.scene->surface->Domain().max;
  for (int i = 0; i <= 10; ++i) {
    const double s = 0.05 * i;  // upper skin: s in [0, 0.5] over u in [0, Lu]
    const Eigen::Vector3d p = r.scene->surface->Point({len.x() * 2 * s, len.y() * 0.3});
    EXPECT_LT((p - wing->Point(s, 0.3)).norm(), 0.01) << s;
  }
  EXPECT_GT(r.scene->surface->Normal(len / 2).z(), 0.9);  // the upper skin faces up
}

TEST(WingScene, BadWingsAreReportedAtTheirLine) {
  const fs::path dir = Folder("bad");
  struct Case {
    std::string text, code, what;
    int line;
  };
  const std::string root = "{naca: \"23014\", chord: 2258.1}";
  const std::string tip = "{naca: \"23012\", chord: 1130.3}";
  const Case cases[] = {
      {SceneText("mm", "{naca: \"23014\", chord: 0}", tip, "7310"), "scene-out-of-range",
       "root.chord must be positive", 8},
      {SceneText("mm", root, "{naca: \"23012\", chord: -3}", "7310"), "scene-out-of-range",
       "tip.chord must be positive", 9},
      {SceneText("mm", root, tip, "0"), "scene-out-of-range", "span must be positive", 10},
      {SceneText("mm", "{naca: \"123456789\", chord: 2258.1}", tip, "7310"), "scene-bad-value",
       "4 or 5 digits", 8},
      {SceneText("mm", root, "{naca: \"26012\", chord: 1130.3}", "7310"), "scene-bad-value",
       "camber position", 9},
      {SceneText("mm", root, "{naca: 23012}", "7310"), "scene-missing-key", "chord", 9},
      {SceneText("mm", root, tip, "7310", "  sweep_deg: 90\n"), "scene-out-of-range", "sweep_deg",
       11},
      {SceneText("mm", root, tip, "7310", "  skin: inner\n"), "scene-bad-value", "skin", 11},
      {SceneText("mm", root, tip, "7310", "  chord: 3\n"), "scene-unknown-key", "chord", 11},
      {"stitchsim_scene: 1\nname: wing\nunits: mm\nhead: afp\npart: {mount: table}\n"
       "surface:\n  type: wing\n  root: " +
           root + "\n  span: 7310\n" + kPaths,
       "scene-missing-key", "tip", 7},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    Write(dir / "s.yaml", c.text);
    const Loaded r = Load(dir / "s.yaml");
    EXPECT_FALSE(r.scene);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_EQ(r.line, c.line) << r.message;
    EXPECT_NE(r.message.find(c.what), std::string::npos) << r.message;
  }
}

TEST(WingScene, TheCommandLineExitsTwoAtTheBadEntry) {
  const fs::path dir = Folder("cli");
  const fs::path scene = dir / "bad.yaml";
  Write(scene, SceneText("mm", "{naca: \"230120000\", chord: 2258.1}",
                         "{naca: \"23012\", chord: 1130.3}", "7310"));
  Write(dir / "p.nc", "G21\nM30\n");
  const fs::path err = dir / "err.txt";
  EXPECT_EQ(RunCli("verify " + (dir / "p.nc").string() + " --scene " + scene.string(), err), 2);
  std::string text = ReadAll(err);
  EXPECT_NE(text.find(scene.string() + ":8:"), std::string::npos) << text;
  EXPECT_NE(text.find("4 or 5 digits"), std::string::npos) << text;
  EXPECT_EQ(
      RunCli("plan afp --scene " + scene.string() + " --lay-angle 0 -o " + (dir / "a.nc").string(),
             err),
      2);
  text = ReadAll(err);
  EXPECT_NE(text.find(scene.string() + ":8:"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(dir / "a.nc"));
}

// scenes/naca_wing.yaml: an AFP course over the upper skin at mid-span plans and verifies
// clean (the reachable window its comments name).
TEST(WingScene, TheBundledWingVerifiesACourseOnItsUpperSkin) {
  const fs::path dir = Folder("bundled");
  const fs::path scene = fs::path(STITCHSIM_SOURCE_DIR) / "scenes" / "naca_wing.yaml";
  const fs::path log = dir / "log.txt";
  ASSERT_EQ(RunCli("plan afp --scene " + scene.string() + " --path upper_mid -o " +
                       (dir / "c.nc").string(),
                   log),
            0)
      << ReadAll(log);
  EXPECT_EQ(RunCli("verify " + (dir / "c.nc").string() + " --scene " + scene.string(), log), 0)
      << ReadAll(log);
  EXPECT_NE(ReadAll(log).find("PASS"), std::string::npos) << ReadAll(log);
}

// A projection must not depend on what was projected before. The wing's skin wraps round its
// section, so the distance from a point just off the upper skin has a second local minimum on
// the lower skin; a descent started from the previous call's answer there once ended on it
// (found when a reordered AFP programme moved from one course to a far one: afp.compaction saw
// the tool point 166 mm below the surface). Each point is projected after a far one and fresh.
TEST(WingScene, ProjectionDoesNotDependOnThePreviousOne) {
  DiagnosticSink sink;
  const auto scene = LoadScene(DataDir() / "scenes" / "naca_wing.yaml", sink);
  ASSERT_TRUE(scene);
  const geom::Surface& s = *scene->surface;
  const geom::Domain2 d = s.Domain();
  int compared = 0;
  for (int i = 1; i < 8; ++i) {
    for (int k = 1; k < 8; ++k) {
      const Eigen::Vector2d uv(d.min.x() + (d.max.x() - d.min.x()) * i / 8.0,
                               d.min.y() + (d.max.y() - d.min.y()) * k / 8.0);
      const Eigen::Vector3d p = s.Point(uv) + 20.0 * s.Normal(uv);  // 20 mm off the skin
      // First from far away: the mirror point across the domain.
      const Eigen::Vector2d far(d.max.x() + d.min.x() - uv.x(), d.max.y() + d.min.y() - uv.y());
      (void)s.Project(s.Point(far));
      const geom::SurfaceProjection after_far = s.Project(p);
      (void)s.Project(s.Point(uv));
      const geom::SurfaceProjection after_near = s.Project(p);
      EXPECT_NEAR(after_far.signed_distance_mm, 20.0, 1e-6) << uv.transpose();
      EXPECT_NEAR(after_near.signed_distance_mm, 20.0, 1e-6) << uv.transpose();
      EXPECT_LT((after_far.point - after_near.point).norm(), 1e-6) << uv.transpose();
      ++compared;
    }
  }
  EXPECT_EQ(compared, 49);
}

}  // namespace
}  // namespace stitchsim::scene
