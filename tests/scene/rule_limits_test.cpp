// The limit table and its validation (issue 11, typed limits): every override in a scene, a
// head spec or a limits file is checked against the table, with file:line:col and a stable
// code; a unit-suffixed value is converted to the key's unit.
#include "stitchsim/scene/rule_limits.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "scene_test_support.h"
#include "stitchsim/scene/limits_file.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;

fs::path WriteTemp(const std::string& name, const std::string& text) {
  return testing::WriteTemp("rule_limits_test", name, text);
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// ---- the table ------------------------------------------------------------------------------

TEST(LimitTable, OneRowPerKeyEachNamedOnceWithItsUnitInItsName) {
  std::set<std::string> seen;
  std::size_t i = 0;
  for (const LimitSpec& s : LimitTable()) {
    EXPECT_EQ(static_cast<std::size_t>(s.key), i++);
    EXPECT_EQ(&SpecOf(s.key), &s);
    const std::string name(s.name);
    EXPECT_TRUE(seen.insert(std::string(s.rule) + "." + name).second) << name;
    EXPECT_EQ(FindLimit(s.rule, s.name), &s);
    EXPECT_FALSE(s.meaning.empty()) << name;
    const char* suffix = s.unit == LimitUnit::kMm       ? "_mm"
                         : s.unit == LimitUnit::kDeg    ? "_deg"
                         : s.unit == LimitUnit::kPct    ? "_pct"
                         : s.unit == LimitUnit::kNPerMm ? "_n_per_mm"
                                                        : "_fraction";
    EXPECT_TRUE(name.ends_with(suffix)) << name << " is in " << LimitUnitName(s.unit);
  }
  EXPECT_EQ(i, kLimitKeyCount);
  EXPECT_EQ(FindLimit("needle.side_force", "eror_mm"), nullptr);
  EXPECT_FALSE(IsLimitRule("kin.reach"));
}

TEST(RuleLimits, GivenValuesOverDefaultsAbsentWithoutEither) {
  RuleLimits l;
  EXPECT_EQ(l.Get(LimitKey::kSideForceErrorMm), std::nullopt);  // no default: no limit
  EXPECT_EQ(l.Value(LimitKey::kSyncErrorMm), 0.01);             // the table's default
  EXPECT_FALSE(l.IsGiven(LimitKey::kSyncErrorMm));
  l.Set(LimitKey::kSyncErrorMm, 0.5);
  l.Set(LimitKey::kSideForceErrorMm, 0.2);
  EXPECT_TRUE(l.IsGiven(LimitKey::kSyncErrorMm));
  EXPECT_EQ(l.Value(LimitKey::kSyncErrorMm), 0.5);
  EXPECT_EQ(l.Get(LimitKey::kSideForceErrorMm), 0.2);
}

// docs/report-format.md holds the table exactly as the code renders it.
TEST(LimitTable, ReportFormatDocListsTheTable) {
  const std::string doc = ReadText(kSource / "docs/report-format.md");
  const std::string begin = "<!-- limit-table:begin -->\n", end = "<!-- limit-table:end -->";
  const std::size_t b = doc.find(begin), e = doc.find(end);
  ASSERT_NE(b, std::string::npos) << "docs/report-format.md has no " << begin;
  ASSERT_NE(e, std::string::npos) << "docs/report-format.md has no " << end;
  ASSERT_LT(b, e);
  EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), LimitTableMarkdown())
      << "replace the table between the limit-table markers in docs/report-format.md with:\n"
      << LimitTableMarkdown();
}

// Every key of the table is read by some consumer (a key nobody reads is a limit a user sets
// to no effect): each LimitKey enumerator appears in the source of process/, planner/, sim/ or
// verify/, or of scene/ outside the table (scene::MinTowLengthMm, which planner and verify call).
TEST(LimitTable, EveryKeyIsReadBySomeConsumer) {
  const std::string header = ReadText(kSource / "scene/include/stitchsim/scene/rule_limits.h");
  const std::size_t begin = header.find("enum class LimitKey");
  const std::size_t end = header.find("\n  kCount", begin);
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  std::string sources;
  for (const char* folder : {"process/src", "planner/src", "sim/src", "verify/src", "scene/src"}) {
    for (const auto& e : fs::recursive_directory_iterator(kSource / folder)) {
      if (e.path().extension() == ".cpp" && e.path().filename() != "rule_limits.cpp")
        sources += ReadText(e.path());
    }
  }
  std::size_t keys = 0;
  for (std::size_t at = header.find("\n  k", begin); at < end; at = header.find("\n  k", at + 1)) {
    const std::size_t stop = header.find_first_of(",= ", at + 3);
    const std::string name = header.substr(at + 3, stop - at - 3);
    ++keys;
    EXPECT_NE(sources.find("LimitKey::" + name), std::string::npos)
        << "no consumer reads LimitKey::" << name;
  }
  EXPECT_EQ(keys, kLimitKeyCount);
}

