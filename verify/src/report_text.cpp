// The plain-text summary of a Report, for stdout (docs/report-format.md, "Text summary").

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "detail/text_format.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::verify {
namespace {

using detail::Count;
using detail::FormatNumber;
using detail::Location;
using detail::NextCodePoint;
using detail::Printable;

constexpr std::size_t kTextColumns = 100;
constexpr std::size_t kExamplesPerRule = 5;

// Columns taken by valid UTF-8 text, counting one per code point (wide CJK glyphs are rare
// enough in reports not to matter).
std::size_t Columns(std::string_view s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// Cuts valid UTF-8 text to at most `columns` columns, ending in "..." when cut.
std::string Shorten(std::string s, std::size_t columns) {
  if (Columns(s) <= columns) return s;
  const std::size_t keep = columns > 3 ? columns - 3 : 0;
  std::size_t kept = 0;
  std::size_t pos = 0;
  while (pos < s.size() && kept < keep) {
    NextCodePoint(s, pos);
    ++kept;
  }
  s.resize(pos);
  return s + "...";
}

std::string FormatFixed1(double v) {
  if (!std::isfinite(v)) return FormatNumber(v);
  std::array<char, 400> buffer{};  // room for the largest double in fixed notation
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::fixed, 1);
  return std::string(buffer.data(), result.ptr);
}

using detail::WithUnit;

std::string Uppercase(std::string s) {
  for (char& c : s) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return s;
}

// ", 3 skipped (--no-collision: collision.head_mold, ...)": the skipped rules by reason.
std::string SkippedText(const std::vector<SkippedRule>& skipped) {
  if (skipped.empty()) return "";
  std::string out = ", " + std::to_string(skipped.size()) + " skipped (";
  for (std::size_t i = 0; i < skipped.size(); ++i) {
    const bool new_reason = i == 0 || skipped[i].reason != skipped[i - 1].reason;
    if (new_reason) {
      out += (i == 0 ? "" : "; ") + Printable(skipped[i].reason) + ": ";
    } else {
      out += ", ";
    }
    out += Printable(skipped[i].id);
  }
  return out + ")";
}

std::string Headline(const Report& report) {
  const std::string& scene = report.scene_name.empty() ? report.scene_file : report.scene_name;
  std::string line = report.verdict.empty() ? "UNKNOWN" : Uppercase(Printable(report.verdict));
  line += "  " + (report.program_file.empty() ? "(no programme)" : Printable(report.program_file));
  if (!scene.empty()) line += " on " + Printable(scene);
  if (!report.head.empty()) line += " (" + Printable(report.head) + ")";
  line += ": " + Count(report.errors, "error", "errors") + ", " +
          Count(report.warnings, "warning", "warnings") + " in " +
          Count(static_cast<long>(report.rules.size()), "rule", "rules") +
          SkippedText(report.skipped) + "; " + Count(report.stitches, "stitch", "stitches") + ", " +
          Count(report.moves, "move", "moves") + ", cycle " + FormatFixed1(report.cycle_time_s) +
          " s";
  if (report.cycle_time_timed_s > 0.0) {
    line += " at the programmed speeds, " + FormatFixed1(report.cycle_time_timed_s) +
            " s with acceleration";
  }
  return line;
}

std::string LimitCell(const std::optional<double>& error_limit,
                      const std::optional<double>& warning_limit, const std::string& unit) {
  std::string cell = error_limit ? WithUnit(FormatNumber(*error_limit), unit) : std::string("-");
  if (warning_limit) cell += " (warn " + FormatNumber(*warning_limit) + ")";
  return cell;
}

// The worst and where: "n/a" for a rule (or subject) that checked nothing, "-" when nothing
// was measured.
std::array<std::string, 2> WorstCells(long checked, const std::optional<double>& worst, int line,
                                      long stitch, const std::string& unit) {
  if (checked == 0) return {"n/a", "-"};
  if (!worst) return {"-", "-"};
  return {WithUnit(FormatNumber(*worst), unit), Location(line, stitch)};
}

// The table: one row of cells per rule under a header; numeric columns right-aligned.
std::string Table(const std::vector<RuleSummary>& rules) {
  enum Align { kLeft, kRight };
  const std::array<Align, 7> align = {kLeft, kRight, kRight, kRight, kLeft, kLeft, kLeft};
  std::vector<std::array<std::string, 7>> rows;
  rows.push_back({"rule", "checked", "errors", "warnings", "worst", "at", "limit"});
  for (const RuleSummary& rule : rules) {
    const auto worst =
        WorstCells(rule.checked, rule.worst_value, rule.worst_line, rule.worst_stitch, rule.unit);
    rows.push_back({Printable(rule.id), std::to_string(rule.checked), std::to_string(rule.errors),
                    std::to_string(rule.warnings), worst[0], worst[1],
                    LimitCell(rule.error_limit, rule.warning_limit, rule.unit)});
    // Each subject with its own limits gets its own row, its figure beside its limit.
    for (const SubjectFigure& s : rule.subjects) {
      const auto cells =
          WorstCells(s.checked, s.worst_value, s.worst_line, s.worst_stitch, rule.unit);
      rows.push_back({"  " + Printable(s.subject), std::to_string(s.checked), "", "", cells[0],
                      cells[1], LimitCell(s.error_limit, s.warning_limit, rule.unit)});
    }
  }
  std::array<std::size_t, 7> width{};
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], Columns(row[c]));
  }
  std::string out;
  for (const auto& row : rows) {
    std::string line = " ";
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string pad(width[c] - Columns(row[c]), ' ');
      line += ' ';
      line += align[c] == kRight ? pad + row[c] : row[c] + pad;
      line += ' ';
    }
    line.erase(line.find_last_not_of(' ') + 1);
    out += line + "\n";
  }
  return out;
}

