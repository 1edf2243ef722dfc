// Report writer tests: the JSON and JUnit outputs are read back by two parsers (nlohmann and
// Python's json / xml.etree) and must agree with the report they came from; every writer is
// byte-deterministic; the text summary shows the verdict, every rule and the worst place.

#include "stitchsim/verify/report.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <locale>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "report_test_support.h"

namespace stitchsim::verify {
namespace {

using namespace report_test_support;  // NOLINT(google-build-using-namespace)

namespace fs = std::filesystem;
using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Messages that a careless writer would break.
const std::string kQuoted =
    "a \"quoted\" <tag> & 'apos' ]]> \xC3\xBCn\xC3\xAF"
    "c\xC3\xB6"
    "d\xC3\xA9 \xE6\x97\xA5\xE6\x9C\xAC \xE2\x9C\x93 \xF0\x9F\xA7\xB5";
const std::string kControl = std::string("ctrl\x01\x07 esc\x1B[31m del\x7F tab\tnl\ncr\r nul") +
                             std::string(1, '\0') + " end";
// 5000 characters, a malformed byte, a UTF-8-encoded surrogate and U+FFFE.
const std::string kLongInvalid =
    std::string(5000, 'x') + " bad\xFF surrogate\xED\xA0\x80 nonchar\xEF\xBF\xBE end";
const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD

Finding MakeFinding(std::string rule, FindingSeverity severity, int line, long stitch, double value,
                    double limit, std::string unit, std::string message) {
  Finding f;
  f.rule = std::move(rule);
  f.severity = severity;
  f.line = line;
  f.stitch = stitch;
  f.value = value;
  f.limit = limit;
  f.unit = std::move(unit);
  f.subject = "insertion";
  f.message = std::move(message);
  return f;
}

// 250 errors and 3 warnings; 200 findings kept (3 warnings, 197 errors), so 53 not kept.
RuleSummary SideForceRule() {
  RuleSummary r;
  r.id = "needle.side_force";
  r.description = "side-force proxy per needle";
  r.unit = "mm";
  r.checked = 255;
  r.errors = 250;
  r.warnings = 3;
  r.error_limit = 0.5;
  r.warning_limit = 0.3;
  r.worst_value = 1.234;
  r.worst_line = 12;
  r.worst_stitch = 3;
  for (int i = 0; i < static_cast<int>(kMaxFindingsPerRule); ++i) {
    const bool warning = i % 67 == 0;
    r.findings.push_back(MakeFinding(
        r.id, warning ? FindingSeverity::kWarning : FindingSeverity::kError, 10 + 2 * i, i + 1,
        warning ? 0.4 : 0.8, warning ? 0.3 : 0.5, "mm",
        "side force proxy " + std::to_string(i) + " over the limit at the insertion needle"));
  }
  r.truncated = true;
  return r;
}

// Warnings only: a <system-out>, no <failure>.
RuleSummary NormalityRule() {
  RuleSummary r;
  r.id = "stitch.normality";
  r.description = "angle between head z and the surface normal at needle entry";
  r.unit = "deg";
  r.checked = 255;
  r.warnings = 2;
  r.error_limit = 5.0;
  r.warning_limit = 3.0;
  r.worst_value = 4.2;
  r.worst_line = 30;
  r.worst_stitch = 5;
  r.findings.push_back(MakeFinding(r.id, FindingSeverity::kWarning, 30, 5, 4.2, 3.0, "deg",
                                   "head tilted 4.2 deg from the normal"));
  r.findings.push_back(MakeFinding(r.id, FindingSeverity::kWarning, 44, 9, 3.5, 3.0, "deg",
                                   "head tilted 3.5 deg from the normal"));
  return r;
}

RuleSummary PassingRule() {
  RuleSummary r;
  r.id = "program.empty";
  r.description = "a programme with no stitches never passes";
  r.checked = 1;
  return r;
}

// Awkward strings everywhere, non-finite numbers, no limits.
RuleSummary AwkwardRule() {
  RuleSummary r;
  r.id = "kin.reach";
  r.description = "pose out of the arm's \"reach\" <&>";
  r.unit = "deg\"<&>'";
  r.checked = 10;
  r.errors = 3;
  r.error_limit = 1.0;
  r.worst_value = 2.5;
  r.worst_line = 7;
  r.findings.push_back(MakeFinding(r.id, FindingSeverity::kError, 7, 0, 2.5, 1.0, r.unit, kQuoted));
  r.findings.push_back(
      MakeFinding(r.id, FindingSeverity::kError, 8, 2, kNaN, kInf, r.unit, kControl));
  r.findings.push_back(
      MakeFinding(r.id, FindingSeverity::kError, 9, 3, -kInf, 1.0, r.unit, kLongInvalid));
  return r;
}

Report FailingReport() {
  Report report;
  report.program_file = "prog.nc";
  report.scene_file = "scenes/circle_8in.yaml";
  report.scene_name = "circle_8in";
  report.head = "rs535";
  report.verdict = "fail";
  report.lines = 600;
  report.moves = 511;
  report.stitches = 255;
  report.stitch_length_mm = 5.0;
  report.cycle_time_s = 101.3;
  report.rules = {SideForceRule(), NormalityRule(), PassingRule()};
  report.errors = 250;
  report.warnings = 5;
  return report;
}

Report PassingReport() {
  Report report = FailingReport();
  report.verdict = "pass";
  report.rules = {NormalityRule(), PassingRule()};
  report.errors = 0;
  report.warnings = 2;
  return report;
}

Report AwkwardReport() {
  Report report = FailingReport();
  report.program_file = "odd \"prog\" <&>.nc";
  report.scene_name = "o'brien <&> \"x\"\tnl\ncr\r";
  report.head =
      "h\xC3\xA9"
      "ad";
  report.stitch_length_mm = kNaN;
  report.cycle_time_s = -kInf;
  RuleSummary nan_worst = PassingRule();
  nan_worst.id = "needle.walk";
  nan_worst.worst_value = kNaN;
  nan_worst.error_limit = kInf;
  nan_worst.warning_limit = kNaN;
  report.rules = {AwkwardRule(), nan_worst};
  report.errors = 3;
  report.warnings = 0;
  return report;
}

std::vector<std::string> Keys(const OrderedJson& object) {
  std::vector<std::string> keys;
  for (const auto& item : object.items()) keys.push_back(item.key());
  return keys;
}

std::size_t Columns(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += (c & 0xC0) != 0x80 ? 1 : 0;
  return n;
}

// ---------------------------------------------------------------------------------------
// JSON

TEST(report_json, KeysInDocumentedOrder) {
  const OrderedJson j = OrderedJson::parse(ReportToJson(FailingReport()));
  EXPECT_EQ(Keys(j),
            (std::vector<std::string>{"stitchsim_report", "stitchsim_version", "verdict", "program",
                                      "scene", "counts", "stitch_length_mm", "cycle_time_s",
                                      "cycle_time_timed_s", "rules", "skipped_rules"}));
  EXPECT_EQ(Keys(j["scene"]), (std::vector<std::string>{"file", "name", "head"}));
  EXPECT_EQ(Keys(j["counts"]),
            (std::vector<std::string>{"lines", "moves", "stitches", "errors", "warnings"}));
  ASSERT_EQ(j["rules"].size(), 3u);
  for (const auto& rule : j["rules"]) {
    EXPECT_EQ(Keys(rule),
              (std::vector<std::string>{"id", "description", "unit", "checked", "applies", "errors",
                                        "warnings", "error_limit", "warning_limit", "worst",
                                        "subjects", "findings_truncated", "findings"}));
  }
  EXPECT_EQ(Keys(j["rules"][0]["worst"]), (std::vector<std::string>{"value", "line", "stitch"}));
  EXPECT_EQ(Keys(j["rules"][0]["findings"][0]),
            (std::vector<std::string>{"rule", "severity", "line", "stitch", "value", "limit",
                                      "unit", "subject", "message", "position_mm"}));
}

TEST(report_json, ValuesMatchTheReport) {
  const Report report = FailingReport();
  const std::string text = ReportToJson(report);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.rfind("{\n  \"stitchsim_report\": 1,\n", 0), 0u) << "indent 2";
  EXPECT_EQ(text.back(), '\n');
  EXPECT_NE(text[text.size() - 2], '\n');