// ---- validation -----------------------------------------------------------------------------

struct Problem {
  std::string code, message;
  int line = 0, column = 0;
};

// The first error of loading `text` (after the standard scene header) as a scene.
Problem SceneProblem(const std::string& name, const std::string& limits_lines) {
  const auto p = WriteTemp(name + ".yaml",
                           "stitchsim_scene: 1\nname: l\nunits: mm\nhead: rs535\n"
                           "part: {mount: table}\nsurface: {type: plane, size: [100, 100]}\n"
                           "paths: [{name: a, type: line, from: [0, 0], to: [20, 0]}]\n"
                           "limits:\n" +
                               limits_lines);
  DiagnosticSink sink;
  EXPECT_EQ(LoadScene(p, sink), nullptr) << name;
  if (!sink.HasErrors()) return {};
  const Diagnostic& d = sink.Diagnostics().front();
  EXPECT_EQ(d.location.file, p.string());
  return {d.code, d.message, d.location.line, d.location.column};
}

// The first error of loading the RS535 head spec with `limits_lines` as its limits.
Problem HeadProblem(const std::string& name, const std::string& limits_lines) {
  std::string text = ReadText(kSource / "models/heads/rs535.yaml");
  const std::size_t mjcf = text.find("mjcf: rs535.xml");
  text.replace(mjcf, std::string("mjcf: rs535.xml").size(),
               "mjcf: " + (kSource / "models/heads/rs535.xml").string());
  text = text.substr(0, text.find("\nlimits:\n")) + "\nlimits:\n" + limits_lines;
  const auto p = WriteTemp(name + ".yaml", text);
  DiagnosticSink sink;
  EXPECT_FALSE(LoadHeadSpec(p, sink).has_value()) << name;
  if (!sink.HasErrors()) return {};
  const Diagnostic& d = sink.Diagnostics().front();
  EXPECT_EQ(d.location.file, p.string());
  // Lines counted from the limits: key (the spec above it varies).
  const int limits_line = static_cast<int>(std::count(
                              text.begin(), text.begin() + text.find("\nlimits:\n") + 1, '\n')) +
                          1;
  return {d.code, d.message, d.location.line - limits_line + 8, d.location.column};
}

struct BadLimit {
  const char* name;
  const char* lines;  ///< the limits block (line 9 of the scene is its first line)
  const char* code;   ///< without the "scene-" / "head-" prefix
  int line, column;
  const char* mentions;  ///< the message names this (the nearest known name, the unit)
};

class BadLimits : public ::testing::TestWithParam<BadLimit> {};

TEST_P(BadLimits, SceneAndHeadSpecReportCodeLineAndColumn) {
  const BadLimit& c = GetParam();
  for (const std::string prefix : {"scene", "head"}) {
    const Problem p = prefix == "scene" ? SceneProblem(std::string("s_") + c.name, c.lines)
                                        : HeadProblem(std::string("h_") + c.name, c.lines);
    EXPECT_EQ(p.code, prefix + "-" + c.code) << p.message;
    EXPECT_EQ(p.line, c.line) << prefix << ": " << p.message;
    EXPECT_EQ(p.column, c.column) << prefix << ": " << p.message;
    EXPECT_NE(p.message.find(c.mentions), std::string::npos) << p.message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadLimits,
    ::testing::Values(BadLimit{"unknown_rule", "  needle.sideforce: {error_mm: 0.1}\n",
                               "unknown-rule", 9, 3, "'needle.side_force'"},
                      BadLimit{"unknown_key",
                               "  stitch.length: {warning_pct: 5}\n  needle.walk: {eror_mm: 4}\n",
                               "unknown-limit", 10, 17, "'error_mm'"},
                      BadLimit{"wrong_unit", "  needle.side_force: {error_mm: 3 deg}\n",
                               "limit-unit", 9, 33, "mm"},
                      BadLimit{"unknown_unit", "  stitch.normality:\n    error_deg: 5 furlongs\n",
                               "limit-unit", 10, 16, "deg|rad"},
                      BadLimit{"percent_for_mm", "  stitch.standoff: {error_mm: 5 %}\n",
                               "limit-unit", 9, 31, "mm|in|m"},
                      BadLimit{"negative", "  stitch.standoff: {error_mm: -1}\n", "out-of-range", 9,
                               31, "stitch.standoff.error_mm"},
                      BadLimit{"not_a_number", "  kin.joint_speed: {max_fraction: fast}\n",
                               "bad-number", 9, 35, "kin.joint_speed.max_fraction"}),
    [](const ::testing::TestParamInfo<BadLimit>& i) { return std::string(i.param.name); });

TEST(Limits, ALimitsFileIsValidatedAsAScene) {
  DiagnosticSink load;
  auto scene = LoadScene(kSource / "scenes/flat_straight.yaml", load);
  ASSERT_NE(scene, nullptr);
  const auto p =
      WriteTemp("tight.limits.yaml",
                "limits:\n  stitch.standoff: {error_mm: 1}\n  kin.reach: {error_mm: 1}\n");
  DiagnosticSink sink;
  EXPECT_FALSE(ApplyLimitsFile(p, *scene, sink));
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "limits-unknown-rule");
  EXPECT_EQ(sink.Diagnostics().front().location.line, 3);
  EXPECT_EQ(scene->limits.Get(LimitKey::kStandoffErrorMm), 2.0);  // unchanged
  const auto ok = WriteTemp("ok.limits.yaml", "limits:\n  stitch.standoff: {error_mm: 0.04 in}\n");
  DiagnosticSink fine;
  EXPECT_TRUE(ApplyLimitsFile(ok, *scene, fine));
  EXPECT_DOUBLE_EQ(*scene->limits.Get(LimitKey::kStandoffErrorMm), 0.04 * 25.4);
}

