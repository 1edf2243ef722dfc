// `plies:` in a scene (docs/scene-format.md): the values read into scene::PlySpec and every
// scene-bad-ply problem at its file:line.

#include <gtest/gtest.h>

#include <string>

#include "scene_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

using testing::WriteTemp;

// 17 lines; `plies:` is line 18, its first entry line 19.
std::string SceneText(const std::string& plies, const std::string& head = "afp") {
  return "stitchsim_scene: 1\nname: plies\nunits: mm\nhead: " + head +
         "\npart:\n  mount: table\n  position: [0, -400, 50]\nsurface:\n  type: plane\n"
         "  size: [600, 400]\npreform:\n  thickness: 2\npaths:\n  - name: row\n    type: line\n"
         "    from: [0, 0]\n    to: [100, 0]\nplies:\n" +
         plies;
}

const char* kRef = "reference: {origin: [0, 0, 50], direction: [1, 0, 0]}";

std::string Ply(const std::string& name, const std::string& rest) {
  return "  - {name: " + name + ", " + kRef + ", " + rest + "}\n";
}

struct Loaded {
  std::unique_ptr<Scene> scene;
  std::string code, message;
  int line = 0;
};
Loaded Load(const std::string& text, const std::string& head = "afp") {
  const auto file = WriteTemp("ply_scene", "s.yaml", SceneText(text, head));
  DiagnosticSink sink;
  Loaded r;
  r.scene = LoadScene(file, sink);
  if (!sink.Diagnostics().empty()) {
    r.code = sink.Diagnostics()[0].code;
    r.message = sink.Diagnostics()[0].message;
    r.line = sink.Diagnostics()[0].location.line;
  }
  return r;
}

TEST(ScenePlies, ValuesAreRead) {
  const Loaded r = Load(
      "  - name: skin_45\n    angle_deg: 45\n    reference:\n      origin: [10, 20, 50]\n"
      "      direction: [0, 2, 0]\n    boundary_uv: [[0, 0], [0, 100], [200, 100], [200, 0]]\n"
      "    rule: offset\n    method: paper\n    coverage: 100\n    tows: 8\n" +
      Ply("b", "boundary: [[0, 0, 30], [100, 0, 30], [100, 50, 30]], coverage: 0"));
  ASSERT_TRUE(r.scene) << r.code << " " << r.message;
  ASSERT_EQ(r.scene->plies.size(), 2u);
  const PlySpec& a = r.scene->plies[0];
  EXPECT_EQ(a.name, "skin_45");
  EXPECT_EQ(a.where.line, 19);
  EXPECT_NEAR(a.angle_rad, kPi / 4, 1e-12);
  EXPECT_EQ(a.origin_mm, Eigen::Vector3d(10, 20, 50));
  EXPECT_EQ(a.direction, Eigen::Vector3d(0, 1, 0));
  EXPECT_LT((a.projection - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);  // minus the normal
  EXPECT_EQ(a.method, PlyOffsetMethod::kPaper);
  EXPECT_EQ(a.rule, PlyRule::kOffset);
  EXPECT_EQ(a.coverage, 1.0);
  EXPECT_EQ(a.tows, 8);
  ASSERT_EQ(a.boundary_uv.size(), 4u);  // given clockwise, kept counter-clockwise
  EXPECT_EQ(a.boundary_uv[0], Eigen::Vector2d(200, 0));
  EXPECT_EQ(a.boundary_uv[1], Eigen::Vector2d(200, 100));
  const PlySpec& b = *r.scene->FindPly("b");
  EXPECT_EQ(b.tows, 16);  // the head's
  EXPECT_EQ(b.coverage, 0.0);
  EXPECT_EQ(b.method, PlyOffsetMethod::kCorrected);
  ASSERT_EQ(b.boundary_uv.size(), 3u);
  EXPECT_LT((b.boundary_uv[2] - Eigen::Vector2d(100, 50)).norm(), 1e-6);  // projected
}

TEST(ScenePlies, EveryBadPlyIsReportedAtItsLine) {
  struct Case {
    std::string plies;
    int line;
  };
  const std::string good = "boundary_uv: [[0, 0], [100, 0], [0, 100]]";
  const Case cases[] = {
      {Ply("a", "boundary_uv: [[0, 0], [400, 0], [0, 100]]"), 19},              // off the domain
      {Ply("a", "boundary: [[0, 0, 10], [1000, 0, 10], [0, 100, 10]]"), 19},    // no projection
      {Ply("a", "boundary_uv: [[0, 0], [100, 0]]"), 19},                        // < 3 points
      {Ply("a", "boundary_uv: [[0, 0], [100, 100], [100, 0], [0, 100]]"), 19},  // crossing
      {Ply("a", good + ", rule: spiral"), 19},
      {Ply("a", good + ", method: exact"), 19},
      {"  - {name: a, reference: {origin: [0, 0, 50], direction: [1, 0, 0], path: constant}, " +
           good + "}\n",
       19},  // an unknown reference path
      {Ply("a", good + ", coverage: 30"), 19},
      {Ply("a", good + ", tows: 17"), 19},
      {Ply("a", good) + Ply("a", good), 20},  // the name twice
      {Ply("a b", good), 19},
      {Ply("a", "boundary_uv: [[0, 0], [100, 0], [0, 100]], boundary: [[0, 0, 0]]"), 19},
      // a reference direction along the projection (issue 29: shared with a laminate's rosette)
      {"  - {name: a, reference: {origin: [0, 0, 50], direction: [1, 0, 0], projection: [2, 0, "
       "0]}, " +
           good + "}\n",
       19},
      // block style: the point itself
      {"  - name: a\n    " + std::string(kRef) +
           "\n    boundary_uv:\n      - [0, 0]\n      - [0, 100]\n      - [350, 100]\n",
       24},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.plies);
    const Loaded r = Load(c.plies);
    EXPECT_FALSE(r.scene);
    EXPECT_EQ(r.code, "scene-bad-ply") << r.message;
    EXPECT_EQ(r.line, c.line) << r.message;
  }
}

