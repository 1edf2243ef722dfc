// The CAD surface kinds of a scene: `bspline` from a control net, `step` from a part file
// written here with the kernel, and their bad input reported at the scene's file:line (exit
// 2 from the command line).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene_test_support.h"
#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;

fs::path Folder(const std::string& name) { return testing::Folder("cad_scene", name); }
using testing::Load;
using testing::Loaded;
using testing::RunCli;
using testing::Write;

// Scene head; the surface map starts on line 6.
// The path runs along u over the middle of a 200 x 100 mm domain (8 x 4 in in inches).
std::string SceneText(const std::string& units, const std::string& surface) {
  const std::string path =
      units == "in" ? "from: [1, 2], to: [7, 2]" : "from: [20, 50], to: [180, 50]";
  return "stitchsim_scene: 1\nname: cad\nunits: " + units +
         "\nhead: rs535\npart: {mount: table}\n" + surface + "paths: [{name: a, type: line, " +
         path + "}]\n";
}

// A curved patch: quadratic along u (a bump of 20 mm), linear along v, 200 x 100 mm.
geom::BSplineSpec Bump() {
  geom::BSplineSpec s;
  s.degree_u = 2;
  s.degree_v = 1;
  s.poles = {
      {{-100, -50, 0}, {-100, 50, 0}}, {{0, -50, 40}, {0, 50, 40}}, {{100, -50, 0}, {100, 50, 0}}};
  return s;
}

TEST(CadScene, BSplineInInchesMatchesTheSameNetInMillimetres) {
  const fs::path dir = Folder("bspline");
  Write(dir / "s.yaml", SceneText("in",
                                  "surface:\n  type: bspline\n  degree: [2, 1]\n"
                                  "  poles:\n    - [[-4, -2, 0], [-4, 2, 0]]\n"
                                  "    - [[0, -2, 1], [0, 2, 1]]\n"
                                  "    - [[4, -2, 0], [4, 2, 0]]\n"
                                  "  weights: [[1, 1], [2, 2], [1, 1]]\n"
                                  "  knots_u: [0, 1]\n  multiplicities_u: [3, 3]\n"));
  const Loaded r = Load(dir / "s.yaml");
  ASSERT_TRUE(r.scene) << r.message;
  ASSERT_TRUE(r.scene->surface);
  EXPECT_EQ(r.scene->surface->Kind(), "bspline");
  geom::BSplineSpec mm;
  mm.degree_u = 2;
  mm.degree_v = 1;
  mm.poles = {{{-101.6, -50.8, 0}, {-101.6, 50.8, 0}},
              {{0, -50.8, 25.4}, {0, 50.8, 25.4}},
              {{101.6, -50.8, 0}, {101.6, 50.8, 0}}};
  mm.weights = {{1, 1}, {2, 2}, {1, 1}};
  std::string err;
  const auto expected = geom::MakeBSplineSurface(mm, err);
  ASSERT_TRUE(expected) << err;
  const geom::Domain2 d = expected->Domain();
  EXPECT_NEAR(r.scene->surface->Domain().max.x(), d.max.x(), 1e-9);
  for (int i = 0; i <= 10; ++i) {
    const Eigen::Vector2d uv = d.max.cwiseProduct(Eigen::Vector2d(i / 10.0, 1 - i / 10.0));
    EXPECT_LT((r.scene->surface->Point(uv) - expected->Point(uv)).norm(), 1e-9);
  }
}

TEST(CadScene, BadBSplinesAreReportedAtTheirLine) {
  const fs::path dir = Folder("bad_bspline");
  struct Case {
    std::string surface;
    std::string code;
    int line;
  };
  const Case cases[] = {
      // row 2 shorter than row 1: the maker's message, at the surface map (line 7)
      {"surface:\n  type: bspline\n  degree: [1, 1]\n  poles:\n    - [[0, 0, 0], [0, 1, 0]]\n"
       "    - [[1, 0, 0]]\n",
       "scene-bad-bspline", 7},
      {"surface:\n  type: bspline\n  degree: [1, 0]\n  poles: [[[0, 0, 0]]]\n",
       "scene-out-of-range", 8},
      {"surface:\n  type: bspline\n  degree: [1, 1]\n  poles:\n    - [[0, 0, 0], [0, 1, nan]]\n"
       "    - [[1, 0, 0], [1, 1, 0]]\n",
       "scene-not-finite", 10},
      {"surface:\n  type: bspline\n  degree: [1, 1]\n  poles:\n    - [[0, 0, 0], [0, 1, 0]]\n"
       "    - [[1, 0, 0], [1, 1, 0]]\n  knots_u: [0, 1]\n  multiplicities_u: [2, 1]\n",
       "scene-bad-bspline", 7},
      {"surface:\n  type: bspline\n  degree: [1, 1]\n  poles:\n    - [[0, 0, 0], [0, 1, 0]]\n"
       "    - [[1, 0, 0], [1, 1, 0]]\n  knots_v: [0, 1]\n",
       "scene-missing-key", 12},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.surface);
    Write(dir / "s.yaml", SceneText("mm", c.surface));
    const Loaded r = Load(dir / "s.yaml");
    EXPECT_FALSE(r.scene);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_EQ(r.line, c.line) << r.message;
  }
}

// A STEP part of two faces (a flat patch and the bump, named) in the scene folder.
void WritePart(const fs::path& file) {
  fs::create_directories(file.parent_path());
  geom::BSplineSpec flat = Bump();
  for (auto& row : flat.poles) {
    for (auto& p : row) p.z() = 0;
  }
  std::string err;
  ASSERT_TRUE(geom::WriteBSplineCad({flat, Bump()}, {"flat", "bump"}, file, geom::CadFormat::kStep,
                                    "MM", err))
      << err;
}

