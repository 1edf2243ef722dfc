#pragma once
// Two reports of one scene compared (`stitchsim diff OLD NEW`): the findings that appeared,
// disappeared or changed, matched by where they are on the path rather than by line number
// (lines shift when a programme is edited), per-rule counts, verdict, cycle time and stitch
// count. Pure: reports in, a ReportDiff out; written as text, JSON and JUnit
// (docs/report-format.md, "Diff").

#include <optional>
#include <string>
#include <vector>

#include "stitchsim/verify/report.h"

namespace stitchsim::verify {

struct DiffOptions {
  /// Findings of one rule and subject whose positions (tool point, part frame) are at most
  /// this far apart are one finding, mm.
  double position_tolerance_mm = 0.5;
  /// A matched finding whose value moved by more than this fraction of the old value, in
  /// percent, is reported as changed.
  double value_tolerance_pct = 1.0;
};

enum class FindingChange { kAppeared, kDisappeared, kChanged };

/// How an old and a new finding were found to be the same one.
enum class FindingMatch {
  kNone,      ///< not matched (appeared or disappeared)
  kPosition,  ///< both positions within DiffOptions::position_tolerance_mm
  kStitch,    ///< no positions: the stitch number, shifted as the nearest position match's
  kLine,      ///< no positions or stitches: the line, shifted as the nearest position match's
  kOrder,     ///< none of those: the k-th of its rule and subject in both reports
};

/// One finding that appeared (new only), disappeared (old only) or changed (matched, severity
/// or value changed).
struct FindingDiff {
  FindingChange change = FindingChange::kAppeared;
  FindingMatch match = FindingMatch::kNone;
  std::optional<Finding> old_finding;  ///< as in the old report; absent when appeared
  std::optional<Finding> new_finding;  ///< as in the new report; absent when disappeared
  /// The finding of the new report if there is one, else the old one's.
  const Finding& Either() const { return new_finding ? *new_finding : *old_finding; }
};

/// One rule's counts in both reports (a rule only one report ran has zeros in the other).
struct RuleCountDiff {
  std::string id;
  bool in_old = false, in_new = false;  ///< the rule ran in that report
  long old_errors = 0, new_errors = 0;  ///< all error findings (past the findings cap too)
  long old_warnings = 0, new_warnings = 0;
  /// The report kept only the first kMaxFindingsPerRule findings of this rule: findings past
  /// the last one both reports kept are not compared one by one, the counts are.
  bool old_truncated = false, new_truncated = false;
  /// Unmatched findings left out of appeared / disappeared because they lie past the last
  /// finding the other (truncated) report kept.
  long old_past_cap = 0, new_past_cap = 0;
  bool Truncated() const { return old_truncated || new_truncated; }
  bool CountsChanged() const {
    return old_errors != new_errors || old_warnings != new_warnings || in_old != in_new;
  }
};

/// The figures of one report the diff shows beside the other's.
struct DiffSide {
  std::string program_file;  ///< as given on the command line
  std::string verdict;       ///< "pass" or "fail"
  long lines = 0;            ///< programme lines read
  long stitches = 0;         ///< stitch cycles executed
  long errors = 0, warnings = 0;
  double cycle_time_s = 0.0;        ///< at the programmed speeds, s
  double cycle_time_timed_s = 0.0;  ///< on the controller's time law, s; 0 when not timed
};

struct ReportDiff {
  std::string scene_file, scene_name, head;  ///< the new report's
  DiffOptions options;
  DiffSide old_side, new_side;
  /// Appeared, disappeared and changed findings, by rule in the new report's rule order
  /// (rules only the old report ran after), each rule's in the new report's finding order,
  /// disappeared ones after the new finding they followed.
  std::vector<FindingDiff> findings;
  std::vector<RuleCountDiff> rules;  ///< every rule of either report, in the same order
  long appeared = 0, disappeared = 0, changed = 0;
  /// The new programme has an error the old one did not: an error finding appeared, a
  /// finding changed from warning to error, or a truncated rule's error count grew.
  bool new_errors = false;
};

/// Compares `old` and `neu`, reports of two programmes on one scene (see DiffOptions and
/// FindingMatch for how findings are matched).
ReportDiff DiffReports(const Report& old, const Report& neu, const DiffOptions& options);

/// Text for stdout: a headline, one line per finding (rule, severity, new line / old line,
/// stitch, position, value, limit), then the rules whose counts changed or were truncated.
std::string ReportDiffToText(const ReportDiff& diff);
/// JSON, format in docs/report-format.md ("Diff"); keys in a fixed order, trailing newline.
std::string ReportDiffToJson(const ReportDiff& diff);
/// JUnit XML: <testsuite name="stitchsim.diff">, one <testcase> per rule, a <failure> listing
/// the errors the new programme has that the old one did not.
std::string ReportDiffToJunit(const ReportDiff& diff);

}  // namespace stitchsim::verify