// Up to kExamplesPerRule error findings of a failing rule, then how many more there are.
std::string Examples(const RuleSummary& rule) {
  std::string out = Printable(rule.id) + ": " + Count(rule.errors, "error", "errors") + "\n";
  long shown = 0;
  for (const Finding& finding : rule.findings) {
    if (finding.severity != FindingSeverity::kError) continue;
    if (shown == static_cast<long>(kExamplesPerRule)) break;
    const std::string prefix = "  " + Location(finding.line, finding.stitch) + ": ";
    const std::size_t room =
        kTextColumns > Columns(prefix) + 20 ? kTextColumns - Columns(prefix) : std::size_t{20};
    out += prefix + Shorten(Printable(finding.message), room) + "\n";
    ++shown;
  }
  if (rule.errors > shown) out += "  ... and " + std::to_string(rule.errors - shown) + " more\n";
  return out;
}

// One line of laydown figures: "laydown ply 2: ..." or "laydown, whole programme: ...".
std::string LaydownLine(const LaydownFigures& f) {
  std::string out =
      f.ply == 0 ? "laydown, whole programme: " : "laydown ply " + std::to_string(f.ply) + ": ";
  out += FormatNumber(f.laid_path_mm) + " mm of lay-up in " + FormatNumber(f.laydown_s) +
         " s at the feeds with the cut/add slow zones, " + FormatNumber(f.laydown_timed_s) +
         " s with acceleration; off-part " + FormatNumber(f.off_part_s) + " s (" +
         FormatNumber(f.off_part_timed_s) + " s timed); " + FormatNumber(f.material_kg) +
         " kg laid, " + FormatNumber(f.rate_kg_h) + " kg/h; " + Count(f.tows_added, "tow", "tows") +
         " added, " + std::to_string(f.tows_cut) + " cut; shortest tow piece " +
         (f.shortest_tow_mm ? FormatNumber(*f.shortest_tow_mm) + " mm" : std::string("-"));
  out += "; thickness ";
  out += f.thickness_min_mm && f.thickness_max_mm ? FormatNumber(*f.thickness_min_mm) + " to " +
                                                        FormatNumber(*f.thickness_max_mm) + " mm"
                                                  : std::string("-");
  out += "; worst fibre angle ";
  out +=
      f.worst_fiber_angle_deg ? FormatNumber(*f.worst_fiber_angle_deg) + " deg" : std::string("-");
  return out + "\n";
}

}  // namespace

std::string ReportToText(const Report& report) {
  std::string out = Headline(report) + "\n";
  if (report.rules.empty()) return out + "\n  (no rules ran)\n";
  out += "\n" + Table(report.rules);
  for (const RuleSummary& rule : report.rules) {
    if (rule.errors > 0) out += "\n" + Examples(rule);
  }
  if (!report.laydown.empty()) out += "\n";
  for (const LaydownFigures& f : report.laydown) out += LaydownLine(f);
  return out;
}

}  // namespace stitchsim::verify