  const Json j = Json::parse(text);
  EXPECT_EQ(j["verdict"], "fail");
  EXPECT_EQ(j["program"], "prog.nc");
  EXPECT_EQ(j["scene"]["file"], "scenes/circle_8in.yaml");
  EXPECT_EQ(j["scene"]["name"], "circle_8in");
  EXPECT_EQ(j["scene"]["head"], "rs535");
  EXPECT_EQ(j["counts"]["lines"], 600);
  EXPECT_EQ(j["counts"]["moves"], 511);
  EXPECT_EQ(j["counts"]["stitches"], 255);
  EXPECT_EQ(j["counts"]["errors"], 250);
  EXPECT_EQ(j["counts"]["warnings"], 5);
  EXPECT_EQ(j["stitch_length_mm"].get<double>(), 5.0);
  EXPECT_EQ(j["cycle_time_s"].get<double>(), 101.3);

  const Json& side = j["rules"][0];
  EXPECT_EQ(side["id"], "needle.side_force");
  EXPECT_EQ(side["unit"], "mm");
  EXPECT_EQ(side["checked"], 255);
  EXPECT_EQ(side["errors"], 250);
  EXPECT_EQ(side["warnings"], 3);
  EXPECT_EQ(side["error_limit"].get<double>(), 0.5);
  EXPECT_EQ(side["warning_limit"].get<double>(), 0.3);
  EXPECT_EQ(side["worst"]["value"].get<double>(), 1.234);
  EXPECT_EQ(side["worst"]["line"], 12);
  EXPECT_EQ(side["worst"]["stitch"], 3);
  EXPECT_EQ(side["findings_truncated"], true);
  ASSERT_EQ(side["findings"].size(), kMaxFindingsPerRule);
  EXPECT_EQ(side["findings"][0]["severity"], "warning");
  EXPECT_EQ(side["findings"][1]["severity"], "error");
  EXPECT_EQ(side["findings"][1]["line"], 12);
  EXPECT_EQ(side["findings"][1]["stitch"], 2);
  EXPECT_EQ(side["findings"][1]["value"].get<double>(), 0.8);
  EXPECT_EQ(side["findings"][1]["limit"].get<double>(), 0.5);
  EXPECT_EQ(side["findings"][1]["subject"], "insertion");
  EXPECT_EQ(side["findings"][1]["rule"], "needle.side_force");

