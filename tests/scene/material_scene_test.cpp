// `materials:` in a scene and a ply's `material:` (issue 29): thickness in the scene unit,
// areal weight in g/m^2, read into the plies; the defaults (assumptions) without one; every
// bad material or reference refused at its file:line.
#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

// 17 lines, then `plies:` at line 18 with one ply per line from 19, then `extra`.
std::string SceneText(const std::string& units, const std::string& plies,
                      const std::string& extra) {
  return "stitchsim_scene: 1\nname: materials\nunits: " + units +
         "\nhead: afp\npart:\n  mount: table\n  position: [0, -400, 50]\nsurface:\n"
         "  type: plane\n  size: [600, 400]\npreform:\n  thickness: 2\npaths:\n  - name: row\n"
         "    type: line\n    from: [0, 0]\n    to: [100, 0]\nplies:\n" +
         plies + extra;
}

std::string Ply(const std::string& name, const std::string& rest = "") {
  return "  - {name: " + name + ", reference: {origin: [0, 0, 50], direction: [1, 0, 0]}, " +
         "boundary_uv: [[0, 0], [100, 0], [100, 100]]" + rest + "}\n";
}

testing::Loaded Load(const std::string& text) {
  return testing::Load(testing::WriteTemp("material_scene", "s.yaml", text));
}

TEST(SceneMaterials, PliesTakeTheirMaterialsValues) {
  const testing::Loaded r =
      Load(SceneText("mm", Ply("a", ", material: im7") + Ply("b"),
                     "materials:\n  - {name: im7, ply_thickness: 0.25, areal_weight_g_m2: 190}\n"));
  ASSERT_TRUE(r.scene) << r.code << " " << r.message;
  ASSERT_EQ(r.scene->materials.size(), 1u);
  EXPECT_EQ(r.scene->materials[0].where.line, 22);  // two plies: `materials:` at 21
  const PlySpec& a = r.scene->plies[0];
  EXPECT_EQ(a.material, "im7");
  EXPECT_EQ(a.thickness_mm, 0.25);
  EXPECT_EQ(a.areal_weight_g_m2, 190.0);
  const PlySpec& b = r.scene->plies[1];  // no material: the assumed defaults
  EXPECT_EQ(b.material, "");
  EXPECT_EQ(b.thickness_mm, 0.18);
  EXPECT_EQ(b.areal_weight_g_m2, 300.0);
}

TEST(SceneMaterials, ThicknessIsInTheSceneUnit) {
  const testing::Loaded r =
      Load(SceneText("in", Ply("a", ", material: m"),
                     "materials:\n  - {name: m, ply_thickness: 0.01, areal_weight_g_m2: 300}\n"));
  ASSERT_TRUE(r.scene) << r.code << " " << r.message;
  EXPECT_NEAR(r.scene->plies[0].thickness_mm, 0.254, 1e-12);
}

TEST(SceneMaterials, EveryBadMaterialIsReportedAtItsLine) {
  struct Case {
    std::string plies, materials, code;
    int line;
  };
  const std::string head = "materials:\n";
  for (const Case& c : {
           Case{Ply("a", ", material: t300"),
                head + "  - {name: m, ply_thickness: 0.2, "
                       "areal_weight_g_m2: 300}\n",
                "scene-bad-ply", 19},
           Case{Ply("a"), head + "  - {name: m, ply_thickness: -0.2, areal_weight_g_m2: 300}\n",
                "scene-out-of-range", 21},
           Case{Ply("a"), head + "  - {name: m, ply_thickness: 0, areal_weight_g_m2: 300}\n",
                "scene-out-of-range", 21},
           Case{Ply("a"), head + "  - {name: m, ply_thickness: 0.2, areal_weight_g_m2: 0}\n",
                "scene-out-of-range", 21},
           Case{Ply("a"), head + "  - {name: m, ply_thickness: 0.2, areal_weight_g_m2: -5}\n",
                "scene-out-of-range", 21},
           Case{Ply("a"), head + "  - {name: m, areal_weight_g_m2: 300}\n", "scene-missing-key",
                21},
           Case{Ply("a"),
                head + "  - {name: m, ply_thickness: 0.2, areal_weight_g_m2: 300}\n" +
                    "  - {name: m, ply_thickness: 0.3, areal_weight_g_m2: 300}\n",
                "scene-bad-material", 22},
           Case{Ply("a"), "materials: []\n", "scene-bad-material", 20},
       }) {
    SCOPED_TRACE(c.materials);
    const testing::Loaded r = Load(SceneText("mm", c.plies, c.materials));
    EXPECT_FALSE(r.scene);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_EQ(r.line, c.line) << r.message;
  }
}

}  // namespace
}  // namespace stitchsim::scene
