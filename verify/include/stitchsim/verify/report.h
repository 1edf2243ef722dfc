#pragma once
// The verification report: verdict, per-rule summaries and findings. Filled by the verifier
// (verify/verifier.h), written as text, JSON (docs/report-format.md) and JUnit XML. Writers
// are deterministic: the same report gives byte-identical output.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/version.h"

namespace stitchsim::verify {

enum class FindingSeverity { kWarning, kError };

/// One rule violation at one place in the programme.
struct Finding {
  std::string rule;  ///< rule id, e.g. "needle.side_force"
  FindingSeverity severity = FindingSeverity::kError;
  int line = 0;         ///< 1-based source line of the programme; 0 = not tied to a line
  long stitch = 0;      ///< 1-based stitch index; 0 = not tied to a stitch
  double value = 0.0;   ///< what was measured, in `unit`
  double limit = 0.0;   ///< the limit it broke, in `unit`
  std::string unit;     ///< "mm", "deg", "%", "N", "" (dimensionless)
  std::string subject;  ///< what was measured: a needle ("insertion"), a joint ("a5"), ...
  std::string message;  ///< one sentence for people
  /// Where: the tool point of the sample the finding was made at, part frame, mm (absent for
  /// a finding not made at a sample, e.g. program.stitch_count). `stitchsim diff` matches
  /// findings of two programmes by it.
  std::optional<std::array<double, 3>> position_mm;
};

/// One subject's figure beside its own limits, for a rule whose subjects are limited
/// differently (stitch.length: the needle at the tool point and the insertion needle).
struct SubjectFigure {
  std::string subject;                  ///< "insertion", "catcher", ...
  long checked = 0;                     ///< items of this subject checked
  std::optional<double> error_limit;    ///< this subject's error limit, if any
  std::optional<double> warning_limit;  ///< this subject's warning limit, if any
  std::optional<double> worst_value;    ///< this subject's worst value, in the rule's unit
  int worst_line = 0;
  long worst_stitch = 0;
};

/// Everything one rule saw over the whole programme.
struct RuleSummary {
  std::string id;           ///< "needle.side_force"
  std::string description;  ///< one line: what the rule checks
  std::string unit;         ///< unit of values and limits
  long checked = 0;         ///< items checked (stitches, samples, lines; see the rule); 0 = n/a
  long errors = 0;          ///< error findings, one per line at most (all, even past the cap)
  long warnings = 0;        ///< warning findings, one per line at most (all, even past the cap)
  std::optional<double> error_limit;    ///< the error limit in force, if the rule has one
  std::optional<double> warning_limit;  ///< the warning limit in force, if any
  /// The worst value seen (largest, or smallest for lower-bound rules) and where.
  std::optional<double> worst_value;
  int worst_line = 0;
  long worst_stitch = 0;
  /// Per-subject figures with their own limits (empty for most rules). The rule-level worst
  /// and limits above are those of the subject the rule's own limits apply to.
  std::vector<SubjectFigure> subjects;
  std::vector<Finding> findings;  ///< the first kMaxFindingsPerRule findings, in line order
  bool truncated = false;         ///< more findings than were kept
  /// False when the rule found nothing to check (reported as "n/a", never as a worst value).
  bool Applies() const { return checked > 0; }
};

/// A rule that did not run, and why (e.g. the collision rules under --no-collision).
struct SkippedRule {
  std::string id;      ///< "collision.head_mold"
  std::string reason;  ///< "--no-collision"
};

inline constexpr std::size_t kMaxFindingsPerRule = 200;

/// Laydown figures of an AFP programme (verify/laydown.h, docs/report-format.md "Laydown").
/// One ply's, or the whole programme's.
struct LaydownFigures {
  int ply = 0;                   ///< M70 P<n>; 0: the whole programme
  double laid_path_mm = 0.0;     ///< tool-point path of the lay-up runs, mm
  double laydown_s = 0.0;        ///< lay-up runs at the programmed feeds, slow zones applied, s
  double laydown_timed_s = 0.0;  ///< the same with the controller's ramps (RampedTime), s
  double off_part_s = 0.0;       ///< every other motion line at its programmed speed, s
  /// The same on the controller's time law (the trace's timed durations; the programmed
  /// duration of a line the trace did not time), s.
  double off_part_timed_s = 0.0;
  double tow_length_mm = 0.0;  ///< every tow piece's length, summed, mm
  double material_kg = 0.0;    ///< tow length x tow width x areal weight, kg
  /// material_kg / (laydown_timed_s + off_part_timed_s) per hour, kg/h; 0 with no time.
  double rate_kg_h = 0.0;
  long tows_added = 0;                    ///< tow adds (a run's start counts each tow it lays)
  long tows_cut = 0;                      ///< tow cuts (a run's end counts each tow it lays)
  std::optional<double> shortest_tow_mm;  ///< shortest tow piece (add to cut, along x), mm
  /// The stack thickness over the area the ply laid, just after it is laid (the whole
  /// programme: over all the area laid, at its end), smallest and largest, mm; from
  /// afp.compaction's thickness map (cells of 2 mm in (u, v)); absent when nothing was laid.
  std::optional<double> thickness_min_mm;
  std::optional<double> thickness_max_mm;
  /// The worst fibre-angle deviation of the ply's tows (afp.fiber_angle), deg; absent when
  /// the rule judged none of its lines.
  std::optional<double> worst_fiber_angle_deg;
};

struct Report {
  std::string program_file;  ///< as given on the command line
  std::string scene_file;
  std::string scene_name;
  std::string head;
  std::string verdict;  ///< "pass" (no errors) or "fail"
  long lines = 0;       ///< programme lines read
  long moves = 0;       ///< motion lines executed
  long stitches = 0;    ///< stitch cycles executed
  double stitch_length_mm = 0.0;
  double cycle_time_s = 0.0;  ///< programme time at the programmed speeds (simple)
  /// Programme time on the controller's time law (acceleration ramps, axis limits, blending;
  /// docs/timing.md); 0 when the run was not timed.
  double cycle_time_timed_s = 0.0;
  long errors = 0;                   ///< sum over rules
  long warnings = 0;                 ///< sum over rules
  std::vector<RuleSummary> rules;    ///< in registry order
  std::vector<SkippedRule> skipped;  ///< rules that did not run, in registry order
  /// AFP programmes: per ply (M70 P<n>, in ply order), then the whole programme (ply 0);
  /// empty for a stitching head.
  std::vector<LaydownFigures> laydown;
  std::string tool_version{stitchsim::ToolVersion()};  ///< stitchsim version that wrote the report
};

/// Human summary for stdout: verdict, counts per rule, worst value and its line.
std::string ReportToText(const Report& report);
/// JSON, format in docs/report-format.md; keys in a fixed order, numbers in shortest
/// round-trip form, trailing newline.
std::string ReportToJson(const Report& report);
/// JUnit XML: <testsuites name="stitchsim"> holding one <testsuite> "stitchsim.<scene>", one
/// <testcase> per rule, a <failure> listing the
/// lines for rules with errors (warnings go to <system-out>).
std::string ReportToJunit(const Report& report);

}  // namespace stitchsim::verify
