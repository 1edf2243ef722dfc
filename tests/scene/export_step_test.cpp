// `stitchsim export-step`: the bundled naca_wing and a polynomial scene written to STEP (and
// IGES, in other units), read back through the `step` kind's reader and compared with the
// scene's surface; bad input exits 2 and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "scene_test_support.h"
#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
using testing::ReadAll;
using testing::RunCli;

std::unique_ptr<Scene> LoadOrFail(const fs::path& file) {
  DiagnosticSink sink;
  auto scene = LoadScene(file, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return scene;
}

// Largest distance from the scene surface's grid points to the read-back face: the face's
// point at the same fraction of its domain (the export keeps the parameters linear).
double Distance(const geom::Surface& a, const geom::Surface& b, int n = 60) {
  const geom::Domain2 da = a.Domain();
  const geom::Domain2 db = b.Domain();
  double worst = 0.0;
  for (int i = 0; i <= n; ++i) {
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector2d f = Eigen::Vector2d(i, k) / static_cast<double>(n);
      const Eigen::Vector2d ua = da.min + (da.max - da.min).cwiseProduct(f);
      const Eigen::Vector2d ub = db.min + (db.max - db.min).cwiseProduct(f);
      worst = std::max(worst, (a.Point(ua) - b.Point(ub)).norm());
      EXPECT_GT(a.Normal(ua).dot(b.Normal(ub)), 0.99) << f.transpose();
    }
  }
  return worst;
}

struct Case {
  std::string scene;
  std::string options;
  geom::CadFormat format;
  bool flip = false;
};

TEST(ExportStep, BundledScenesRoundTripThroughTheStepReader) {
  const fs::path dir = testing::Folder("export_step", "roundtrip");
  const Case cases[] = {
      {"naca_wing", "", geom::CadFormat::kStep},
      {"wing_cover", "", geom::CadFormat::kStep},  // polynomial, inches
      {"naca_wing", "--format iges --unit cm", geom::CadFormat::kIges, true},
      {"wing_cover", "--unit inch", geom::CadFormat::kStep},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.scene + " " + c.options);
    const fs::path scene_file = kSource / "scenes" / (c.scene + ".yaml");
    const fs::path out = dir / (c.scene + (c.format == geom::CadFormat::kIges ? ".igs" : ".step"));
    ASSERT_EQ(RunCli("export-step --scene " + scene_file.string() + " -o " + out.string() + " " +
                         c.options,
                     dir / "log.txt"),
              0)
        << ReadAll(dir / "log.txt");
    const std::string log = ReadAll(dir / "log.txt");
    EXPECT_NE(log.find("largest deviation"), std::string::npos);
    EXPECT_EQ(log.find("flip_normal: true") != std::string::npos, c.flip) << log;
    const auto scene = LoadOrFail(scene_file);
    ASSERT_TRUE(scene);
    std::string error;
    geom::CadFaceRef ref;
    ref.flip_normal = c.flip;  // an IGES face keeps du x dv: the wing's points inwards
    const auto face = geom::ReadCadFace(out, c.format, ref, error);
    ASSERT_TRUE(face) << error;
    EXPECT_LT(Distance(*scene->surface, *face), 0.01);
  }
}

TEST(ExportStep, BadInputExitsTwoAndWritesNothing) {
  const fs::path dir = testing::Folder("export_step", "bad");
  testing::Write(dir / "bad.yaml",
                 "stitchsim_scene: 1\nname: w\nunits: mm\nhead: afp\npart: {mount: table}\n"
                 "surface:\n  type: wing\n  root: {naca: \"23014\", chord: 0}\n"
                 "  tip: {naca: \"23012\", chord: 1130.3}\n  span: 7310\n"
                 "paths: [{name: a, type: line, from: [10, 10], to: [60, 10]}]\n");
  const fs::path log = dir / "log.txt";
  EXPECT_EQ(RunCli("export-step --scene " + (dir / "bad.yaml").string() + " -o " +
                       (dir / "a.step").string(),
                   log),
            2);
  EXPECT_NE(ReadAll(log).find((dir / "bad.yaml").string() + ":8:"), std::string::npos)
      << ReadAll(log);
  EXPECT_FALSE(fs::exists(dir / "a.step"));
  const fs::path good = kSource / "scenes" / "flat_straight.yaml";
  EXPECT_EQ(RunCli("export-step --scene " + good.string() + " -o " + dir.string(),  // a directory
                   log),
            2);
  EXPECT_EQ(RunCli("export-step --scene " + good.string() + " -o " + (dir / "a.step").string() +
                       " --unit furlong",
                   log),
            2);
  EXPECT_FALSE(fs::exists(dir / "a.step"));
}

}  // namespace
}  // namespace stitchsim::scene
