// `laminates:` in a scene (docs/scene-format.md, issue 29): every field read into
// scene::LaminateSpec (a scene in inches against the hand conversion, 25.4 mm per inch), the
// inline plies appended to Scene::plies, and every scene-bad-laminate problem at its line.

#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

using testing::WriteTemp;

// 17 lines; `plies:` is line 18, the four plies lines 19 to 22, `laminates:` line 23 and the
// first laminate line 24. A plane 600 x 400 mm centred on the part origin, at z = 0.
std::string LaminateScene(const std::string& unit, double mm, const std::string& laminates) {
  const auto n = [&](double v_mm) { return std::to_string(v_mm / mm); };
  std::string text = "stitchsim_scene: 1\nname: laminates\nunits: " + unit +
                     "\nhead: afp\npart:\n  mount: table\n  position: [0, " + n(-400) + ", " +
                     n(50) + "]\nsurface:\n  type: plane\n  size: [" + n(600) + ", " + n(400) +
                     "]\npreform:\n  thickness: " + n(2) +
                     "\npaths:\n  - name: row\n    type: line\n    from: [0, 0]\n    to: [" +
                     n(100) + ", 0]\nplies:\n";
  for (const char* ply : {"p0", "p45", "pm45", "p90"}) {
    text += "  - {name: " + std::string(ply) + ", reference: {origin: [0, 0, " + n(50) +
            "], direction: [1, 0, 0]}, boundary_uv: [[0, 0], [" + n(100) + ", 0], [0, " + n(100) +
            "]]}\n";
  }
  return text + "laminates:\n" + laminates;
}

// Lines 24 to 27 (+ the stack from line 28 on).
std::string Laminate(const std::string& name, const std::string& rosette,
                     const std::string& stagger, const std::string& stack) {
  return "  - name: " + name + "\n    rosette: " + rosette + "\n    stagger: " + stagger +
         "\n    stack:" + stack;
}
const char* kRosette = "{origin: [0, 0, 50], direction: [1, 0, 0]}";
const char* kStagger = "{offset: 5, plies_before_repeat: 2}";
// Lines 28 to 30.
const char* kStack =
    "\n      - p0\n      - {ply: p45, thickness: 0.18}\n"
    "      - {angle_deg: 90, boundary_uv: [[0, 0], [50, 0], [0, 50]]}\n";

testing::Loaded LoadText(const std::string& text) {
  return testing::Load(WriteTemp("laminate_scene", "s.yaml", text));
}

