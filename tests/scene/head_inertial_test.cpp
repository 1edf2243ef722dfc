// The head spec's `inertial:` block: the bundled heads' mass properties read back, and bad
// blocks refused with head-bad-inertial at their line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "scene_test_support.h"
#include "stitchsim/common/files.h"
#include "stitchsim/scene/head_spec.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;

std::string FormatAll(const DiagnosticSink& sink) {
  std::string out;
  for (const Diagnostic& d : sink.Diagnostics()) out += FormatDiagnostic(d) + "\n";
  return out;
}

TEST(HeadInertial, BundledHeadsReadBack) {
  struct Expected {
    std::string head;
    double mass_kg;
    Eigen::Vector3d com_m;
    double ixz;
  };
  for (const Expected& e : {Expected{"rs535", 110.0, {0.008, 0.004, 0.256}, 0.0},
                            Expected{"rs566", 160.0, {-0.117, 0.0, 0.312}, 1.39},
                            Expected{"afp", 350.0, {0.0, 0.015, 0.31}, 0.0}}) {
    SCOPED_TRACE(e.head);
    DiagnosticSink sink;
    const std::optional<HeadSpec> spec = LoadHeadSpec(ResolveHeadFile(e.head, {}), sink);
    ASSERT_TRUE(spec.has_value()) << FormatAll(sink);
    ASSERT_TRUE(spec->inertial.has_value());
    EXPECT_DOUBLE_EQ(spec->inertial->mass_kg, e.mass_kg);
    EXPECT_LT((spec->inertial->com_m - e.com_m).norm(), 1e-15);  // mm in the file
    const Eigen::Matrix3d& inertia = spec->inertial->inertia_kg_m2;
    EXPECT_EQ(inertia, inertia.transpose());
    EXPECT_DOUBLE_EQ(inertia(0, 2), e.ixz);
    EXPECT_GT(inertia.diagonal().minCoeff(), 0.0);
  }
}

TEST(HeadInertial, ThreeValuesAreTheDiagonal) {
  DiagnosticSink sink;
  const std::optional<HeadSpec> spec = LoadHeadSpec(ResolveHeadFile("rs535", {}), sink);
  ASSERT_TRUE(spec && spec->inertial) << FormatAll(sink);
  Eigen::Matrix3d expected = Eigen::Vector3d(3.37, 3.98, 2.21).asDiagonal();
  EXPECT_EQ(spec->inertial->inertia_kg_m2, expected);
}

TEST(HeadInertial, AHeadWithoutItLoads) {
  std::string text = ReadFile(ResolveHeadFile("rs535", {})).value();
  const std::size_t at = text.find("inertial:");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find("inertia_kg_m2:", at) - at);
  text.erase(at, text.find('\n', at) + 1 - at);
  const std::string mjcf = "mjcf: rs535.xml";
  text.replace(text.find(mjcf), mjcf.size(),
               "mjcf: " + (ModelsDir() / "heads" / "rs535.xml").string());
  const fs::path dir = testing::Folder("head_inertial", "none");
  testing::Write(dir / "h.yaml", text);
  DiagnosticSink sink;
  const std::optional<HeadSpec> spec = LoadHeadSpec(dir / "h.yaml", sink);
  ASSERT_TRUE(spec.has_value()) << FormatAll(sink) << text;
  EXPECT_FALSE(spec->inertial.has_value());
}

TEST(HeadInertial, BadBlocksAreRefusedAtTheirLine) {
  const fs::path dir = testing::Folder("head_inertial", "bad");
  struct Case {
    std::string from, to, code;
  };
  const std::string bad = "head-bad-inertial";
  const std::string mass = "mass_kg: 110";
  const std::string inertia = "inertia_kg_m2: [3.37, 3.98, 2.21]";
  for (const Case& c : {
           Case{mass, "mass_kg: 0", bad},
           Case{mass, "mass_kg: -110", bad},
           Case{mass, "mass_kg: .inf", bad},
           Case{mass, "mass_kg: heavy", bad},
           Case{"com_mm: [8, 4, 256]", "com_mm: [8, 4]", bad},
           Case{"com_mm: [8, 4, 256]", "com_mm: [8, .nan, 256]", bad},
           Case{inertia, "inertia_kg_m2: [3.37, 3.98, 2.21, 0]", bad},        // wrong count
           Case{inertia, "inertia_kg_m2: 3.37", bad},                         // not a list
           Case{inertia, "inertia_kg_m2: [3.37, -3.98, 2.21]", bad},          // not definite
           Case{inertia, "inertia_kg_m2: [3.37, 3.98, 2.21, 5, 0, 0]", bad},  // indefinite
           Case{inertia, "inertia_kg_m2: [1, 1, 3]", bad},                    // triangle
           Case{mass, "mass: 110", "head-unknown-key"},
       }) {
    SCOPED_TRACE(c.to);
    std::string text = ReadFile(ResolveHeadFile("rs535", {})).value();
    const std::size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, c.from.size(), c.to);
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
    const std::string mjcf = "mjcf: rs535.xml";
    text.replace(text.find(mjcf), mjcf.size(),
                 "mjcf: " + (ModelsDir() / "heads" / "rs535.xml").string());
    testing::Write(dir / "h.yaml", text);
    DiagnosticSink sink;
    EXPECT_FALSE(LoadHeadSpec(dir / "h.yaml", sink).has_value());
    const auto d = std::find_if(sink.Diagnostics().begin(), sink.Diagnostics().end(),
                                [&](const Diagnostic& x) { return x.code == c.code; });
    ASSERT_NE(d, sink.Diagnostics().end()) << FormatAll(sink);
    EXPECT_EQ(d->location.line, line) << FormatAll(sink);
    EXPECT_EQ(d->location.file, (dir / "h.yaml").string());
  }
}

}  // namespace
}  // namespace stitchsim::scene
