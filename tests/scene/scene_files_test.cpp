// What a scene may name and how its files are read (issue 10 items 7, 8, 10, 13): only
// regular files within size limits, only inside the scene's folder or the models folder
// (unless allowed), duplicate keys refused, head-spec counts range-checked.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene_test_support.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test: <tmp>/stitchsim_scene_files_<pid>/<name>.
fs::path Folder(const std::string& name) { return testing::Folder("scene_files", name); }
using testing::Write;

// A 200 x 200 mm flat plate as ASCII STL (two triangles).
const char kPlateStl[] =
    "solid plate\n"
    "facet normal 0 0 1\nouter loop\nvertex -100 -100 0\nvertex 100 -100 0\nvertex 100 100 0\n"
    "endloop\nendfacet\n"
    "facet normal 0 0 1\nouter loop\nvertex -100 -100 0\nvertex 100 100 0\nvertex -100 100 0\n"
    "endloop\nendfacet\nendsolid plate\n";

// A scene on a mesh surface read from `stl` (line 6 names it).
std::string MeshScene(const std::string& stl) {
  return "stitchsim_scene: 1\nname: m\nunits: mm\nhead: rs535\npart: {mount: table}\n"
         "surface: {type: mesh, file: " +
         stl + "}\npaths: [{name: a, type: line, from: [-50, 0], to: [50, 0]}]\n";
}

struct Loaded {
  bool ok = false;
  std::string code;  // of the first diagnostic
  int line = 0;
  std::string message;
};

Loaded Load(const fs::path& scene, const LoadOptions& options = {}) {
  DiagnosticSink sink;
  Loaded out;
  out.ok = LoadScene(scene, sink, options) != nullptr;
  if (!sink.Diagnostics().empty()) {
    out.code = sink.Diagnostics().front().code;
    out.line = sink.Diagnostics().front().location.line;
    out.message = FormatDiagnostic(sink.Diagnostics().front());
  }
  return out;
}

// ---- item 8: paths that escape the scene ------------------------------------------------------

TEST(SceneFiles, AMeshInTheSceneFolderLoads) {
  const fs::path dir = Folder("inside");
  Write(dir / "meshes" / "plate.stl", kPlateStl);
  Write(dir / "s.yaml", MeshScene("meshes/plate.stl"));
  const Loaded r = Load(dir / "s.yaml");
  EXPECT_TRUE(r.ok) << r.message;
}

TEST(SceneFiles, RelativeAbsoluteAndSymlinkedPathsOutsideAreRefusedAtTheirLine) {
  const fs::path base = Folder("escape");
  Write(base / "outside" / "plate.stl", kPlateStl);
  const fs::path dir = base / "scene";
  fs::create_directories(dir);
  fs::create_symlink(base / "outside" / "plate.stl", dir / "link.stl");
  for (const std::string& name :
       {std::string("../outside/plate.stl"), (base / "outside" / "plate.stl").string(),
        std::string("link.stl"), std::string("../../../../../../../../etc/passwd")}) {
    SCOPED_TRACE(name);
    Write(dir / "s.yaml", MeshScene(name));
    const Loaded r = Load(dir / "s.yaml");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.code, "scene-path-outside") << r.message;
    EXPECT_EQ(r.line, 6);
  }
  // The flag lifts the refusal: the same outside plate then loads.
  Write(dir / "s.yaml", MeshScene("../outside/plate.stl"));
  LoadOptions allow;
  allow.allow_outside_paths = true;
  const Loaded r = Load(dir / "s.yaml", allow);
  EXPECT_TRUE(r.ok) << r.message;
}

TEST(SceneFiles, AHeadSpecMayNotNameAnMjcfOutsideItsFolderOrTheModels) {
  const fs::path base = Folder("head_escape");
  std::string head = ReadFile(ResolveHeadFile("rs535", {})).value();
  const std::string mjcf = "mjcf: rs535.xml";
  head.replace(head.find(mjcf), mjcf.size(), "mjcf: ../elsewhere/rs535.xml");
  Write(base / "elsewhere" / "rs535.xml", ReadFile(ModelsDir() / "heads" / "rs535.xml").value());
  Write(base / "scene" / "myhead.yaml", head);
  Write(base / "scene" / "s.yaml",
        "stitchsim_scene: 1\nname: m\nunits: mm\nhead: myhead.yaml\npart: {mount: table}\n"
        "surface: {type: plane, size: [200, 200]}\n"
        "paths: [{name: a, type: line, from: [-50, 0], to: [50, 0]}]\n");
  DiagnosticSink sink;
  EXPECT_EQ(LoadScene(base / "scene" / "s.yaml", sink), nullptr);
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "head-path-outside");
  EXPECT_EQ(sink.Diagnostics().front().location.file, (base / "scene" / "myhead.yaml").string());
}

// ---- item 7: directories, FIFOs and devices -----------------------------------------------------

TEST(SceneFiles, ADirectoryOrFifoAsSceneIsADiagnosticNotACrashOrAHang) {
  const fs::path dir = Folder("dir_scene");
  fs::create_directories(dir / "scene.yaml");
  Loaded r = Load(dir / "scene.yaml");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.code, "scene-not-a-file") << r.message;
  ASSERT_EQ(::mkfifo((dir / "fifo.yaml").c_str(), 0600), 0);
  r = Load(dir / "fifo.yaml");  // would block in open() for ever
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.code, "scene-not-a-file") << r.message;
}