// Four named plies and two inline ones (one on the rosette, one with its own reference), in
// inches: every length arrives in mm as 25.4 times the file's number.
TEST(SceneLaminates, EveryFieldIsReadInMillimetres) {
  const std::string stack =
      "\n      - p0\n"
      "      - {ply: p45, material: T700, thickness: 0.0072}\n"
      "      - {angle_deg: 90, boundary_uv: [[0, 0], [2, 0], [0, 2]], material: IM7, "
      "thickness: 0.01}\n"
      "      - pm45\n"
      "      - p90\n"
      "      - {angle_deg: -30, reference: {origin: [1, 1, 1], direction: [1, 1, 0]}, "
      "boundary: [[0, 0, 1], [2, 0, 1], [0, 2, 1]], tows: 8}\n";
  const testing::Loaded r =
      LoadText(LaminateScene("in", 25.4,
                             Laminate("skin", "{origin: [1, 2, 3], direction: [0, 2, 0]}",
                                      "{offset: 0.5, plies_before_repeat: 4}", stack)) +
               "materials: [{name: T700, ply_thickness: 0.006, areal_weight_g_m2: 310}, "
               "{name: IM7, ply_thickness: 0.009, areal_weight_g_m2: 290}]\n");
  ASSERT_TRUE(r.scene) << r.message;
  const Scene& s = *r.scene;
  ASSERT_EQ(s.laminates.size(), 1u);
  const LaminateSpec& lam = s.laminates[0];
  EXPECT_EQ(lam.name, "skin");
  EXPECT_EQ(lam.where.line, 24);
  EXPECT_LT((lam.rosette.origin_mm - Eigen::Vector3d(25.4, 50.8, 76.2)).norm(), 1e-9);
  EXPECT_LT((lam.rosette.direction - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_LT((lam.rosette.projection - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  EXPECT_NEAR(lam.stagger_offset_mm, 12.7, 1e-9);
  EXPECT_EQ(lam.stagger_plies_before_repeat, 4);
  ASSERT_EQ(lam.stack.size(), 6u);
  ASSERT_EQ(s.plies.size(), 6u);  // the four named, then the two inline
  const char* names[] = {"p0", "p45", "skin/3", "pm45", "p90", "skin/6"};
  const bool inlined[] = {false, false, true, false, false, true};
  for (std::size_t i = 0; i < 6; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(s.plies[lam.stack[i].ply].name, names[i]);
    EXPECT_EQ(lam.stack[i].inline_ply, inlined[i]);
    EXPECT_EQ(lam.stack[i].where.line, 28 + static_cast<int>(i));
  }
  EXPECT_EQ(lam.stack[1].material, "T700");
  EXPECT_NEAR(*lam.stack[1].thickness_mm, 0.0072 * 25.4, 1e-12);
  EXPECT_EQ(lam.stack[2].material, "IM7");
  EXPECT_NEAR(*lam.stack[2].thickness_mm, 0.254, 1e-12);
  EXPECT_TRUE(lam.stack[0].material.empty());
  EXPECT_FALSE(lam.stack[0].thickness_mm);
  // Resolved onto the plies: the material's data, the entry's thickness over it; an entry
  // without either leaves the ply's defaults.
  EXPECT_EQ(s.plies[lam.stack[1].ply].material, "T700");
  EXPECT_NEAR(s.plies[lam.stack[1].ply].thickness_mm, 0.0072 * 25.4, 1e-12);
  EXPECT_NEAR(s.plies[lam.stack[1].ply].areal_weight_g_m2, 310.0, 1e-12);
  EXPECT_NEAR(s.plies[lam.stack[2].ply].thickness_mm, 0.254, 1e-12);
  EXPECT_NEAR(s.plies[lam.stack[2].ply].areal_weight_g_m2, 290.0, 1e-12);
  EXPECT_NEAR(s.plies[lam.stack[0].ply].thickness_mm, kDefaultPlyThicknessMm, 1e-12);
  // The inline 90: the rosette's reference, its angle about it, its (u, v) boundary in mm.
  const PlySpec& p90 = s.plies[lam.stack[2].ply];
  EXPECT_NEAR(p90.angle_rad, kPi / 2, 1e-12);
  EXPECT_EQ(p90.origin_mm, lam.rosette.origin_mm);
  EXPECT_EQ(p90.direction, lam.rosette.direction);
  EXPECT_EQ(p90.projection, lam.rosette.projection);
  ASSERT_EQ(p90.boundary_uv.size(), 3u);
  EXPECT_LT((p90.boundary_uv[1] - Eigen::Vector2d(50.8, 0)).norm(), 1e-9);
  EXPECT_EQ(p90.tows, 16);
  EXPECT_EQ(p90.where.line, 30);
  // The inline -30: a reference of its own, a 3D boundary projected, 8 tows.
  const PlySpec& p30 = s.plies[lam.stack[5].ply];
  EXPECT_NEAR(p30.angle_rad, -kPi / 6, 1e-12);
  EXPECT_LT((p30.origin_mm - Eigen::Vector3d(25.4, 25.4, 25.4)).norm(), 1e-9);
  EXPECT_LT((p30.direction - Eigen::Vector3d(1, 1, 0) / std::sqrt(2.0)).norm(), 1e-12);
  ASSERT_EQ(p30.boundary_uv.size(), 3u);
  EXPECT_LT((p30.boundary_uv[2] - Eigen::Vector2d(0, 50.8)).norm(), 1e-6);
  EXPECT_EQ(p30.tows, 8);
}

TEST(SceneLaminates, EveryBadLaminateIsReportedAtItsLine) {
  struct Case {
    std::string laminates, code;
    int line;
  };
  const std::string bad = "scene-bad-laminate";
  const std::string good = Laminate("skin", kRosette, kStagger, kStack);
  const auto with_stack = [](const std::string& stack) {
    return Laminate("skin", kRosette, kStagger, stack);
  };
  const auto with_stagger = [](const std::string& stagger) {
    return Laminate("skin", kRosette, stagger, kStack);
  };
  const auto with_rosette = [](const std::string& rosette) {
    return Laminate("skin", rosette, kStagger, kStack);
  };
  const Case cases[] = {
      {with_stack("\n      - p0\n      - p7\n"), bad, 29},             // unknown ply
      {with_stack("\n      - p0\n      - {ply: p46}\n"), bad, 29},     // unknown, map form
      {with_stack("\n      - skin/3\n"), bad, 28},                     // an inline ply's name
      {with_stack(" []\n"), bad, 27},                                  // empty stack
      {good + Laminate("skin", kRosette, kStagger, kStack), bad, 31},  // the name twice
      {Laminate("a/b", kRosette, kStagger, kStack), bad, 24},
      {with_stagger("{offset: -1, plies_before_repeat: 2}"), bad, 26},
      {with_stagger("{offset: 101.7, plies_before_repeat: 2}"), bad, 26},  // > 16 x 6.35 mm
      {with_stagger("{offset: 5, plies_before_repeat: 0}"), bad, 26},
      {with_stagger("{offset: 5, plies_before_repeat: 1.5}"), bad, 26},
      {with_rosette("{origin: [400, 0, 50], direction: [1, 0, 0]}"), bad, 25},  // off the plane
      {with_rosette("{origin: [0, 0, 50], direction: [0, 0, 2]}"), bad, 25},    // the normal
      {with_rosette("{origin: [0, 0, 50], direction: [1, 0, 0], projection: [-1, 0, 0]}"), bad,
       25},  // along the projection
      {with_rosette("{origin: [0, 0, 50], direction: [0, 0, 0]}"), bad, 25},
      {with_stack("\n      - p0\n      - {ply: p45, thickness: -0.18}\n"), bad, 29},
      {with_stack("\n      - p0\n      - {ply: p45, thickness: 0}\n"), bad, 29},
      {with_stack("\n      - {angle_deg: 90, boundary_uv: [[0, 0], [50, 0], [0, 50]], "
                  "thickness: -1}\n"),
       bad, 28},
      {with_stack("\n      - p0\n      - {ply: p45, material: 'T 700'}\n"), bad, 29},
      {with_stack("\n      - p0\n      - {ply: p45, material: T800}\n"), bad, 29},    // unknown
      {with_stack("\n      - p45\n      - {ply: p45, thickness: 0.25}\n"), bad, 29},  // two

      // an inline ply's own problem is the ply reader's
      {with_stack("\n      - p0\n      - {angle_deg: 90, boundary_uv: [[0, 0], [50, 0]]}\n"),
       "scene-bad-ply", 29},
      {with_stack("\n      - {name: x, angle_deg: 90, boundary_uv: [[0, 0], [50, 0], [0, 50]]}\n"),
       "scene-unknown-key", 28},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.laminates);
    const testing::Loaded r = LoadText(LaminateScene("mm", 1.0, c.laminates));
    EXPECT_FALSE(r.scene);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_EQ(r.line, c.line) << r.message;
  }
}

// The edges of the ranges are accepted: a stagger of exactly one course (16 x 6.35 mm), one
// ply before a repeat.
TEST(SceneLaminates, StaggerOfOneCourseIsAccepted) {
  const testing::Loaded r = LoadText(LaminateScene(
      "mm", 1.0, Laminate("skin", kRosette, "{offset: 101.6, plies_before_repeat: 1}", kStack)));
  ASSERT_TRUE(r.scene) << r.message;
  EXPECT_NEAR(r.scene->laminates[0].stagger_offset_mm, 101.6, 1e-12);
  EXPECT_EQ(r.scene->laminates[0].stagger_plies_before_repeat, 1);
}

}  // namespace
}  // namespace stitchsim::scene