TEST(CadScene, AStepFaceByIndexOrNameIsTheSurfaceWritten) {
  const fs::path dir = Folder("step");
  WritePart(dir / "parts" / "part.step");
  std::string err;
  const auto original = geom::MakeBSplineSurface(Bump(), err);
  ASSERT_TRUE(original) << err;
  for (const std::string face : {"1", "bump"}) {
    SCOPED_TRACE(face);
    // The scene is in inches: the part file's millimetres are not rescaled.
    Write(dir / "s.yaml",
          SceneText("in", "surface: {type: step, file: parts/part.step, face: " + face + "}\n"));
    const Loaded r = Load(dir / "s.yaml");
    ASSERT_TRUE(r.scene) << r.message;
    EXPECT_EQ(r.scene->surface->Kind(), "step");
    for (int i = 0; i <= 10; ++i) {
      const Eigen::Vector2d uv =
          original->Domain().max.cwiseProduct(Eigen::Vector2d(i / 10.0, 1 - i / 10.0));
      EXPECT_LT((r.scene->surface->Point(uv) - original->Point(uv)).norm(), 1e-6);
      EXPECT_GT(r.scene->surface->Normal(uv).z(), 0.0);
    }
  }
}

TEST(CadScene, AnIgesFaceLoadsAndRefusesAName) {
  const fs::path dir = Folder("iges");
  std::string err;
  ASSERT_TRUE(
      geom::WriteBSplineCad({Bump()}, {}, dir / "part.igs", geom::CadFormat::kIges, "M", err))
      << err;
  const auto original = geom::MakeBSplineSurface(Bump(), err);
  Write(dir / "s.yaml", SceneText("mm", "surface: {type: iges, file: part.igs, face: 0}\n"));
  const Loaded r = Load(dir / "s.yaml");
  ASSERT_TRUE(r.scene) << r.message;
  EXPECT_EQ(r.scene->surface->Kind(), "iges");
  const Eigen::Vector2d uv(37, 61);
  EXPECT_LT((r.scene->surface->Point(uv) - original->Point(uv)).norm(), 1e-6);
  Write(dir / "s.yaml", SceneText("mm", "surface: {type: iges, file: part.igs, face: bump}\n"));
  const Loaded bad = Load(dir / "s.yaml");
  EXPECT_FALSE(bad.scene);
  EXPECT_EQ(bad.code, "scene-bad-cad-file") << bad.message;
  EXPECT_EQ(bad.line, 6);
}

TEST(CadScene, BadPartFilesAreReportedAtTheirLine) {
  const fs::path dir = Folder("bad_step");
  WritePart(dir / "part.step");
  Write(dir / "empty.step", "");
  Write(dir / "text.step", "solid plate\nthis is not a STEP file\n");
  // A valid STEP file that holds no faces: the header and an empty data section.
  Write(dir / "nofaces.step",
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('n','',(''),(''),'',"
        "'','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\n"
        "DATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n");
  fs::create_directories(dir / "sub");
  struct Case {
    std::string file, face, code, what;
    int line;
  };
  const Case cases[] = {
      {"missing.step", "0", "scene-missing-file", "", 6},
      {"../part.step", "0", "scene-path-outside", "", 6},
      {"empty.step", "0", "scene-bad-cad-file", "is empty", 6},
      {"text.step", "0", "scene-bad-cad-file", "not a readable STEP file", 6},
      {"nofaces.step", "0", "scene-bad-cad-file", "has no faces", 6},
      {"part.step", "2", "scene-bad-cad-file", "out of range", 6},
      {"part.step", "wing", "scene-bad-cad-file", "no face named 'wing'", 6},
      {"part.step", "\"1\"", "scene-bad-cad-file", "no face named '1'", 6},
      {"part.step", "-1", "scene-out-of-range", "", 6},
      {"part.step", "1.5", "scene-bad-number", "", 6},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file + " face " + c.face);
    const fs::path scene = (c.file == "../part.step" ? dir / "sub" : dir) / "s.yaml";
    Write(scene,
          SceneText("mm", "surface: {type: step, file: " + c.file + ", face: " + c.face + "}\n"));
    const Loaded r = Load(scene);
    EXPECT_FALSE(r.scene);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_EQ(r.line, c.line) << r.message;
    EXPECT_NE(r.message.find(c.what), std::string::npos) << r.message;
  }
}

TEST(CadScene, TheCommandLinePlansOnAStepFaceAndExitsTwoOnABadOne) {
  const fs::path dir = Folder("cli");
  WritePart(dir / "part.step");
  Write(dir / "good.yaml", SceneText("mm", "surface: {type: step, file: part.step, face: bump}\n"));
  Write(dir / "bad.yaml", SceneText("mm", "surface: {type: step, file: part.step, face: 7}\n"));
  const fs::path err = dir / "err.txt";
  EXPECT_EQ(RunCli("plan stitch --scene " + (dir / "good.yaml").string() + " --path a -o " +
                       (dir / "a.nc").string(),
                   err),
            0);
  EXPECT_TRUE(fs::exists(dir / "a.nc"));
  EXPECT_EQ(RunCli("plan stitch --scene " + (dir / "bad.yaml").string() + " --path a -o " +
                       (dir / "b.nc").string(),
                   err),
            2);
  const std::string text = testing::ReadAll(err);
  EXPECT_NE(text.find((dir / "bad.yaml").string() + ":6:"), std::string::npos) << text;
  EXPECT_NE(text.find("out of range"), std::string::npos) << text;
}

}  // namespace
}  // namespace stitchsim::scene
