// Scene loading: every bundled scene loads clean; broken scenes give file:line diagnostics.
#include "stitchsim/scene/scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "scene_test_support.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

fs::path WriteTemp(const std::string& name, const std::string& text) {
  return testing::WriteTemp("scene_test", name, text);
}

TEST(Scene, EveryBundledSceneLoadsWithoutDiagnostics) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(kSource / "scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    DiagnosticSink sink;
    auto scene = LoadScene(entry.path(), sink);
    for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
    ASSERT_NE(scene, nullptr) << entry.path();
    EXPECT_FALSE(scene->paths.empty());
    EXPECT_NE(scene->surface, nullptr);
    ++count;
  }
  EXPECT_GE(count, 6);
}

TEST(Scene, UnitsConvertToMillimetres) {
  DiagnosticSink sink;
  auto scene = LoadScene(kSource / "scenes/circle_8in.yaml", sink);
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(scene->units, LengthUnit::kInch);
  EXPECT_DOUBLE_EQ(scene->preform_thickness_mm, 12.0);
  EXPECT_DOUBLE_EQ(scene->nominal_stitch_length_mm, 5.0);
  const PathSpec* circle = scene->FindPath("circle");
  ASSERT_NE(circle, nullptr);
  geom::SurfacePath path(*scene->surface, *circle->curve);
  EXPECT_NEAR(path.Length(), 2 * kPi * 8 * 25.4, 1e-6);
  EXPECT_TRUE(path.Closed());
  EXPECT_NEAR(scene->mount_to_part_m.translation().z(), 2 * 0.0254, 1e-12);
}

TEST(Scene, HeadDefaultsComeFromTheHeadSpec) {
  DiagnosticSink sink;
  auto scene = LoadScene(kSource / "scenes/flat_straight.yaml", sink);
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(scene->head.name, "rs535");
  EXPECT_EQ(scene->head.kind, HeadKind::kSingleSidedStitch);
  ASSERT_EQ(scene->head.needles.size(), 2u);
  EXPECT_DOUBLE_EQ(scene->head.stitch.width_mm, 17.0);
  EXPECT_DOUBLE_EQ(scene->head.stitch.phase_in, 0.15);
  EXPECT_DOUBLE_EQ(scene->head.stitch.phase_out, 0.85);
  EXPECT_EQ(scene->limits.Get(LimitKey::kSideForceErrorMm), 0.10);
  // Tool z is the flange z turned over.
  EXPECT_NEAR(scene->head.flange_to_tool_m.linear()(2, 2), -1.0, 1e-12);
  EXPECT_NEAR(scene->head.flange_to_tool_m.translation().z(), 0.7, 1e-12);
}

TEST(Scene, LimitOverridesMergeKeyByKey) {
  const auto p = WriteTemp("override.yaml", R"(stitchsim_scene: 1
name: o
units: mm
head: rs535
part: {mount: rotator}
surface: {type: plane, size: [100, 100]}
paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]
limits:
  needle.side_force: {error_mm: 0.2}
)");
  DiagnosticSink sink;
  auto scene = LoadScene(p, sink);
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(scene->mount, Mount::kRotator);
  EXPECT_EQ(scene->limits.Get(LimitKey::kSideForceErrorMm), 0.2);
  EXPECT_EQ(scene->limits.Get(LimitKey::kSideForceWarningMm), 0.07);
}

struct BrokenCase {
  const char* name;
  const char* text;
  const char* code;
  int line;
};

constexpr const char* kHeader = "stitchsim_scene: 1\nname: b\nunits: mm\nhead: rs535\n";

class BrokenScene : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenScene, GivesItsCodeAndLine) {
  const BrokenCase& c = GetParam();
  const auto p = WriteTemp(std::string(c.name) + ".yaml", std::string(kHeader) + c.text);
  DiagnosticSink sink;
  auto scene = LoadScene(p, sink);
  EXPECT_EQ(scene, nullptr);
  ASSERT_TRUE(sink.HasErrors());
  const Diagnostic& d = sink.Diagnostics().front();
  EXPECT_EQ(d.code, c.code) << FormatDiagnostic(d);
  EXPECT_EQ(d.location.line, c.line) << FormatDiagnostic(d);
  EXPECT_EQ(d.location.file, p.string());
  const std::string text = FormatDiagnostic(d);
  EXPECT_NE(text.find(p.string() + ":" + std::to_string(c.line) + ":"), std::string::npos) << text;
  EXPECT_NE(text.find("error[" + std::string(c.code) + "]"), std::string::npos) << text;
}

