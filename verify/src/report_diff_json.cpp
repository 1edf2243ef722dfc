// The JSON and JUnit forms of a report diff (docs/report-format.md, "Diff"). JSON keys are
// written in the order below, which is part of the format.

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <type_traits>

#include "detail/json_format.h"
#include "detail/text_format.h"
#include "stitchsim/common/version.h"
#include "stitchsim/verify/report_diff.h"

namespace stitchsim::verify {
namespace {

using Json = nlohmann::ordered_json;
using detail::Count;
using detail::FormatNumber;
using detail::XmlAttribute;
using detail::XmlContext;
using detail::XmlEscape;

constexpr int kDiffFormatVersion = 1;

using detail::Number;
using detail::SeverityName;

const char* ChangeName(FindingChange c) {
  switch (c) {
    case FindingChange::kAppeared:
      return "appeared";
    case FindingChange::kDisappeared:
      return "disappeared";
    case FindingChange::kChanged:
      return "changed";
  }
  return "";
}

Json MatchName(FindingMatch m) {
  switch (m) {
    case FindingMatch::kNone:
      return nullptr;
    case FindingMatch::kPosition:
      return "position";
    case FindingMatch::kStitch:
      return "stitch";
    case FindingMatch::kLine:
      return "line";
    case FindingMatch::kOrder:
      return "order";
  }
  return nullptr;
}

Json FindingJson(const std::optional<Finding>& f) {
  if (!f) return nullptr;
  Json j = Json::object();
  j["severity"] = SeverityName(f->severity);
  j["line"] = f->line;
  j["stitch"] = f->stitch;
  if (f->position_mm) {
    j["position_mm"] = {Number((*f->position_mm)[0]), Number((*f->position_mm)[1]),
                        Number((*f->position_mm)[2])};
  } else {
    j["position_mm"] = nullptr;
  }
  j["value"] = Number(f->value);
  j["limit"] = Number(f->limit);
  j["message"] = f->message;
  return j;
}

Json SideJson(const DiffSide& s) {
  Json j = Json::object();
  j["program"] = s.program_file;
  j["verdict"] = s.verdict;
  j["lines"] = s.lines;
  j["stitches"] = s.stitches;
  j["errors"] = s.errors;
  j["warnings"] = s.warnings;
  j["cycle_time_s"] = Number(s.cycle_time_s);
  j["cycle_time_timed_s"] = Number(s.cycle_time_timed_s);
  return j;
}

// {old, new, change, change_pct}: change_pct null when the old value is 0.
template <typename T>
Json Change(T old_v, T new_v) {
  const auto value = [](T v) { return std::is_floating_point_v<T> ? Number(double(v)) : Json(v); };
  Json j = Json::object();
  j["old"] = value(old_v);
  j["new"] = value(new_v);
  j["change"] = value(new_v - old_v);
  j["change_pct"] =
      old_v != 0 ? Number(double(new_v - old_v) / double(old_v) * 100.0) : Json(nullptr);
  return j;
}

template <typename T>
Json OldNew(const T& old_v, const T& new_v) {
  Json j = Json::object();
  j["old"] = old_v;
  j["new"] = new_v;
  return j;
}

Json RuleJson(const RuleCountDiff& r) {
  Json j = Json::object();
  j["id"] = r.id;
  j["ran"] = OldNew(r.in_old, r.in_new);
  j["errors"] = OldNew(r.old_errors, r.new_errors);
  j["warnings"] = OldNew(r.old_warnings, r.new_warnings);
  j["findings_truncated"] = OldNew(r.old_truncated, r.new_truncated);
  j["past_cap"] = OldNew(r.old_past_cap, r.new_past_cap);
  return j;
}

// "line 57 stitch 12: message" of the new finding (one line).
std::string FindingText(const Finding& f) {
  std::string message = f.message;
  for (char& c : message) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  return detail::Location(f.line, f.stitch) + ": " + message;
}

// The errors of one rule the new programme has that the old one did not, one a line.
std::string NewErrorList(const ReportDiff& diff, const RuleCountDiff& r, long& count) {
  std::string text;
  count = 0;
  for (const FindingDiff& d : diff.findings) {
    if (d.Either().rule != r.id || !d.new_finding ||
        d.new_finding->severity != FindingSeverity::kError) {
      continue;
    }
    const bool appeared = d.change == FindingChange::kAppeared;
    const bool worse =
        d.change == FindingChange::kChanged && d.old_finding->severity == FindingSeverity::kWarning;
    if (!appeared && !worse) continue;
    text += (text.empty() ? "" : "\n") + std::string(appeared ? "appeared: " : "was a warning: ") +
            FindingText(*d.new_finding);
    ++count;
  }
  if (r.Truncated() && r.new_errors > r.old_errors) {
    text += (text.empty() ? "" : "\n") + std::string("findings truncated: errors ") +
            std::to_string(r.old_errors) + " -> " + std::to_string(r.new_errors);
    count = std::max(count, 1L);
  }
  return text;
}

std::string Testcase(const ReportDiff& diff, const RuleCountDiff& r) {
  std::string out = "    <testcase" + XmlAttribute("classname", "stitchsim.diff") +
                    XmlAttribute("name", r.id) + XmlAttribute("time", "0");
  long count = 0;
  const std::string errors = NewErrorList(diff, r, count);
  if (count == 0) return out + "/>\n";
  return out + ">\n      <failure" +
         XmlAttribute("message", Count(count, "new error", "new errors")) +
         XmlAttribute("type", r.id) + ">" + XmlEscape(errors, XmlContext::kText) +
         "</failure>\n    </testcase>\n";
}

}  // namespace

std::string ReportDiffToJson(const ReportDiff& diff) {
  Json j = Json::object();
  j["stitchsim_diff"] = kDiffFormatVersion;
  j["stitchsim_version"] = std::string(ToolVersion());
  j["new_errors"] = diff.new_errors;
  Json scene = Json::object();
  scene["file"] = diff.scene_file;
  scene["name"] = diff.scene_name;
  scene["head"] = diff.head;
  j["scene"] = std::move(scene);
  j["old"] = SideJson(diff.old_side);
  j["new"] = SideJson(diff.new_side);
  j["verdict"] = OldNew(diff.old_side.verdict, diff.new_side.verdict);
  j["stitches"] = Change(diff.old_side.stitches, diff.new_side.stitches);
  j["cycle_time_s"] = Change(diff.old_side.cycle_time_s, diff.new_side.cycle_time_s);
  j["cycle_time_timed_s"] =
      Change(diff.old_side.cycle_time_timed_s, diff.new_side.cycle_time_timed_s);
  Json options = Json::object();
  options["position_tolerance_mm"] = Number(diff.options.position_tolerance_mm);
  options["value_tolerance_pct"] = Number(diff.options.value_tolerance_pct);
  j["options"] = std::move(options);
  Json counts = Json::object();
  counts["appeared"] = diff.appeared;
  counts["disappeared"] = diff.disappeared;
  counts["changed"] = diff.changed;
  j["counts"] = std::move(counts);
  Json findings = Json::array();
  for (const FindingDiff& d : diff.findings) {
    Json f = Json::object();
    f["change"] = ChangeName(d.change);
    f["rule"] = d.Either().rule;
    f["subject"] = d.Either().subject;
    f["unit"] = d.Either().unit;
    f["matched_by"] = MatchName(d.match);
    f["old"] = FindingJson(d.old_finding);
    f["new"] = FindingJson(d.new_finding);
    findings.push_back(std::move(f));
  }
  j["findings"] = std::move(findings);
  Json rules = Json::array();
  for (const RuleCountDiff& r : diff.rules) rules.push_back(RuleJson(r));
  j["rules"] = std::move(rules);
  return j.dump(2, ' ', /*ensure_ascii=*/false, Json::error_handler_t::replace) + "\n";
}

std::string ReportDiffToJunit(const ReportDiff& diff) {
  std::string cases;
  long failures = 0;
  for (const RuleCountDiff& r : diff.rules) {
    std::string c = Testcase(diff, r);
    if (c.find("<failure") != std::string::npos) ++failures;
    cases += c;
  }
  const std::string tests = std::to_string(diff.rules.size()), failed = std::to_string(failures);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites" + XmlAttribute("name", "stitchsim") + XmlAttribute("tests", tests) +
         XmlAttribute("failures", failed) + XmlAttribute("errors", "0") +
         XmlAttribute("time", "0") + ">\n";
  out += "  <testsuite" + XmlAttribute("name", "stitchsim.diff") + XmlAttribute("tests", tests) +
         XmlAttribute("failures", failed) + XmlAttribute("errors", "0") +
         XmlAttribute("skipped", "0") + XmlAttribute("time", "0") + ">\n";
  out += "    <properties>\n";
  out += "      <property" + XmlAttribute("name", "old_program") +
         XmlAttribute("value", diff.old_side.program_file) + "/>\n";
  out += "      <property" + XmlAttribute("name", "new_program") +
         XmlAttribute("value", diff.new_side.program_file) + "/>\n";
  out += "      <property" + XmlAttribute("name", "scene") +
         XmlAttribute("value", diff.scene_name) + "/>\n";
  out += "    </properties>\n";
  out += cases;
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

}  // namespace stitchsim::verify