  const Json& pass = j["rules"][2];
  EXPECT_TRUE(pass["error_limit"].is_null());
  EXPECT_TRUE(pass["warning_limit"].is_null());
  EXPECT_TRUE(pass["worst"].is_null());
  EXPECT_EQ(pass["findings_truncated"], false);
  EXPECT_TRUE(pass["findings"].is_array());
  EXPECT_TRUE(pass["findings"].empty());
}

TEST(report_json, DoublesRoundTripExactly) {
  const std::vector<double> values = {0.1,     1.0 / 3.0, 123456.78901234567,
                                      1e-300,  5e-324,    std::numeric_limits<double>::max(),
                                      -2.5e17, -0.0};
  Report report = PassingReport();
  report.rules[0].findings.clear();
  for (double v : values) {
    report.rules[0].findings.push_back(
        MakeFinding("stitch.normality", FindingSeverity::kWarning, 1, 1, v, -v, "deg", "x"));
  }
  const Json j = Json::parse(ReportToJson(report));
  const Json& findings = j["rules"][0]["findings"];
  ASSERT_EQ(findings.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double value = findings[i]["value"].get<double>();
    const double limit = findings[i]["limit"].get<double>();
    EXPECT_EQ(value, values[i]) << i;
    EXPECT_EQ(limit, -values[i]) << i;
    EXPECT_EQ(std::signbit(value), std::signbit(values[i])) << i;
  }
}

TEST(report_json, NonFiniteNumbersBecomeNull) {
  const std::string text = ReportToJson(AwkwardReport());
  for (const char* bad : {"nan", "NaN", "inf", "Infinity"}) {
    EXPECT_EQ(text.find(bad), std::string::npos) << bad;
  }
  const Json j = Json::parse(text);
  EXPECT_TRUE(j["stitch_length_mm"].is_null());
  EXPECT_TRUE(j["cycle_time_s"].is_null());
  const Json& reach = j["rules"][0];
  EXPECT_TRUE(reach["findings"][1]["value"].is_null());
  EXPECT_TRUE(reach["findings"][1]["limit"].is_null());
  EXPECT_TRUE(reach["findings"][2]["value"].is_null());
  EXPECT_EQ(reach["findings"][2]["limit"].get<double>(), 1.0);
  const Json& walk = j["rules"][1];
  ASSERT_TRUE(walk["worst"].is_object());
  EXPECT_TRUE(walk["worst"]["value"].is_null());
  EXPECT_TRUE(walk["error_limit"].is_null());
  EXPECT_TRUE(walk["warning_limit"].is_null());
}

TEST(report_json, StringsSurvive) {
  const Report report = AwkwardReport();
  const Json j = Json::parse(ReportToJson(report));
  EXPECT_EQ(j["program"], report.program_file);
  EXPECT_EQ(j["scene"]["name"], report.scene_name);
  EXPECT_EQ(j["scene"]["head"], report.head);
  const Json& reach = j["rules"][0];
  EXPECT_EQ(reach["description"], report.rules[0].description);
  EXPECT_EQ(reach["unit"], report.rules[0].unit);
  EXPECT_EQ(reach["findings"][0]["message"], kQuoted);
  EXPECT_EQ(reach["findings"][1]["message"], kControl);  // controls escaped, not lost
  // Malformed UTF-8 is replaced, the rest kept.
  const std::string long_message = reach["findings"][2]["message"].get<std::string>();
  EXPECT_EQ(long_message.rfind(std::string(5000, 'x') + " bad" + kReplacement, 0), 0u);
  EXPECT_NE(long_message.find(" end"), std::string::npos);
  EXPECT_EQ(long_message.find('\xFF'), std::string::npos);
}

TEST(report_json, PythonReadsTheSameDocument) {
  for (const Report& report : {FailingReport(), PassingReport(), AwkwardReport(), Report{}}) {
    const std::string text = ReportToJson(report);
    TempFile in(".json");
    TempFile out(".json");
    in.Write(text);
    ASSERT_EQ(RunPython(kPythonJsonCheck, {in.path().string(), out.path().string()}), 0)
        << text.substr(0, 2000);
    // Python's reading, written back, equals nlohmann's reading: same values, same strings.
    EXPECT_EQ(Json::parse(out.Read()), Json::parse(text));
  }
}

TEST(report_json, EveryKeyIsDocumented) {
  const auto doc = [] {
    std::ifstream in(fs::path(STITCHSIM_SOURCE_DIR) / "docs" / "report-format.md");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }();
  ASSERT_FALSE(doc.empty()) << "docs/report-format.md";
  std::set<std::string> keys;
  const auto collect = [&keys](const Json& j, const auto& self) -> void {
    if (j.is_object()) {
      for (const auto& item : j.items()) {
        keys.insert(item.key());
        self(item.value(), self);
      }
    } else if (j.is_array()) {
      for (const auto& element : j) self(element, self);
    }
  };
  collect(Json::parse(ReportToJson(FailingReport())), collect);
  EXPECT_GE(keys.size(), 30u);
  for (const std::string& key : keys) {
    EXPECT_NE(doc.find("`" + key + "`"), std::string::npos) << key << " not in the doc";
  }
}

// ---------------------------------------------------------------------------------------
// JUnit

TEST(report_junit, StructureAndCounts) {
  const std::string xml = ReportToJunit(FailingReport());
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites ", 0), 0u);
  EXPECT_EQ(xml.back(), '\n');
  const Json root = ParseJunitWithPython(xml);
  ASSERT_TRUE(root.is_object());
  EXPECT_EQ(root["attrib"]["tests"], "3");
  EXPECT_EQ(root["attrib"]["failures"], "1");
  ASSERT_EQ(root["children"].size(), 1u);
  const Json& suite = root["children"][0];
  EXPECT_EQ(suite["attrib"]["name"], "stitchsim.circle_8in.prog_nc");
  EXPECT_EQ(suite["attrib"]["tests"], "3");
  EXPECT_EQ(suite["attrib"]["failures"], "1");
  EXPECT_EQ(suite["attrib"]["time"], "0");
  ASSERT_EQ(suite["children"].size(), 4u);  // <properties>, then the test cases
  EXPECT_EQ(suite["children"][0]["tag"], "properties");
  EXPECT_EQ(suite["children"][1]["attrib"]["name"], "needle.side_force");
  EXPECT_EQ(suite["children"][2]["attrib"]["name"], "stitch.normality");
  EXPECT_EQ(suite["children"][3]["attrib"]["name"], "program.empty");

  // Errors: one <failure> listing every kept finding, then how many were not kept.
  const Json* side = FindCase(suite, "needle.side_force");
  ASSERT_NE(side, nullptr);
  ASSERT_EQ((*side)["children"].size(), 1u);
  const Json& failure = (*side)["children"][0];
  EXPECT_EQ(failure["tag"], "failure");
  EXPECT_EQ(failure["attrib"]["type"], "needle.side_force");
  EXPECT_EQ(failure["attrib"]["message"], "250 errors; worst 1.234 mm at line 12 (limit 0.5 mm)");
  const std::vector<std::string> lines = SplitLines(failure["text"].get<std::string>());
  ASSERT_EQ(lines.size(), kMaxFindingsPerRule + 1);
  EXPECT_EQ(lines[0],
            "line 10 stitch 1: warning: side force proxy 0 over the limit at the insertion needle");
  EXPECT_EQ(lines[1],
            "line 12 stitch 2: side force proxy 1 over the limit at the insertion needle");
  EXPECT_EQ(lines.back(), "... and 53 more");

  // Warnings only: <system-out>, no <failure>.
  const Json* normality = FindCase(suite, "stitch.normality");
  ASSERT_NE(normality, nullptr);
  ASSERT_EQ((*normality)["children"].size(), 1u);
  EXPECT_EQ((*normality)["children"][0]["tag"], "system-out");
  EXPECT_EQ((*normality)["children"][0]["text"],
            "line 30 stitch 5: warning: head tilted 4.2 deg from the normal\n"
            "line 44 stitch 9: warning: head tilted 3.5 deg from the normal");

  const Json* pass = FindCase(suite, "program.empty");
  ASSERT_NE(pass, nullptr);
  EXPECT_TRUE((*pass)["children"].empty());
}

TEST(report_junit, PassingAndEmptyReports) {
  const Json pass = ParseJunitWithPython(ReportToJunit(PassingReport()));
  ASSERT_TRUE(pass.is_object());
  EXPECT_EQ(pass["attrib"]["tests"], "2");
  EXPECT_EQ(pass["attrib"]["failures"], "0");

  const Json empty = ParseJunitWithPython(ReportToJunit(Report{}));
  ASSERT_TRUE(empty.is_object());
  EXPECT_EQ(empty["attrib"]["tests"], "0");
  ASSERT_EQ(empty["children"].size(), 1u);
  EXPECT_EQ(empty["children"][0]["attrib"]["name"], "stitchsim.unnamed");
}

TEST(report_junit, AwkwardStringsAreEscaped) {
  const std::string xml = ReportToJunit(AwkwardReport());
  for (char c : xml) {
    const auto byte = static_cast<unsigned char>(c);
    EXPECT_TRUE(byte >= 0x20 || c == '\n') << "raw control byte " << int{byte};
  }
  const Json root = ParseJunitWithPython(xml);
  ASSERT_TRUE(root.is_object());
  EXPECT_EQ(root["attrib"]["failures"], "1");
  const Json& suite = root["children"][0];
  const std::string suite_name = "stitchsim.o'brien <&> \"x\"\tnl\ncr\r.odd__prog______nc";
  EXPECT_EQ(suite["attrib"]["name"], suite_name);
  const Json* reach = FindCase(suite, "kin.reach");
  ASSERT_NE(reach, nullptr);
  EXPECT_EQ((*reach)["attrib"]["classname"], suite_name);
  const Json& failure = (*reach)["children"][0];
  EXPECT_EQ(failure["attrib"]["message"],
            "3 errors; worst 2.5 deg\"<&>' at line 7 (limit 1 deg\"<&>')");
  const std::vector<std::string> lines = SplitLines(failure["text"].get<std::string>());
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "line 7: " + kQuoted);
  // Whitespace controls become spaces (one finding a line); others become U+FFFD.
  EXPECT_EQ(lines[1], "line 8 stitch 2: ctrl" + kReplacement + kReplacement + " esc" +
                          kReplacement + "[31m del\x7F tab nl cr  nul" + kReplacement + " end");
  EXPECT_EQ(lines[2], "line 9 stitch 3: " + std::string(5000, 'x') + " bad" + kReplacement +
                          " surrogate" + kReplacement + kReplacement + kReplacement + " nonchar" +
                          kReplacement + " end");
  // A NaN worst value and an infinite limit stay readable words.
  const Json* walk = FindCase(suite, "needle.walk");
  ASSERT_NE(walk, nullptr);
  EXPECT_TRUE((*walk)["children"].empty());
}