constexpr const char* kPart = "part: {mount: table}\n";
constexpr const char* kPlane = "surface: {type: plane, size: [100, 100]}\n";
constexpr const char* kPath = "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n";

// Lines: the header takes lines 1-4, so the case text starts at line 5.
INSTANTIATE_TEST_SUITE_P(
    Cases, BrokenScene,
    ::testing::Values(
        BrokenCase{"bad_yaml", "part: {mount: table\nsurface: [\n", "scene-yaml-syntax", 6},
        BrokenCase{"unknown_key",
                   "part: {mount: table}\nsurfce: {type: plane, size: [1, 1]}\n"
                   "surface: {type: plane, size: [100, 100]}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-unknown-key", 6},
        BrokenCase{"negative_radius",
                   "part: {mount: table}\n"
                   "surface: {type: cylinder, side: outside, length: 100, arc_length: 50,\n"
                   "          radius: -5}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-out-of-range", 7},
        BrokenCase{"nan_value",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, .nan]}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-not-finite", 6},
        BrokenCase{"missing_stl",
                   "part: {mount: table}\nsurface: {type: mesh, file: nope.stl}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-missing-file", 6},
        BrokenCase{"unknown_head_type",
                   "part: {mount: shelf}\nsurface: {type: plane, size: [100, 100]}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-bad-value", 5},
        BrokenCase{"bad_unit",
                   "part: {mount: table}\nsurface: {type: plane, size: [100 furlong, 100]}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-bad-unit", 6},
        BrokenCase{"path_off_surface",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n"
                   "paths:\n  - {name: a, type: line, from: [0, 0], to: [200, 0]}\n",
                   "scene-path-off-surface", 8},
        BrokenCase{"duplicate_path",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n"
                   "paths:\n  - {name: a, type: line, from: [0, 0], to: [20, 0]}\n"
                   "  - {name: a, type: line, from: [0, 5], to: [20, 5]}\n",
                   "scene-duplicate-name", 9},
        BrokenCase{"missing_paths",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n",
                   "scene-missing-key", 1},
        BrokenCase{"number_is_text",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n"
                   "paths: [{name: a, type: arc, center: [0, 0], radius: 10, start_deg: zero,\n"
                   "         end_deg: 90}]\n",
                   "scene-bad-number", 7},
        BrokenCase{"zero_sweep_arc",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n"
                   "paths:\n  - {name: a, type: arc, center: [0, 0], radius: 10, start_deg: 5, "
                   "end_deg: 5}\n",
                   "scene-degenerate-path", 8},
        BrokenCase{"infinite_thickness",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n"
                   "preform: {thickness: .inf}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-not-finite", 7},
        BrokenCase{"omit_unknown_fixture",
                   "cell:\n  omit: [rotator, crane]\npart: {mount: table}\n"
                   "surface: {type: plane, size: [100, 100]}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-bad-value", 6},
        BrokenCase{"omit_not_a_list",
                   "cell: {omit: table}\npart: {mount: rotator}\n"
                   "surface: {type: plane, size: [100, 100]}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-type", 5},
        BrokenCase{"negative_raster_margin",
                   "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n"
                   "raster:\n  row_spacing: 4\n  margin: -1\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-out-of-range", 9},
        BrokenCase{"bad_surface_type",
                   "part: {mount: table}\nsurface: {type: torus}\n"
                   "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n",
                   "scene-bad-value", 6}),
    [](const ::testing::TestParamInfo<BrokenCase>& info) { return std::string(info.param.name); });

TEST(Scene, MissingSceneFile) {
  DiagnosticSink sink;
  auto scene = LoadScene("/nonexistent/scene.yaml", sink);
  EXPECT_EQ(scene, nullptr);
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "scene-missing-file");
}

TEST(Scene, UnknownHead) {
  const auto p = WriteTemp("unknown_head.yaml",
                           std::string("stitchsim_scene: 1\nname: b\nunits: mm\nhead: rs999\n") +
                               kPart + kPlane + kPath);
  DiagnosticSink sink;
  EXPECT_EQ(LoadScene(p, sink), nullptr);
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "scene-unknown-head");
  EXPECT_EQ(sink.Diagnostics().front().location.line, 4);
}

