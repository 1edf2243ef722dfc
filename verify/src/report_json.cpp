// The JSON report (docs/report-format.md, "JSON report"). Keys are written in the order below,
// which is part of the format; numbers go through nlohmann's shortest round-trip printer.

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "detail/json_format.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::verify {
namespace {

using Json = nlohmann::ordered_json;

constexpr int kFormatVersion = 1;

using detail::Number;

Json OptionalNumber(const std::optional<double>& v) { return v ? Number(*v) : Json(nullptr); }

using detail::SeverityName;

Json FindingToJson(const Finding& finding) {
  Json j = Json::object();
  j["rule"] = finding.rule;
  j["severity"] = SeverityName(finding.severity);
  j["line"] = finding.line;
  j["stitch"] = finding.stitch;
  j["value"] = Number(finding.value);
  j["limit"] = Number(finding.limit);
  j["unit"] = finding.unit;
  j["subject"] = finding.subject;
  j["message"] = finding.message;
  if (finding.position_mm) {
    const auto& p = *finding.position_mm;
    j["position_mm"] = Json::array({Number(p[0]), Number(p[1]), Number(p[2])});
  } else {
    j["position_mm"] = nullptr;
  }
  return j;
}

// {value, line, stitch}, or null when nothing was measured.
Json WorstToJson(const std::optional<double>& value, int line, long stitch) {
  if (!value) return Json(nullptr);
  Json worst = Json::object();
  worst["value"] = Number(*value);
  worst["line"] = line;
  worst["stitch"] = stitch;
  return worst;
}

Json SubjectToJson(const SubjectFigure& s) {
  Json j = Json::object();
  j["subject"] = s.subject;
  j["checked"] = s.checked;
  j["applies"] = s.checked > 0;
  j["error_limit"] = OptionalNumber(s.error_limit);
  j["warning_limit"] = OptionalNumber(s.warning_limit);
  j["worst"] =
      s.checked > 0 ? WorstToJson(s.worst_value, s.worst_line, s.worst_stitch) : Json(nullptr);
  return j;
}

Json RuleToJson(const RuleSummary& rule) {
  Json j = Json::object();
  j["id"] = rule.id;
  j["description"] = rule.description;
  j["unit"] = rule.unit;
  j["checked"] = rule.checked;
  j["applies"] = rule.Applies();
  j["errors"] = rule.errors;
  j["warnings"] = rule.warnings;
  j["error_limit"] = OptionalNumber(rule.error_limit);
  j["warning_limit"] = OptionalNumber(rule.warning_limit);
  // A rule that checked nothing has no worst value ("n/a"), whatever it observed.
  j["worst"] = rule.Applies() ? WorstToJson(rule.worst_value, rule.worst_line, rule.worst_stitch)
                              : Json(nullptr);
  Json subjects = Json::array();
  for (const SubjectFigure& s : rule.subjects) subjects.push_back(SubjectToJson(s));
  j["subjects"] = std::move(subjects);
  j["findings_truncated"] = rule.truncated;
  Json findings = Json::array();
  for (const Finding& finding : rule.findings) findings.push_back(FindingToJson(finding));
  j["findings"] = std::move(findings);
  return j;
}

Json LaydownToJson(const LaydownFigures& f) {
  Json j = Json::object();
  j["ply"] = f.ply;
  j["laid_path_mm"] = Number(f.laid_path_mm);
  j["laydown_s"] = Number(f.laydown_s);
  j["laydown_timed_s"] = Number(f.laydown_timed_s);
  j["off_part_s"] = Number(f.off_part_s);
  j["off_part_timed_s"] = Number(f.off_part_timed_s);
  j["tow_length_mm"] = Number(f.tow_length_mm);
  j["material_kg"] = Number(f.material_kg);
  j["rate_kg_h"] = Number(f.rate_kg_h);
  j["tows_added"] = f.tows_added;
  j["tows_cut"] = f.tows_cut;
  j["shortest_tow_mm"] = OptionalNumber(f.shortest_tow_mm);
  j["thickness_min_mm"] = OptionalNumber(f.thickness_min_mm);
  j["thickness_max_mm"] = OptionalNumber(f.thickness_max_mm);
  j["worst_fiber_angle_deg"] = OptionalNumber(f.worst_fiber_angle_deg);
  return j;
}

}  // namespace

std::string ReportToJson(const Report& report) {
  Json j = Json::object();
  j["stitchsim_report"] = kFormatVersion;
  j["stitchsim_version"] = report.tool_version;
  j["verdict"] = report.verdict;
  j["program"] = report.program_file;
  Json scene = Json::object();
  scene["file"] = report.scene_file;
  scene["name"] = report.scene_name;
  scene["head"] = report.head;
  j["scene"] = std::move(scene);
  Json counts = Json::object();
  counts["lines"] = report.lines;
  counts["moves"] = report.moves;
  counts["stitches"] = report.stitches;
  counts["errors"] = report.errors;
  counts["warnings"] = report.warnings;
  j["counts"] = std::move(counts);
  j["stitch_length_mm"] = Number(report.stitch_length_mm);
  j["cycle_time_s"] = Number(report.cycle_time_s);
  j["cycle_time_timed_s"] = Number(report.cycle_time_timed_s);
  Json rules = Json::array();
  for (const RuleSummary& rule : report.rules) rules.push_back(RuleToJson(rule));
  j["rules"] = std::move(rules);
  Json skipped = Json::array();
  for (const SkippedRule& rule : report.skipped) {
    Json s = Json::object();
    s["id"] = rule.id;
    s["reason"] = rule.reason;
    skipped.push_back(std::move(s));
  }
  j["skipped_rules"] = std::move(skipped);
  if (!report.laydown.empty()) {  // AFP programmes only
    Json laydown = Json::array();
    for (const LaydownFigures& f : report.laydown) laydown.push_back(LaydownToJson(f));
    j["laydown"] = std::move(laydown);
  }
  // Malformed UTF-8 in a string (a programme comment, a path) becomes U+FFFD instead of
  // throwing; non-ASCII stays UTF-8 and control characters are escaped as \u00XX.
  return j.dump(2, ' ', /*ensure_ascii=*/false, Json::error_handler_t::replace) + "\n";
}

}  // namespace stitchsim::verify
