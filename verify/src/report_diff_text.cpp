// The plain-text diff of two reports, for stdout (docs/report-format.md, "Diff").

#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>

#include "detail/text_format.h"
#include "stitchsim/verify/report_diff.h"

namespace stitchsim::verify {
namespace {

using detail::Count;
using detail::FormatNumber;
using detail::Printable;

using detail::WithUnit;

std::string Signed(double v) { return (v > 0.0 ? "+" : "") + FormatNumber(v); }

// "61.2 s -> 61.5 s (+0.3 s, +0.49 %)"; the percentage left out when the old time is 0.
std::string TimeChange(double old_s, double new_s) {
  std::string out =
      FormatNumber(old_s) + " s -> " + FormatNumber(new_s) + " s (" + Signed(new_s - old_s) + " s";
  if (old_s != 0.0) out += ", " + Signed((new_s - old_s) / old_s * 100.0) + " %";
  return out + ")";
}

const char* Severity(FindingSeverity s) {
  return s == FindingSeverity::kError ? "error" : "warning";
}

std::string NumberOrDash(long v) { return v > 0 ? std::to_string(v) : std::string("-"); }

// " line 57 (was 55)": the new number, then the old one where it differs (absent: the finding
// is not in that report; 0: not tied to a line or stitch).
std::string Where(const char* what, std::optional<long> old, std::optional<long> neu) {
  if (old.value_or(0) == 0 && neu.value_or(0) == 0) return "";
  std::string out = std::string(" ") + what + " " + (neu ? NumberOrDash(*neu) : "-");
  if (!neu || !old || *old != *neu) out += " (was " + (old ? NumberOrDash(*old) : "-") + ")";
  return out;
}

std::optional<long> LineOf(const std::optional<Finding>& f) {
  return f ? std::optional<long>(f->line) : std::nullopt;
}
std::optional<long> StitchOf(const std::optional<Finding>& f) {
  return f ? std::optional<long>(f->stitch) : std::nullopt;
}

// A coordinate to 0.1 mm (the default position tolerance is 0.5 mm).
std::string Tenths(double v) {
  if (!std::isfinite(v)) return FormatNumber(v);
  std::array<char, 400> buffer{};  // room for the largest double in fixed notation
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::fixed, 1);
  return std::string(buffer.data(), result.ptr);
}

std::string Position(const Finding& f) {
  if (!f.position_mm) return "";
  const auto& p = *f.position_mm;
  return " at (" + Tenths(p[0]) + ", " + Tenths(p[1]) + ", " + Tenths(p[2]) + ") mm";
}

// One finding on one line: "+ rule error line 57 (was -) stitch 12 at (...) mm: 3.2 mm
// (limit 0 mm) [subject]".
std::string FindingLine(const FindingDiff& d) {
  const Finding& f = d.Either();
  std::string line = d.change == FindingChange::kAppeared      ? "  + "
                     : d.change == FindingChange::kDisappeared ? "  - "
                                                               : "  ~ ";
  line += Printable(f.rule) + " ";
  if (d.change == FindingChange::kChanged && d.old_finding->severity != f.severity) {
    line += std::string(Severity(d.old_finding->severity)) + " -> ";
  }
  line += Severity(f.severity);
  line += Where("line", LineOf(d.old_finding), LineOf(d.new_finding));
  line += Where("stitch", StitchOf(d.old_finding), StitchOf(d.new_finding));
  line += Position(f) + ": ";
  if (d.change == FindingChange::kChanged) line += FormatNumber(d.old_finding->value) + " -> ";
  line += WithUnit(FormatNumber(f.value), f.unit);
  line += " (limit " + WithUnit(FormatNumber(f.limit), f.unit) + ")";
  if (!f.subject.empty()) line += " [" + Printable(f.subject) + "]";
  return line + "\n";
}

std::string Truncation(const RuleCountDiff& r) {
  if (!r.Truncated()) return "";
  std::string which = r.old_truncated && r.new_truncated ? "old and new"
                      : r.old_truncated                  ? "old"
                                                         : "new";
  std::string out = "; findings truncated in " + which + " report";
  const long past = r.old_past_cap + r.new_past_cap;
  if (past > 0) out += ", " + Count(past, "finding", "findings") + " past the cap not compared";
  return out;
}

std::string RuleLine(const RuleCountDiff& r) {
  std::string line = "  " + Printable(r.id) + ": ";
  if (!r.in_old) line += "(new rule) ";
  if (!r.in_new) line += "(not run in new) ";
  line += "errors " + std::to_string(r.old_errors) + " -> " + std::to_string(r.new_errors) +
          ", warnings " + std::to_string(r.old_warnings) + " -> " + std::to_string(r.new_warnings);
  return line + Truncation(r) + "\n";
}

std::string Verdict(const std::string& v) { return v.empty() ? "unknown" : Printable(v); }

}  // namespace

std::string ReportDiffToText(const ReportDiff& diff) {
  const DiffSide &o = diff.old_side, &n = diff.new_side;
  const bool any = diff.appeared + diff.disappeared + diff.changed > 0;
  bool counts = false;  // a truncated rule's counts may change with no finding listed
  for (const RuleCountDiff& r : diff.rules) counts = counts || r.CountsChanged();
  std::string out = diff.new_errors ? "NEW ERRORS" : any || counts ? "CHANGED" : "SAME";
  out += "  " + Printable(o.program_file) + " -> " + Printable(n.program_file);
  const std::string& scene = diff.scene_name.empty() ? diff.scene_file : diff.scene_name;
  if (!scene.empty()) out += " on " + Printable(scene);
  out += ": " + std::to_string(diff.appeared) + " appeared, " + std::to_string(diff.disappeared) +
         " disappeared, " + std::to_string(diff.changed) + " changed; verdict " +
         Verdict(o.verdict) + " -> " + Verdict(n.verdict) + "\n";
  out += "  stitches " + std::to_string(o.stitches) + " -> " + std::to_string(n.stitches) + " (" +
         (n.stitches >= o.stitches ? "+" : "") + std::to_string(n.stitches - o.stitches) +
         "), cycle " + TimeChange(o.cycle_time_s, n.cycle_time_s);
  if (o.cycle_time_timed_s > 0.0 || n.cycle_time_timed_s > 0.0) {
    out += ", with acceleration " + TimeChange(o.cycle_time_timed_s, n.cycle_time_timed_s);
  }
  out += "\n  errors " + std::to_string(o.errors) + " -> " + std::to_string(n.errors) +
         ", warnings " + std::to_string(o.warnings) + " -> " + std::to_string(n.warnings) + "\n";
  if (any) {
    out +=
        "\nfindings (+ appeared, - disappeared, ~ changed; line and stitch in the new "
        "programme, was: the old):\n";
    for (const FindingDiff& d : diff.findings) out += FindingLine(d);
  }
  std::string rules;
  for (const RuleCountDiff& r : diff.rules) {
    if (r.CountsChanged() || r.Truncated()) rules += RuleLine(r);
  }
  if (!rules.empty()) out += "\nrules whose counts changed or were truncated:\n" + rules;
  return out;
}

}  // namespace stitchsim::verify