// Two routes to one value: a number with a unit equals the bare number in the key's unit.
TEST(Limits, UnitSuffixedValuesConvertToTheKeysUnit) {
  const auto p = WriteTemp("units.yaml",
                           "stitchsim_scene: 1\nname: u\nunits: in\nhead: rs535\n"
                           "part: {mount: table}\nsurface: {type: plane, size: [4, 4]}\n"
                           "paths: [{name: a, type: line, from: [0, 0], to: [1, 0]}]\n"
                           "limits:\n"
                           "  needle.side_force: {error_mm: 0.02 in, warning_mm: '0.001m',\n"
                           "                      stiffness_n_per_mm: 40 N/mm}\n"
                           "  stitch.normality: {error_deg: 0.1 rad, warning_deg: 3 deg}\n"
                           "  stitch.length: {error_pct: 12 %}\n"
                           "  kin.joint_speed: {max_fraction: 80 %}\n"
                           "  needle.walk: {error_mm: 0.1 in}\n");
  DiagnosticSink sink;
  auto scene = LoadScene(p, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  ASSERT_NE(scene, nullptr);
  const RuleLimits& l = scene->limits;
  EXPECT_DOUBLE_EQ(*l.Get(LimitKey::kSideForceErrorMm), 0.508);
  EXPECT_DOUBLE_EQ(*l.Get(LimitKey::kSideForceWarningMm), 1.0);
  EXPECT_DOUBLE_EQ(*l.Get(LimitKey::kSideForceStiffness), 40.0);
  EXPECT_DOUBLE_EQ(*l.Get(LimitKey::kNormalityErrorDeg), 0.1 * 180.0 / kPi);
  EXPECT_DOUBLE_EQ(*l.Get(LimitKey::kNormalityWarningDeg), 3.0);
  EXPECT_DOUBLE_EQ(*l.Get(LimitKey::kStitchLengthErrorPct), 12.0);
  EXPECT_DOUBLE_EQ(l.Value(LimitKey::kJointSpeedMaxFraction), 0.8);
  EXPECT_DOUBLE_EQ(*l.Get(LimitKey::kWalkErrorMm), 2.54);
  EXPECT_EQ(l.Get(LimitKey::kStandoffErrorMm), 2.0);  // the head's, untouched
}

TEST(Limits, BareNumbersAreInTheKeysUnitWhateverTheSceneUnits) {
  const auto p = WriteTemp("bare_in.yaml",
                           "stitchsim_scene: 1\nname: u\nunits: in\nhead: rs535\n"
                           "part: {mount: table}\nsurface: {type: plane, size: [4, 4]}\n"
                           "paths: [{name: a, type: line, from: [0, 0], to: [1, 0]}]\n"
                           "limits: {stitch.standoff: {error_mm: 1.5}}\n");
  DiagnosticSink sink;
  auto scene = LoadScene(p, sink);
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(scene->limits.Get(LimitKey::kStandoffErrorMm), 1.5);
}

}  // namespace
}  // namespace stitchsim::scene