TEST(Scene, BrokenHeadSpecPointsIntoTheHeadFile) {
  const auto head = WriteTemp("broken_head.yaml", "stitchsim_head: 1\nname: x\nkind: laser\n");
  const auto p = WriteTemp("uses_broken_head.yaml",
                           "stitchsim_scene: 1\nname: b\nunits: mm\nhead: " + head.string() + "\n" +
                               kPart + kPlane + kPath);
  DiagnosticSink sink;
  EXPECT_EQ(LoadScene(p, sink), nullptr);
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().location.file, head.string());
  EXPECT_EQ(sink.Diagnostics().front().code, "head-bad-value");
  EXPECT_EQ(sink.Diagnostics().front().location.line, 3);
}

// The head envelope: both keys required and positive, reported in the head file; the
// bundled RS535 spec gives one.
TEST(Scene, HeadEnvelopeIsReadAndChecked) {
  DiagnosticSink ok_sink;
  const auto rs535 = LoadHeadSpec(ResolveHeadFile("rs535", {}), ok_sink);
  ASSERT_TRUE(rs535.has_value());
  ASSERT_TRUE(rs535->envelope.has_value());
  EXPECT_EQ(rs535->envelope->height_mm, 60.0);
  EXPECT_EQ(rs535->envelope->radius_mm, 44.0);
  std::string text = ReadFile(ResolveHeadFile("rs535", {})).value();
  const std::string good = "envelope: {height_mm: 60, radius_mm: 44}";
  const auto at = text.find(good);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, good.size(), "envelope: {height_mm: 60, radius_mm: -4}");
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  // The copy lives in the temp folder: its mjcf path made absolute (same line count).
  const std::string mjcf = "mjcf: rs535.xml";
  const auto m = text.find(mjcf);
  ASSERT_NE(m, std::string::npos);
  text.replace(m, mjcf.size(), "mjcf: " + rs535->mjcf.string());
  const auto copy = WriteTemp("envelope_head.yaml", text);
  DiagnosticSink sink;
  EXPECT_FALSE(LoadHeadSpec(copy, sink).has_value());
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "head-out-of-range");
  EXPECT_EQ(sink.Diagnostics().front().location.line, line);
}

// The AFP head's `sequence:` block (docs/sequence.md): read with its defaults; a negative
// weight, an unknown key and a non-number are errors at their line.
TEST(Scene, HeadSequenceBlockIsReadAndChecked) {
  DiagnosticSink ok_sink;
  const auto afp = LoadHeadSpec(ResolveHeadFile("afp", {}), ok_sink);
  ASSERT_TRUE(afp.has_value());
  EXPECT_EQ(afp->sequence.retract_mm, 100.0);
  EXPECT_EQ(afp->sequence.clearance_mm, 100.0);
  ASSERT_EQ(afp->sequence.axis_weights.size(), 8u);
  EXPECT_EQ(afp->sequence.axis_weights.front().joint, "rail_x");
  const std::string text = ReadFile(ResolveHeadFile("afp", {})).value();
  struct Case {
    std::string good, bad, code;
  };
  for (const Case& c :
       std::vector<Case>{{"    a3: 0.0142857", "    a3: -1", "head-out-of-range"},
                         {"    a3: 0.0142857", "    a3: fast", "head-bad-number"},
                         {"  retract_mm: 100", "  retract: 100", "head-unknown-key"},
                         {"  clearance_mm: 100", "  clearance_mm: 0", "head-out-of-range"}}) {
    const auto at = text.find(c.good);
    ASSERT_NE(at, std::string::npos) << c.good;
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
    std::string copy = text;
    copy.replace(at, c.good.size(), c.bad);
    const std::string mjcf = "mjcf: afp.xml";
    const auto m = copy.find(mjcf);
    ASSERT_NE(m, std::string::npos);
    copy.replace(m, mjcf.size(), "mjcf: " + afp->mjcf.string());
    DiagnosticSink sink;
    EXPECT_FALSE(LoadHeadSpec(WriteTemp("sequence_head.yaml", copy), sink).has_value()) << c.bad;
    ASSERT_TRUE(sink.HasErrors()) << c.bad;
    EXPECT_EQ(sink.Diagnostics().front().code, c.code) << c.bad;
    EXPECT_EQ(sink.Diagnostics().front().location.line, line) << c.bad;
  }
}

}  // namespace
}  // namespace stitchsim::scene
