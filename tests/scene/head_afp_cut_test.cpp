// The AFP head's cut and restart parameters (`afp:` in a head spec, issue 29): the bundled
// head's values read back, a head without them loads with none given, and bad values are
// refused at their line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "scene_test_support.h"
#include "stitchsim/common/files.h"
#include "stitchsim/scene/head_spec.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;

// The bundled AFP head's text, `from` replaced by `to`, with its MJCF path made absolute;
// `line` gets the 1-based line of the replacement.
std::string AfpHeadText(const std::string& from, const std::string& to, long* line = nullptr) {
  std::string text = ReadFile(ResolveHeadFile("afp", {})).value();
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  text.replace(at, from.size(), to);
  if (line) *line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  const std::string mjcf = "mjcf: afp.xml";
  text.replace(text.find(mjcf), mjcf.size(),
               "mjcf: " + (ModelsDir() / "heads" / "afp.xml").string());
  return text;
}

TEST(HeadAfpCut, BundledHeadReadsBack) {
  DiagnosticSink sink;
  const std::optional<HeadSpec> spec = LoadHeadSpec(ResolveHeadFile("afp", {}), sink);
  ASSERT_TRUE(spec.has_value());
  ASSERT_TRUE(spec->afp.cut_to_roller_mm.has_value());
  EXPECT_EQ(*spec->afp.cut_to_roller_mm, 100.0);
  ASSERT_TRUE(spec->afp.min_restart_mm.has_value());
  EXPECT_EQ(*spec->afp.min_restart_mm, 100.0);
  EXPECT_EQ(spec->afp.cut_add_feed_mm_s, 150.0);
  EXPECT_EQ(spec->afp.cut_add_zone_mm, 25.0);
}

TEST(HeadAfpCut, WithoutThemNoneIsGiven) {
  std::string text = AfpHeadText("  cut_to_roller_mm: 100\n", "");
  for (const char* key :
       {"  min_restart_mm: 100\n", "  cut_add_feed_mm_s: 150\n", "  cut_add_zone_mm: 25\n"}) {
    text.erase(text.find(key), std::string(key).size());
  }
  const fs::path dir = testing::Folder("head_afp_cut", "none");
  testing::Write(dir / "h.yaml", text);
  DiagnosticSink sink;
  const std::optional<HeadSpec> spec = LoadHeadSpec(dir / "h.yaml", sink);
  ASSERT_TRUE(spec.has_value()) << text;
  EXPECT_FALSE(spec->afp.cut_to_roller_mm.has_value());
  EXPECT_FALSE(spec->afp.min_restart_mm.has_value());
  EXPECT_EQ(spec->afp.cut_add_feed_mm_s, 0.0);  // no slow-down
  EXPECT_EQ(spec->afp.cut_add_zone_mm, 0.0);
}

TEST(HeadAfpCut, BadValuesAreRefusedAtTheirLine) {
  struct Case {
    std::string from, to, code;
  };
  const std::string range = "head-out-of-range";
  for (const Case& c : {Case{"cut_to_roller_mm: 100", "cut_to_roller_mm: -100", range},
                        Case{"cut_to_roller_mm: 100", "cut_to_roller_mm: 0", range},
                        Case{"min_restart_mm: 100", "min_restart_mm: -1", range},
                        Case{"cut_add_feed_mm_s: 150", "cut_add_feed_mm_s: 0", range},
                        Case{"cut_add_zone_mm: 25", "cut_add_zone_mm: -25", range},
                        Case{"  cut_add_zone_mm: 25\n", "", "head-missing-key"}}) {
    SCOPED_TRACE(c.to);
    long line = 0;
    const std::string text = AfpHeadText(c.from, c.to, &line);
    const fs::path dir = testing::Folder("head_afp_cut", "bad");
    testing::Write(dir / "h.yaml", text);
    DiagnosticSink sink;
    EXPECT_FALSE(LoadHeadSpec(dir / "h.yaml", sink).has_value());
    const auto d = std::find_if(sink.Diagnostics().begin(), sink.Diagnostics().end(),
                                [&](const Diagnostic& x) { return x.code == c.code; });
    ASSERT_NE(d, sink.Diagnostics().end())
        << (sink.Diagnostics().empty() ? std::string("no diagnostic")
                                       : FormatDiagnostic(sink.Diagnostics()[0]));
    // A value at its own line.
    if (c.to.empty()) {  // the zone missing: reported at the feed given without it
      const std::size_t feed = text.find("cut_add_feed_mm_s:");
      line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(feed), '\n');
    }
    EXPECT_EQ(d->location.line, line);
    EXPECT_EQ(d->location.file, (dir / "h.yaml").string());
  }
}

}  // namespace
}  // namespace stitchsim::scene