TEST(report_junit, NonFiniteWorstInFailureMessage) {
  Report report = FailingReport();
  report.rules[0].worst_value = kNaN;
  report.rules[0].error_limit = kInf;
  const Json root = ParseJunitWithPython(ReportToJunit(report));
  ASSERT_TRUE(root.is_object());
  EXPECT_EQ(root["children"][0]["children"][1]["children"][0]["attrib"]["message"],
            "250 errors; worst nan mm at line 12 (limit inf mm)");
}

// ---------------------------------------------------------------------------------------
// Text

TEST(report_text, HeadlineTableAndExamples) {
  const std::string text = ReportToText(FailingReport());
  const std::vector<std::string> lines = SplitLines(text);
  ASSERT_GE(lines.size(), 6u);
  EXPECT_EQ(lines[0],
            "FAIL  prog.nc on circle_8in (rs535): 250 errors, 5 warnings in 3 rules; "
            "255 stitches, 511 moves, cycle 101.3 s");
  EXPECT_EQ(text.back(), '\n');

  // One row per rule under the header, columns aligned.
  std::size_t header = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find("rule") != std::string::npos && lines[i].find("worst") != std::string::npos) {
      header = i;
      break;
    }
  }
  ASSERT_LT(header + 3, lines.size());
  const std::string& side = lines[header + 1];
  const std::string& normality = lines[header + 2];
  const std::string& pass = lines[header + 3];
  EXPECT_NE(side.find("needle.side_force"), std::string::npos);
  EXPECT_NE(normality.find("stitch.normality"), std::string::npos);
  EXPECT_NE(pass.find("program.empty"), std::string::npos);
  const std::size_t worst_column = lines[header].find("worst");
  EXPECT_EQ(side.find("1.234 mm"), worst_column);
  EXPECT_EQ(normality.find("4.2 deg"), worst_column);
  EXPECT_EQ(pass.find("-"), worst_column);
  EXPECT_NE(side.find("line 12 stitch 3"), std::string::npos);
  EXPECT_NE(side.find("0.5 mm (warn 0.3)"), std::string::npos);
  EXPECT_NE(normality.find("line 30 stitch 5"), std::string::npos);
  const std::size_t checked_end = lines[header].find("checked") + 7;
  EXPECT_EQ(side.substr(checked_end - 3, 3), "255");
  EXPECT_EQ(pass.substr(checked_end - 1, 1), "1");

  // Five example errors of the failing rule (warnings skipped), then the rest counted.
  const auto examples = std::find(lines.begin(), lines.end(), "needle.side_force: 250 errors");
  ASSERT_NE(examples, lines.end());
  ASSERT_GE(lines.end() - examples, 7);
  EXPECT_EQ(examples[1],
            "  line 12 stitch 2: side force proxy 1 over the limit at the insertion needle");
  EXPECT_EQ(examples[5],
            "  line 20 stitch 6: side force proxy 5 over the limit at the insertion needle");
  EXPECT_EQ(examples[6], "  ... and 245 more");
  // Rules without errors get no example block.
  EXPECT_EQ(text.find("stitch.normality: "), std::string::npos);
  EXPECT_EQ(text.find("program.empty: "), std::string::npos);
}

