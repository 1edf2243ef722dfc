// Scenes an audit found handled differently by different commands (issue 26, item 8): an
// alias bomb, a plane and path of 1e300 mm, a stitch length of 1e-6 mm, an STL with
// coordinates near 1e30. Each must be refused by `plan stitch`, `render` and `verify` alike:
// exit 2 and the same first diagnostic, at the scene line that asks for it. The alias bomb
// stands for ten billion nodes, so a walk that expands it runs into the test's timeout.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app_test_support.h"

namespace {

namespace fs = std::filesystem;
using stitchsim::app::testing::CliRun;
using stitchsim::app::testing::ReadText;
using stitchsim::app::testing::RunCli;
using stitchsim::app::testing::ScratchDir;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

std::string Describe(const CliRun& r) {
  return "exit " + std::to_string(r.exit_code) + "\n--- stdout\n" + r.out + "--- stderr\n" + r.err;
}

// The first `error[` line of `text`, or "".
std::string FirstError(const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find(": error[") != std::string::npos) return line;
  }
  return {};
}

class BadSceneCli : public ::testing::Test {
 protected:
  void SetUp() override {
    name_ = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = ScratchDir() / name_;
    fs::create_directories(dir_);
    // A clean programme for verify, planned from the good scene.
    const fs::path good = Write("good.yaml", Flat());
    const CliRun r =
        RunCli("plan stitch --quiet --scene " + good.string() + " -o " + Program().string(),
               name_ + "_plan_good");
    ASSERT_EQ(r.exit_code, 0) << Describe(r);
  }

  static std::string Flat() { return ReadText(kSource / "scenes" / "flat_straight.yaml"); }
  // flat_straight with `from` replaced by `to`.
  static std::string Flat(const std::string& from, const std::string& to) {
    std::string text = Flat();
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  }

  fs::path Write(const std::string& file, const std::string& text) const {
    const fs::path p = dir_ / file;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  fs::path Program() const { return dir_ / "good.nc"; }

  // `plan stitch`, `render` and `verify` on `scene`: each exits 2, and the first error line
  // of each is the same and begins with `expected` (file:line:col: error[code]).
  void ExpectEveryCommandRefuses(const fs::path& scene, const std::string& expected) {
    const std::string s = " --scene " + scene.string();
    const struct {
      std::string tag, args;
    } commands[] = {
        {"plan", "plan stitch --quiet" + s + " -o " + (dir_ / "o.nc").string()},
        {"render", "render" + s + " -o " + (dir_ / "o.png").string()},
        {"verify", "verify " + Program().string() + s + " --report " + (dir_ / "o.json").string()},
    };
    std::string first;
    for (const auto& c : commands) {
      SCOPED_TRACE(c.tag);
      const CliRun r = RunCli(c.args, name_ + "_" + c.tag);
      EXPECT_EQ(r.exit_code, 2) << Describe(r);
      const std::string line = FirstError(r.err);
      EXPECT_EQ(line.rfind(expected, 0), 0u) << "expected " << expected << "\n" << Describe(r);
      if (first.empty()) first = line;
      EXPECT_EQ(line, first) << Describe(r);
    }
  }

  std::string name_;
  fs::path dir_;
};

TEST_F(BadSceneCli, AnAliasBombIsRefusedAtTheAliasByEveryCommand) {
  // Ten levels of ten aliases under an unknown key: 10^10 nodes once expanded.
  std::string bomb = "bomb:\n  a: &a [x,x,x,x,x,x,x,x,x,x]\n";
  const std::string names = "abcdefghij";
  for (std::size_t level = 1; level < names.size(); ++level) {
    bomb += std::string("  ") + names[level] + ": &" + names[level] + " [";
    for (int i = 0; i < 10; ++i) bomb += std::string(i ? ", " : "") + "*" + names[level - 1];
    bomb += "]\n";
  }
  const std::string flat = Flat();
  const fs::path scene = Write("bomb.yaml", flat + bomb);
  // Level f stands for 1,111,111 nodes: the third alias of level g (column 18) passes 4 million.
  const long g_line = std::count(flat.begin(), flat.end(), '\n') + 8;
  ExpectEveryCommandRefuses(scene, scene.string() + ":" + std::to_string(g_line) +
                                       ":18: error[scene-yaml-alias]: alias '*f'");
}

TEST_F(BadSceneCli, APlaneOfAKilometreAndMoreIsRefusedByEveryCommand) {
  std::string text = Flat("size: [1000, 600]", "size: [1e300, 1e300]");
  text.replace(text.find("from: [-300, 0]"), 15, "from: [-1e299, 0]");
  text.replace(text.find("to: [300, 0]"), 12, "to: [1e299, 0]");
  const fs::path scene = Write("huge_plane.yaml", text);
  ExpectEveryCommandRefuses(scene, scene.string() + ":11:10: error[scene-out-of-range]");
}

TEST_F(BadSceneCli, ATinyStitchLengthIsRefusedByEveryCommand) {
  const fs::path scene =
      Write("tiny_stitch.yaml", Flat("nominal_length: 5", "nominal_length: 0.000001"));
  ExpectEveryCommandRefuses(scene, scene.string() + ":19:5: error[scene-too-many-stitches]");
}

TEST_F(BadSceneCli, AnStlBeyondAKilometreIsRefusedByEveryCommand) {
  Write("far.stl",
        "solid far\nfacet normal 0 0 1\nouter loop\nvertex -1e30 -1e30 0\nvertex 1e30 -1e30 0\n"
        "vertex 1e30 1e30 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
        "vertex -1e30 -1e30 0\nvertex 1e30 1e30 0\nvertex -1e30 1e30 0\nendloop\nendfacet\n"
        "endsolid far\n");
  const fs::path scene = Write("far_mesh.yaml", Flat("  type: plane\n  size: [1000, 600]\n",
                                                     "  type: mesh\n  file: far.stl\n"));
  ExpectEveryCommandRefuses(scene, scene.string() + ":11:9: error[scene-bad-mesh]: STL file " +
                                       (dir_ / "far.stl").string());
}

}  // namespace
