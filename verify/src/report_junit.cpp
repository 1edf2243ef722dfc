// The JUnit XML report (docs/report-format.md, "JUnit XML"): one <testsuite> per run, one
// <testcase> per rule, a <failure> for a rule with errors. No timestamps or host names, so
// the same report gives the same bytes.

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>

#include "detail/text_format.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::verify {
namespace {

using detail::Count;
using detail::FormatNumber;
using detail::Location;
using detail::XmlContext;
using detail::XmlEscape;

std::string Attribute(std::string_view name, std::string_view value) {
  return detail::XmlAttribute(name, value);
}

std::string Attribute(std::string_view name, long value) {
  return Attribute(name, std::to_string(value));
}

std::string RawWithUnit(const std::string& number, const std::string& unit) {
  return unit.empty() ? number : number + " " + unit;
}

// One finding on one line of element text: "line 12 stitch 3: message", warnings marked.
std::string FindingLine(const Finding& finding) {
  std::string message = finding.message;
  for (char& c : message) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  return Location(finding.line, finding.stitch) + ": " +
         (finding.severity == FindingSeverity::kWarning ? "warning: " : "") + message;
}

// "3 errors; worst 1.2 mm at line 12 (limit 0.5 mm)", parts left out when unknown.
std::string FailureMessage(const RuleSummary& rule) {
  std::string message = Count(rule.errors, "error", "errors");
  if (rule.worst_value) {
    message += "; worst " + RawWithUnit(FormatNumber(*rule.worst_value), rule.unit);
    if (rule.worst_line > 0) {
      message += " at line " + std::to_string(rule.worst_line);
    } else if (rule.worst_stitch > 0) {
      message += " at stitch " + std::to_string(rule.worst_stitch);
    }
  }
  if (rule.error_limit) {
    message += " (limit " + RawWithUnit(FormatNumber(*rule.error_limit), rule.unit) + ")";
  }
  // Subjects with their own limits: each figure beside its own limit.
  for (const SubjectFigure& s : rule.subjects) {
    message += "; " + s.subject + " worst ";
    message += s.checked == 0 || !s.worst_value
                   ? std::string("n/a")
                   : RawWithUnit(FormatNumber(*s.worst_value), rule.unit);
    message += s.error_limit
                   ? " (limit " + RawWithUnit(FormatNumber(*s.error_limit), rule.unit) + ")"
                   : std::string(" (no limit)");
  }
  return message;
}

// The element text of a <failure> (every kept finding) or <system-out> (kept warnings),
// one finding a line, then "... and N more" for those past the cap.
std::string FindingList(const RuleSummary& rule, bool warnings_only) {
  std::string text;
  long listed = 0;
  for (const Finding& finding : rule.findings) {
    if (warnings_only && finding.severity != FindingSeverity::kWarning) continue;
    if (!text.empty()) text += '\n';
    text += FindingLine(finding);
    ++listed;
  }
  const long total = warnings_only ? rule.warnings : rule.errors + rule.warnings;
  if (total > listed) {
    text += (text.empty() ? "" : "\n") + ("... and " + std::to_string(total - listed) + " more");
  } else if (rule.truncated) {
    text += text.empty() ? "... and more" : "\n... and more";
  }
  return XmlEscape(text, XmlContext::kText);
}

std::string Testcase(const RuleSummary& rule, const std::string& classname) {
  std::string out = "    <testcase" + Attribute("classname", classname) +
                    Attribute("name", rule.id) + Attribute("time", "0");
  if (rule.errors > 0) {
    out += ">\n      <failure" + Attribute("message", FailureMessage(rule)) +
           Attribute("type", rule.id) + ">" + FindingList(rule, false) + "</failure>\n";
    out += "    </testcase>\n";
  } else if (rule.warnings > 0) {
    out += ">\n      <system-out>" + FindingList(rule, true) + "</system-out>\n";
    out += "    </testcase>\n";
  } else if (!rule.Applies()) {
    out += ">\n      <system-out>n/a: the rule found nothing to check</system-out>\n";
    out += "    </testcase>\n";
  } else {
    out += "/>\n";
  }
  return out;
}

// A rule that did not run: a test case marked <skipped/> with the reason.
std::string SkippedTestcase(const SkippedRule& rule, const std::string& classname) {
  return "    <testcase" + Attribute("classname", classname) + Attribute("name", rule.id) +
         Attribute("time", "0") + ">\n      <skipped" +
         Attribute("message", "skipped: " + rule.reason) + "/>\n    </testcase>\n";
}

// The programme as a name part: characters other than letters, digits, '_' and '-' become
// '_', so a CI view's package.class split at '.' keeps one programme together.
std::string NamePart(const std::string& s) {
  std::string out = s;
  for (char& c : out) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '_' || c == '-';
    if (!keep) c = '_';
  }
  return out;
}

std::string Property(std::string_view name, std::string_view value) {
  return "      <property" + Attribute("name", name) + Attribute("value", value) + "/>\n";
}

}  // namespace

std::string ReportToJunit(const Report& report) {
  // stitchsim.<scene>.<programme>: reports of many programmes merged in one view stay apart.
  std::string suite =
      "stitchsim." + (report.scene_name.empty() ? std::string("unnamed") : report.scene_name);
  if (!report.program_file.empty()) suite += "." + NamePart(report.program_file);
  const long skipped = static_cast<long>(report.skipped.size());
  const long tests = static_cast<long>(report.rules.size()) + skipped;
  long failures = 0;
  for (const RuleSummary& rule : report.rules) failures += rule.errors > 0 ? 1 : 0;

  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites" + Attribute("name", "stitchsim") + Attribute("tests", tests) +
         Attribute("failures", failures) + Attribute("errors", 0L) + Attribute("skipped", skipped) +
         Attribute("time", "0") + ">\n";
  out += "  <testsuite" + Attribute("name", suite) + Attribute("tests", tests) +
         Attribute("failures", failures) + Attribute("errors", 0L) + Attribute("skipped", skipped) +
         Attribute("time", "0") + ">\n";
  out += "    <properties>\n";
  out += Property("program", report.program_file);
  out += Property("scene", report.scene_name);
  out += Property("scene_file", report.scene_file);
  out += Property("head", report.head);
  out += Property("stitchsim_version", report.tool_version);
  out += "    </properties>\n";
  for (const RuleSummary& rule : report.rules) out += Testcase(rule, suite);
  for (const SkippedRule& rule : report.skipped) out += SkippedTestcase(rule, suite);
  out += "  </testsuite>\n";
  out += "</testsuites>\n";
  return out;
}

}  // namespace stitchsim::verify