TEST(report_text, PassingReport) {
  const std::string text = ReportToText(PassingReport());
  EXPECT_EQ(text.rfind("PASS  prog.nc on circle_8in (rs535): 0 errors, 2 warnings in 2 rules;", 0),
            0u)
      << text;
  EXPECT_EQ(text.find("... and"), std::string::npos);
  const std::string empty = ReportToText(Report{});
  EXPECT_NE(empty.find("0 rules"), std::string::npos) << empty;
}

TEST(report_text, NarrowCleanAndValidUtf8) {
  const std::string text = ReportToText(AwkwardReport());
  // Valid UTF-8: nlohmann's strict serializer throws on anything else.
  EXPECT_NO_THROW((void)Json(text).dump());
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    EXPECT_TRUE((byte >= 0x20 && byte != 0x7F) || c == '\n') << "control byte " << int{byte};
  }
  const std::vector<std::string> lines = SplitLines(text);
  for (std::size_t i = 1; i < lines.size(); ++i) {  // the headline carries the names in full
    EXPECT_LE(Columns(lines[i]), 100u) << lines[i].substr(0, 120);
  }
  EXPECT_NE(text.find("kin.reach: 3 errors"), std::string::npos);
  EXPECT_NE(text.find("  line 9 stitch 3: xxxx"), std::string::npos);
  EXPECT_NE(text.find("xxx...\n"), std::string::npos) << "long message cut";
  EXPECT_NE(text.find("nan"), std::string::npos) << "NaN worst value shown";
}

// ---------------------------------------------------------------------------------------
// Determinism

// A locale that writes numbers the German way; streams would pick it up, the writers must not.
struct CommaDecimal : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
  char do_thousands_sep() const override { return '.'; }
  std::string do_grouping() const override { return "\3"; }
};

TEST(report_writers, ByteIdenticalOutput) {
  for (const Report& report : {FailingReport(), PassingReport(), AwkwardReport()}) {
    const Report copy = report;
    const std::string text = ReportToText(report);
    const std::string json = ReportToJson(report);
    const std::string junit = ReportToJunit(report);
    EXPECT_EQ(ReportToText(copy), text);
    EXPECT_EQ(ReportToJson(copy), json);
    EXPECT_EQ(ReportToJunit(copy), junit);

    const std::locale previous =
        std::locale::global(std::locale(std::locale::classic(), new CommaDecimal));
    const std::string text_comma = ReportToText(report);
    const std::string json_comma = ReportToJson(report);
    const std::string junit_comma = ReportToJunit(report);
    std::locale::global(previous);
    EXPECT_EQ(text_comma, text);
    EXPECT_EQ(json_comma, json);
    EXPECT_EQ(junit_comma, junit);
  }
}

}  // namespace
}  // namespace stitchsim::verify
