// A rule's accumulators as JSON and back (Rule::SavePartial, Rule::LoadPartial): the
// per-rule half of the verifier partial (Verifier::SavePartial, docs/report-format.md).
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "detail/partial_json.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

using detail::DoubleFromJson;
using detail::DoubleToJson;
using detail::OptionalFromJson;
using detail::OptionalToJson;
using nlohmann::json;

const char* SeverityText(FindingSeverity s) {
  return s == FindingSeverity::kError ? "error" : "warning";
}

FindingSeverity SeverityFrom(const json& j) {
  const std::string s = j.get<std::string>();
  if (s == "error") return FindingSeverity::kError;
  if (s == "warning") return FindingSeverity::kWarning;
  throw std::invalid_argument("severity '" + s + "'");
}

json PositionToJson(const std::optional<std::array<double, 3>>& p) {
  return p ? json::array({DoubleToJson((*p)[0]), DoubleToJson((*p)[1]), DoubleToJson((*p)[2])})
           : json(nullptr);
}

std::optional<std::array<double, 3>> PositionFrom(const json& j) {
  if (j.is_null()) return std::nullopt;
  if (!j.is_array() || j.size() != 3) throw std::invalid_argument("position_mm");
  return std::array<double, 3>{DoubleFromJson(j.at(0)), DoubleFromJson(j.at(1)),
                               DoubleFromJson(j.at(2))};
}

json FindingToPartialJson(const Finding& f) {
  return json{{"rule", f.rule},
              {"severity", SeverityText(f.severity)},
              {"line", f.line},
              {"stitch", f.stitch},
              {"value", DoubleToJson(f.value)},
              {"limit", DoubleToJson(f.limit)},
              {"unit", f.unit},
              {"subject", f.subject},
              {"message", f.message},
              {"position_mm", PositionToJson(f.position_mm)}};
}

Finding FindingFrom(const json& j) {
  Finding f;
  f.rule = j.at("rule").get<std::string>();
  f.severity = SeverityFrom(j.at("severity"));
  f.line = j.at("line").get<int>();
  f.stitch = j.at("stitch").get<long>();
  f.value = DoubleFromJson(j.at("value"));
  f.limit = DoubleFromJson(j.at("limit"));
  f.unit = j.at("unit").get<std::string>();
  f.subject = j.at("subject").get<std::string>();
  f.message = j.at("message").get<std::string>();
  f.position_mm = PositionFrom(j.at("position_mm"));
  return f;
}

json SubjectToPartialJson(const SubjectFigure& s) {
  return json{{"subject", s.subject},
              {"checked", s.checked},
              {"error_limit", OptionalToJson(s.error_limit)},
              {"warning_limit", OptionalToJson(s.warning_limit)},
              {"worst_value", OptionalToJson(s.worst_value)},
              {"worst_line", s.worst_line},
              {"worst_stitch", s.worst_stitch}};
}

SubjectFigure SubjectFrom(const json& j) {
  SubjectFigure s;
  s.subject = j.at("subject").get<std::string>();
  s.checked = j.at("checked").get<long>();
  s.error_limit = OptionalFromJson(j.at("error_limit"));
  s.warning_limit = OptionalFromJson(j.at("warning_limit"));
  s.worst_value = OptionalFromJson(j.at("worst_value"));
  s.worst_line = j.at("worst_line").get<int>();
  s.worst_stitch = j.at("worst_stitch").get<long>();
  return s;
}

json SummaryToJson(const RuleSummary& s) {
  json subjects = json::array(), findings = json::array();
  for (const SubjectFigure& f : s.subjects) subjects.push_back(SubjectToPartialJson(f));
  for (const Finding& f : s.findings) findings.push_back(FindingToPartialJson(f));
  return json{{"id", s.id},
              {"description", s.description},
              {"unit", s.unit},
              {"checked", s.checked},
              {"errors", s.errors},
              {"warnings", s.warnings},
              {"error_limit", OptionalToJson(s.error_limit)},
              {"warning_limit", OptionalToJson(s.warning_limit)},
              {"worst_value", OptionalToJson(s.worst_value)},
              {"worst_line", s.worst_line},
              {"worst_stitch", s.worst_stitch},
              {"subjects", std::move(subjects)},
              {"findings", std::move(findings)},
              {"truncated", s.truncated}};
}

