// DiffReports on hand-built reports: findings matched by position (lines shifted: no change;
// moved: appeared and disappeared), then by stitch, line or order for findings without a
// position; value and severity changes; truncated rules compared by counts; the exit rule;
// the JSON, JUnit and text forms read back.

#include "stitchsim/verify/report_diff.h"

#include <gtest/gtest.h>

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace stitchsim::verify {
namespace {

using Json = nlohmann::json;
using Position = std::array<double, 3>;

constexpr FindingSeverity kError = FindingSeverity::kError;
constexpr FindingSeverity kWarning = FindingSeverity::kWarning;

Finding MakeFinding(const std::string& rule, FindingSeverity severity, int line, long stitch,
                    double value, std::optional<Position> position,
                    const std::string& subject = "insertion") {
  Finding f;
  f.rule = rule;
  f.severity = severity;
  f.line = line;
  f.stitch = stitch;
  f.value = value;
  f.limit = 1.0;
  f.unit = "mm";
  f.subject = subject;
  f.message = rule + " at line " + std::to_string(line);
  f.position_mm = position;
  return f;
}

// A rule holding `findings`, its counts those of the findings unless `extra_errors` more
// were found past the cap (then truncated).
RuleSummary MakeRule(const std::string& id, std::vector<Finding> findings, long extra_errors = 0) {
  RuleSummary r;
  r.id = id;
  r.unit = "mm";
  r.checked = 1000;
  for (const Finding& f : findings) ++(f.severity == kError ? r.errors : r.warnings);
  r.errors += extra_errors;
  r.truncated = extra_errors > 0;
  r.findings = std::move(findings);
  return r;
}

Report MakeReport(const std::string& program, std::vector<RuleSummary> rules) {
  Report r;
  r.program_file = program;
  r.scene_file = "scenes/s.yaml";
  r.scene_name = "s";
  r.head = "rs535";
  r.stitches = 100;
  r.cycle_time_s = 50.0;
  r.cycle_time_timed_s = 60.0;
  for (const RuleSummary& rule : rules) {
    r.errors += rule.errors;
    r.warnings += rule.warnings;
  }
  r.verdict = r.errors == 0 ? "pass" : "fail";
  r.rules = std::move(rules);
  return r;
}

// Positions along a row 10 mm apart.
Position At(double x) { return {x, 20.0, 3.0}; }

TEST(ReportDiff, AReportAgainstItselfHasNoChange) {
  const Report r = MakeReport(
      "a.nc", {MakeRule("needle.side_force",
                        {MakeFinding("needle.side_force", kError, 12, 3, 2.0, At(10.0)),
                         MakeFinding("needle.side_force", kWarning, 14, 4, 1.5, At(20.0))}),
               MakeRule("program.stitch_count", {MakeFinding("program.stitch_count", kError, 0, 0,
                                                             99.0, std::nullopt, "")})});
  const ReportDiff d = DiffReports(r, r, {});
  EXPECT_TRUE(d.findings.empty());
  EXPECT_EQ(d.appeared + d.disappeared + d.changed, 0);
  EXPECT_FALSE(d.new_errors);
  ASSERT_EQ(d.rules.size(), 2u);
  EXPECT_FALSE(d.rules[0].CountsChanged());
}

TEST(ReportDiff, ShiftedLinesAndStitchesAreNoChange) {
  // Ten lines inserted and one stitch more before every finding: positions stay, numbers move.
  std::vector<Finding> old_f, new_f;
  for (int k = 0; k < 5; ++k) {
    old_f.push_back(MakeFinding("stitch.width", kError, 100 + 10 * k, 20 + k, 1.0 + k, At(k)));
    new_f.push_back(MakeFinding("stitch.width", kError, 110 + 10 * k, 21 + k, 1.0 + k, At(k)));
  }
  // Without positions: by stitch shifted as the nearest position match (+1), by line shifted
  // likewise (+10).
  old_f.push_back(MakeFinding("stitch.width", kWarning, 300, 40, 0.5, std::nullopt));
  new_f.push_back(MakeFinding("stitch.width", kWarning, 310, 41, 0.5, std::nullopt));
  std::vector<Finding> old_c = {
      MakeFinding("constraint.crossing", kError, 120, 0, 2.0, std::nullopt, "stringer")};
  std::vector<Finding> new_c = {
      MakeFinding("constraint.crossing", kError, 130, 0, 2.0, std::nullopt, "stringer")};
  const Report old =
      MakeReport("a.nc", {MakeRule("stitch.width", old_f), MakeRule("constraint.crossing", old_c)});
  const Report neu =
      MakeReport("b.nc", {MakeRule("stitch.width", new_f), MakeRule("constraint.crossing", new_c)});
  const ReportDiff d = DiffReports(old, neu, {});
  EXPECT_TRUE(d.findings.empty()) << ReportDiffToText(d);
  EXPECT_FALSE(d.new_errors);

  // The same stitch number unshifted is another stitch: the finding moved.
  Report moved = neu;
  moved.rules[0].findings[5].stitch = 40;
  const ReportDiff m = DiffReports(old, moved, {});
  EXPECT_EQ(m.appeared, 1);
  EXPECT_EQ(m.disappeared, 1);
  EXPECT_FALSE(m.new_errors);  // a warning
}

TEST(ReportDiff, AMovedPositionIsAppearedAndDisappeared) {
  const auto report = [](double x, int line) {
    return MakeReport(
        "p.nc",
        {MakeRule("needle.walk", {MakeFinding("needle.walk", kError, line, 7, 2.0, At(x))})});
  };
  const Report old = report(100.0, 50);
  // Within the tolerance (0.4 mm < 0.5 mm), on another line: the same finding.
  EXPECT_TRUE(DiffReports(old, report(100.4, 60), {}).findings.empty());
  // 0.6 mm away: another place.
  const ReportDiff d = DiffReports(old, report(100.6, 50), {});
  ASSERT_EQ(d.findings.size(), 2u);
  EXPECT_EQ(d.appeared, 1);
  EXPECT_EQ(d.disappeared, 1);
  EXPECT_TRUE(d.new_errors);  // the error at the new place is new
  // A wider tolerance takes them as one.
  DiffOptions wide;
  wide.position_tolerance_mm = 1.0;
  EXPECT_TRUE(DiffReports(old, report(100.6, 50), wide).findings.empty());
  // Another subject at the same place is another finding.
  Report other = old;
  other.rules[0].findings[0].subject = "catcher";
  EXPECT_EQ(DiffReports(old, other, {}).appeared, 1);
}

TEST(ReportDiff, NearestPositionsArePairedFirst) {
  const Report old = MakeReport(
      "p.nc", {MakeRule("kin.reach", {MakeFinding("kin.reach", kError, 10, 1, 1.0, At(0.0)),
                                      MakeFinding("kin.reach", kError, 11, 2, 2.0, At(0.45))})});
  // New: one finding at 0.4 mm: closer to the second old one (0.05 mm) than to the first.
  const Report neu = MakeReport(
      "p.nc", {MakeRule("kin.reach", {MakeFinding("kin.reach", kError, 11, 2, 2.0, At(0.4))})});
  const ReportDiff d = DiffReports(old, neu, {});
  ASSERT_EQ(d.findings.size(), 1u);
  EXPECT_EQ(d.findings[0].change, FindingChange::kDisappeared);
  EXPECT_EQ(d.findings[0].old_finding->line, 10);
}

TEST(ReportDiff, ValueAndSeverityChanges) {
  const auto report = [](FindingSeverity s, double value) {
    return MakeReport("p.nc", {MakeRule("needle.side_force", {MakeFinding("needle.side_force", s,
                                                                          30, 9, value, At(5))})});
  };
  const Report old = report(kWarning, 10.0);
  EXPECT_TRUE(DiffReports(old, report(kWarning, 10.09), {}).findings.empty());  // 0.9 %
  const ReportDiff d = DiffReports(old, report(kWarning, 10.2), {});            // 2 %
  ASSERT_EQ(d.findings.size(), 1u);
  EXPECT_EQ(d.findings[0].change, FindingChange::kChanged);
  EXPECT_EQ(d.findings[0].match, FindingMatch::kPosition);
  EXPECT_DOUBLE_EQ(d.findings[0].old_finding->value, 10.0);
  EXPECT_DOUBLE_EQ(d.findings[0].new_finding->value, 10.2);
  EXPECT_FALSE(d.new_errors);
  EXPECT_NE(ReportDiffToText(d).find("10 -> 10.2 mm"), std::string::npos) << ReportDiffToText(d);
  DiffOptions loose;
  loose.value_tolerance_pct = 5.0;
  EXPECT_TRUE(DiffReports(old, report(kWarning, 10.2), loose).findings.empty());
  // Warning to error: changed, and a new error.
  const ReportDiff worse = DiffReports(old, report(kError, 10.0), {});
  ASSERT_EQ(worse.changed, 1);
  EXPECT_TRUE(worse.new_errors);
  // Error to warning: changed, no new error.
  const ReportDiff better = DiffReports(report(kError, 10.0), old, {});
  EXPECT_EQ(better.changed, 1);
  EXPECT_FALSE(better.new_errors);
}

// 200 kept findings 10 mm apart from `first` on, and `extra` errors past the cap.
RuleSummary Truncated(int first, long extra) {
  std::vector<Finding> f;
  for (int k = first; k < first + 200; ++k) {
    f.push_back(MakeFinding("stitch.length", kError, 10 + k, 1 + k, 30.0, At(10.0 * k)));
  }
  return MakeRule("stitch.length", std::move(f), extra);
}

TEST(ReportDiff, TruncatedRulesAreComparedByCount) {
  const Report old = MakeReport("a.nc", {Truncated(0, 100)});
  // One error more, before all the others: the first 200 now end one finding earlier.
  RuleSummary r = Truncated(0, 100);
  r.findings.pop_back();
  r.findings.insert(r.findings.begin(), MakeFinding("stitch.length", kError, 5, 1, 30.0, At(-10)));
  r.errors = 301;
  const ReportDiff d = DiffReports(old, MakeReport("b.nc", {r}), {});
  // The inserted one appeared; the old 200th, past the new report's cap, is not "disappeared".
  ASSERT_EQ(d.findings.size(), 1u) << ReportDiffToText(d);
  EXPECT_EQ(d.findings[0].change, FindingChange::kAppeared);
  EXPECT_EQ(d.rules[0].old_past_cap, 1);
  EXPECT_TRUE(d.new_errors);
  EXPECT_NE(ReportDiffToText(d).find("truncated in old and new"), std::string::npos);

  // The same kept findings and more errors past the cap: a new error all the same.
  const ReportDiff grew = DiffReports(old, MakeReport("b.nc", {Truncated(0, 105)}), {});
  EXPECT_TRUE(grew.findings.empty());
  EXPECT_TRUE(grew.new_errors);
  EXPECT_EQ(grew.rules[0].new_errors - grew.rules[0].old_errors, 5);
  // Fewer past the cap: none.
  const ReportDiff fewer = DiffReports(old, MakeReport("b.nc", {Truncated(0, 50)}), {});
  EXPECT_FALSE(fewer.new_errors);
  EXPECT_EQ(ReportDiffToText(fewer).rfind("CHANGED  ", 0), 0u) << ReportDiffToText(fewer);

  // The old report truncated, the new one clean after its fix of the first 150: the 50 left
  // match, nothing past the old cap is listed as appeared.
  RuleSummary fixed = Truncated(0, 0);
  fixed.findings.erase(fixed.findings.begin(), fixed.findings.begin() + 150);
  fixed.findings.push_back(MakeFinding("stitch.length", kError, 900, 900, 30.0, At(9000)));
  fixed.errors = 51;
  const ReportDiff f = DiffReports(old, MakeReport("b.nc", {fixed}), {});
  EXPECT_EQ(f.disappeared, 150);
  EXPECT_EQ(f.appeared, 0);
  EXPECT_EQ(f.rules[0].new_past_cap, 1);
  EXPECT_FALSE(f.new_errors);
}

TEST(ReportDiff, ExitRule) {
  const Report clean = MakeReport("a.nc", {MakeRule("kin.reach", {})});
  const auto with = [](FindingSeverity s) {
    return MakeReport("b.nc",
                      {MakeRule("kin.reach", {MakeFinding("kin.reach", s, 3, 1, 1.0, At(0))})});
  };
  EXPECT_FALSE(DiffReports(clean, with(kWarning), {}).new_errors);  // appeared warning
  EXPECT_TRUE(DiffReports(clean, with(kError), {}).new_errors);     // appeared error
  EXPECT_FALSE(DiffReports(with(kError), clean, {}).new_errors);    // disappeared error
  EXPECT_FALSE(DiffReports(with(kError), with(kError), {}).new_errors);
  // A rule only the new report ran, with an error: appeared.
  const Report extra = MakeReport(
      "b.nc", {MakeRule("kin.reach", {}),
               MakeRule("program.sync",
                        {MakeFinding("program.sync", kError, 8, 0, 1.0, std::nullopt, "")})});
  const ReportDiff d = DiffReports(clean, extra, {});
  EXPECT_TRUE(d.new_errors);
  ASSERT_EQ(d.rules.size(), 2u);
  EXPECT_FALSE(d.rules[1].in_old);
}

TEST(ReportDiff, FindingsWithoutAnythingAreMatchedInOrder) {
  const auto report = [](std::vector<double> values) {
    std::vector<Finding> f;
    for (double v : values) {
      f.push_back(MakeFinding("program.stitch_count", kError, 0, 0, v, std::nullopt, ""));
    }
    return MakeReport("p.nc", {MakeRule("program.stitch_count", f)});
  };
  EXPECT_TRUE(DiffReports(report({5.0}), report({5.0}), {}).findings.empty());
  const ReportDiff d = DiffReports(report({5.0}), report({5.0, 6.0}), {});
  ASSERT_EQ(d.findings.size(), 1u);
  EXPECT_EQ(d.findings[0].change, FindingChange::kAppeared);
  EXPECT_DOUBLE_EQ(d.findings[0].new_finding->value, 6.0);
}

TEST(ReportDiff, LineFindingsWithoutAnyPositionMatchInOrder) {
  // No finding has a position: no line shift is known, so the line findings of a rule and
  // subject pair in order (ten lines inserted before them change nothing) ...
  const auto report = [](int shift, std::vector<int> lines) {
    std::vector<Finding> f;
    for (int l : lines) {
      f.push_back(MakeFinding("program.sync", kError, l + shift, 0, 2.0, std::nullopt, "V"));
    }
    return MakeReport("p.nc", {MakeRule("program.sync", f)});
  };
  const ReportDiff d = DiffReports(report(0, {20, 30}), report(10, {20, 30}), {});
  EXPECT_TRUE(d.findings.empty()) << ReportDiffToText(d);
  ASSERT_EQ(d.rules.size(), 1u);
  // ... and one more is listed as appeared (the last in order).
  const ReportDiff more = DiffReports(report(0, {20, 30}), report(10, {20, 30, 40}), {});
  ASSERT_EQ(more.findings.size(), 1u);
  EXPECT_EQ(more.findings[0].new_finding->line, 50);
  EXPECT_TRUE(more.new_errors);
}

TEST(ReportDiff, JsonJunitAndTextAgreeWithTheDiff) {
  const Report old = MakeReport(
      "old.nc",
      {MakeRule("constraint.crossing", {}),
       MakeRule("stitch.width", {MakeFinding("stitch.width", kWarning, 40, 12, 3.0, At(1))})});
  Report neu = MakeReport(
      "new.nc", {MakeRule("constraint.crossing", {MakeFinding("constraint.crossing", kError, 57, 30,
                                                              4.5, At(99), "stringer")}),
                 MakeRule("stitch.width", {})});
  neu.cycle_time_s = 55.0;
  neu.stitches = 101;
  const ReportDiff d = DiffReports(old, neu, {});
  const Json j = Json::parse(ReportDiffToJson(d));
  EXPECT_EQ(j.at("stitchsim_diff"), 1);
  EXPECT_EQ(j.at("new_errors"), true);
  EXPECT_EQ(j.at("counts").at("appeared"), 1);
  EXPECT_EQ(j.at("counts").at("disappeared"), 1);
  EXPECT_EQ(j.at("verdict").at("old"), "pass");
  EXPECT_EQ(j.at("verdict").at("new"), "fail");
  EXPECT_DOUBLE_EQ(j.at("cycle_time_s").at("change").get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(j.at("cycle_time_s").at("change_pct").get<double>(), 10.0);
  EXPECT_EQ(j.at("stitches").at("change"), 1);
  const Json& f0 = j.at("findings").at(0);
  EXPECT_EQ(f0.at("change"), "appeared");
  EXPECT_EQ(f0.at("rule"), "constraint.crossing");
  EXPECT_TRUE(f0.at("old").is_null());
  EXPECT_EQ(f0.at("new").at("line"), 57);
  EXPECT_DOUBLE_EQ(f0.at("new").at("position_mm").at(0).get<double>(), 99.0);
  EXPECT_EQ(j.at("findings").at(1).at("change"), "disappeared");
  EXPECT_EQ(j.at("rules").at(0).at("errors").at("new"), 1);

  const std::string xml = ReportDiffToJunit(d);
  EXPECT_NE(xml.find("<testsuite name=\"stitchsim.diff\""), std::string::npos);
  EXPECT_NE(xml.find("<failure message=\"1 new error\" type=\"constraint.crossing\">"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("appeared: line 57 stitch 30"), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"stitch.width\" time=\"0\"/>"), std::string::npos) << xml;

  const std::string text = ReportDiffToText(d);
  EXPECT_EQ(text.rfind("NEW ERRORS  old.nc -> new.nc on s: 1 appeared, 1 disappeared", 0), 0u)
      << text;
  EXPECT_NE(text.find("  + constraint.crossing error line 57 (was -) stitch 30 (was -) at (99.0, "
                      "20.0, 3.0) mm: 4.5 mm (limit 1 mm) [stringer]"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  - stitch.width warning line - (was 40) stitch - (was 12)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("cycle 50 s -> 55 s (+5 s, +10 %)"), std::string::npos) << text;
  // Deterministic.
  EXPECT_EQ(ReportDiffToJson(DiffReports(old, neu, {})), ReportDiffToJson(d));
}

}  // namespace
}  // namespace stitchsim::verify