TEST(ScenePlies, ReferencePathsAreRead) {
  const std::string good = "boundary_uv: [[0, 0], [100, 0], [0, 100]]";
  auto ref = [](const std::string& path) {
    return "reference: {origin: [0, 0, 50], direction: [1, 0, 0]" +
           (path.empty() ? std::string() : ", path: " + path) + "}, ";
  };
  const Loaded r = Load("  - {name: a, " + ref("") + good + "}\n  - {name: b, " + ref("projected") +
                        good + "}\n  - {name: c, " + ref("geodesic") + good + "}\n  - {name: d, " +
                        ref("constant_angle") + good + "}\n");
  ASSERT_TRUE(r.scene) << r.code << " " << r.message;
  EXPECT_EQ(r.scene->FindPly("a")->reference_path, ReferencePath::kProjected);
  EXPECT_EQ(r.scene->FindPly("b")->reference_path, ReferencePath::kProjected);
  EXPECT_EQ(r.scene->FindPly("c")->reference_path, ReferencePath::kGeodesic);
  EXPECT_EQ(r.scene->FindPly("d")->reference_path, ReferencePath::kConstantAngle);
  // An unknown path, in block style: at the line of its value, naming every path.
  const Loaded bad = Load(
      "  - name: a\n    reference:\n      origin: [0, 0, 50]\n"
      "      direction: [1, 0, 0]\n      path: streamline\n    " +
      good + "\n");
  EXPECT_FALSE(bad.scene);
  EXPECT_EQ(bad.code, "scene-bad-ply");
  EXPECT_EQ(bad.line, 23);
  EXPECT_NE(bad.message.find("projected or geodesic or constant_angle, got 'streamline'"),
            std::string::npos)
      << bad.message;
}

TEST(ScenePlies, PliesNeedAnAfpHead) {
  const Loaded r = Load(Ply("a", "boundary_uv: [[0, 0], [100, 0], [0, 100]]"), "rs535");
  EXPECT_FALSE(r.scene);
  EXPECT_EQ(r.code, "scene-bad-ply");
  EXPECT_EQ(r.line, 19);
}

}  // namespace
}  // namespace stitchsim::scene