RuleSummary SummaryFrom(const json& j) {
  RuleSummary s;
  s.id = j.at("id").get<std::string>();
  s.description = j.at("description").get<std::string>();
  s.unit = j.at("unit").get<std::string>();
  s.checked = j.at("checked").get<long>();
  s.errors = j.at("errors").get<long>();
  s.warnings = j.at("warnings").get<long>();
  s.error_limit = OptionalFromJson(j.at("error_limit"));
  s.warning_limit = OptionalFromJson(j.at("warning_limit"));
  s.worst_value = OptionalFromJson(j.at("worst_value"));
  s.worst_line = j.at("worst_line").get<int>();
  s.worst_stitch = j.at("worst_stitch").get<long>();
  for (const json& f : j.at("subjects")) s.subjects.push_back(SubjectFrom(f));
  for (const json& f : j.at("findings")) s.findings.push_back(FindingFrom(f));
  s.truncated = j.at("truncated").get<bool>();
  return s;
}

// Why `loaded` is not `mine`'s rule as configured here (empty when it is).
std::string ConfigDifference(const RuleSummary& mine, const RuleSummary& loaded) {
  if (loaded.id != mine.id) return "rule " + loaded.id + " where " + mine.id + " was expected";
  if (loaded.description != mine.description || loaded.unit != mine.unit)
    return "rule " + mine.id + ": another description or unit";
  if (!detail::SameOptional(loaded.error_limit, mine.error_limit) ||
      !detail::SameOptional(loaded.warning_limit, mine.warning_limit))
    return "rule " + mine.id + ": other limits (another scene?)";
  if (loaded.subjects.size() != mine.subjects.size()) return "rule " + mine.id + ": other subjects";
  for (std::size_t i = 0; i < mine.subjects.size(); ++i) {
    const SubjectFigure &a = mine.subjects[i], &b = loaded.subjects[i];
    if (a.subject != b.subject || !detail::SameOptional(a.error_limit, b.error_limit) ||
        !detail::SameOptional(a.warning_limit, b.warning_limit))
      return "rule " + mine.id + ": other subjects or subject limits";
  }
  if (loaded.findings.size() > kMaxFindingsPerRule)
    return "rule " + mine.id + ": more findings than a rule keeps";
  return "";
}

}  // namespace

json Rule::SavePartial() const {
  if (!mergeable_ && SawAnything()) {
    throw std::logic_error("AFP programmes are verified in one part (" + summary_.id + ")");
  }
  json recent = json::array();
  for (const LineFinding& e : recent_lines_) {
    const long index = e.index == static_cast<std::size_t>(-1) ? -1L : static_cast<long>(e.index);
    recent.push_back(json::array({e.line, SeverityText(e.severity), index}));
  }
  json extra = json::object();
  SaveExtra(extra);
  return json{{"id", summary_.id},
              {"summary", SummaryToJson(summary_)},
              {"extra", std::move(extra)},
              {"base", json{{"saw_input", saw_input_},
                            {"recent_lines", std::move(recent)},
                            {"series", series_.ToJson()}}}};
}

bool Rule::LoadPartial(const json& j, std::string& error) {
  RuleSummary loaded;
  std::deque<LineFinding> recent;
  bool saw_input = false;
  ValueSeries series;
  try {
    if (!j.is_object()) throw std::invalid_argument("not an object");
    if (j.at("id").get<std::string>() != summary_.id) {
      error = "rule " + j.at("id").get<std::string>() + " where " + summary_.id + " was expected";
      return false;
    }
    loaded = SummaryFrom(j.at("summary"));
    error = ConfigDifference(summary_, loaded);
    if (!error.empty()) return false;
    const json& base = j.at("base");
    saw_input = base.at("saw_input").get<bool>();
    for (const json& e : base.at("recent_lines")) {
      const long index = e.at(2).get<long>();
      if (index >= static_cast<long>(loaded.findings.size()))
        throw std::invalid_argument("a finding index beyond the findings");
      recent.push_back(
          {e.at(0).get<int>(), SeverityFrom(e.at(1)),
           index < 0 ? static_cast<std::size_t>(-1) : static_cast<std::size_t>(index)});
    }
    if (recent.size() > kRecentFindingLines) throw std::invalid_argument("too many recent lines");
    if (!series.FromJson(base.at("series"))) throw std::invalid_argument("malformed \"series\"");
    if (!LoadExtra(j.at("extra"))) throw std::invalid_argument("malformed \"extra\"");
  } catch (const std::exception& e) {
    error = "rule " + summary_.id + ": " + e.what();
    return false;
  }
  summary_ = std::move(loaded);
  recent_lines_ = std::move(recent);
  saw_input_ = saw_input;
  series_ = std::move(series);
  worst_sample_.reset();
  worst_entry_tool_.reset();
  return true;
}

}  // namespace stitchsim::verify