TEST(SceneFiles, ADirectoryFifoOrDeviceAsStlIsRefusedAtItsLine) {
  const fs::path dir = Folder("dir_stl");
  fs::create_directories(dir / "plate.stl");
  ASSERT_EQ(::mkfifo((dir / "fifo.stl").c_str(), 0600), 0);
  for (const char* name : {"plate.stl", "fifo.stl", "/dev/zero"}) {
    SCOPED_TRACE(name);
    Write(dir / "s.yaml", MeshScene(name));
    LoadOptions allow;  // /dev/zero lies outside: allow it, to reach the file-type check
    allow.allow_outside_paths = true;
    const Loaded r = Load(dir / "s.yaml", allow);
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.code, "scene-not-a-file") << r.message;
    EXPECT_EQ(r.line, 6);
  }
}

TEST(SceneFiles, AnStlBeyondTheSizeLimitIsRefused) {
  const fs::path dir = Folder("big_stl");
  {
    std::ofstream big(dir / "big.stl", std::ios::binary);
    big << "solid big\n";
    big.seekp(static_cast<std::streamoff>(limits::kMaxStlFileBytes) + 10);
    big << "endsolid\n";  // a sparse file: no disk used
  }
  Write(dir / "s.yaml", MeshScene("big.stl"));
  const Loaded r = Load(dir / "s.yaml");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.code, "scene-bad-mesh") << r.message;
  EXPECT_NE(r.message.find("limit"), std::string::npos) << r.message;
}

TEST(SceneFiles, ADirectoryAsHeadSpecIsADiagnostic) {
  const fs::path dir = Folder("dir_head");
  fs::create_directories(dir / "head.yaml");
  DiagnosticSink sink;
  EXPECT_FALSE(LoadHeadSpec(dir / "head.yaml", sink).has_value());
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "head-not-a-file");
}

// ---- item 9: counts beyond the limits -----------------------------------------------------------

TEST(SceneFiles, MorePathsThanTheLimitAreRefusedAtThePathsKey) {
  const fs::path dir = Folder("many_paths");
  std::string text =
      "stitchsim_scene: 1\nname: m\nunits: mm\nhead: rs535\npart: {mount: table}\n"
      "surface: {type: plane, size: [200, 200]}\npaths:\n";
  for (int i = 0; i <= limits::kMaxScenePaths; ++i) {
    text += "  - {name: p" + std::to_string(i) + ", type: line, from: [-50, 0], to: [50, 0]}\n";
  }
  Write(dir / "s.yaml", text);
  const Loaded r = Load(dir / "s.yaml");
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.code, "scene-too-many-paths") << r.message;
  EXPECT_EQ(r.line, 8);
}

// ---- item 13: duplicate keys ----------------------------------------------------------------

TEST(SceneFiles, AKeyGivenTwiceIsAnErrorAtTheSecond) {
  const fs::path dir = Folder("duplicate");
  Write(dir / "s.yaml",
        "stitchsim_scene: 1\nname: m\nunits: mm\nhead: rs535\npart: {mount: table}\n"
        "surface: {type: plane, size: [200, 200]}\n"
        "stitch: {nominal_length: 5}\n"
        "paths: [{name: a, type: line, from: [-50, 0], to: [50, 0], to: [60, 0]}]\n"
        "stitch: {nominal_length: 4}\n");
  DiagnosticSink sink;
  EXPECT_EQ(LoadScene(dir / "s.yaml", sink), nullptr);
  ASSERT_EQ(sink.ErrorCount(), 2u);
  std::vector<int> lines;
  for (const auto& d : sink.Diagnostics()) {
    EXPECT_EQ(d.code, "scene-duplicate-key") << FormatDiagnostic(d);
    lines.push_back(d.location.line);
  }
  std::sort(lines.begin(), lines.end());
  EXPECT_EQ(lines, (std::vector<int>{8, 9}));
}

// ---- item 10: head-spec numbers converted to int --------------------------------------------

TEST(SceneFiles, HeadSpecCountsOutsideTheirRangeAreRefusedNotConverted) {
  const fs::path dir = Folder("head_counts");
  struct Case {
    std::string head, from, to;
  };
  for (const Case& c :
       {Case{"rs535", "tool_number: 1", "tool_number: 1e300"},
        Case{"rs535", "tool_number: 1", "tool_number: 2.5"}, Case{"afp", "tows: 16", "tows: 6e36"},
        // more tows than M62/M63 can address (program::kMaxTows = 64)
        Case{"afp", "tows: 16", "tows: 65"}}) {
    SCOPED_TRACE(c.to);
    std::string text = ReadFile(ResolveHeadFile(c.head, {})).value();
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, c.from.size(), c.to);
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
    const std::string mjcf = "mjcf: " + c.head + ".xml";
    text.replace(text.find(mjcf), mjcf.size(),
                 "mjcf: " + (ModelsDir() / "heads" / (c.head + ".xml")).string());
    Write(dir / "h.yaml", text);
    DiagnosticSink sink;
    EXPECT_FALSE(LoadHeadSpec(dir / "h.yaml", sink).has_value());
    ASSERT_TRUE(sink.HasErrors());
    EXPECT_EQ(sink.Diagnostics().front().code, "head-out-of-range")
        << FormatDiagnostic(sink.Diagnostics().front());
    EXPECT_EQ(sink.Diagnostics().front().location.line, line);
  }
}

}  // namespace
}  // namespace stitchsim::scene
