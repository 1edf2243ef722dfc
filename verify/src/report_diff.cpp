// DiffReports (report_diff.h): findings matched per rule and subject, by position first, then
// (for findings without one) by stitch, line or order; docs/report-format.md, "Diff".

#include "stitchsim/verify/report_diff.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace stitchsim::verify {
namespace {

using Findings = std::vector<Finding>;

// One rule's findings in both reports and which old finding each new one is (-1: none).
struct RulePair {
  const RuleSummary* old_rule = nullptr;  ///< null when only the new report ran the rule
  const RuleSummary* new_rule = nullptr;  ///< null when only the old report ran the rule
  std::vector<int> new_of_old, old_of_new;
  std::vector<FindingMatch> match_of_new;  ///< how new finding j was matched
  const Findings& Old() const { return old_rule ? old_rule->findings : kNone; }
  const Findings& New() const { return new_rule ? new_rule->findings : kNone; }
  void Pair(int i, int j, FindingMatch how) {
    new_of_old[i] = j;
    old_of_new[j] = i;
    match_of_new[j] = how;
  }
  static const Findings kNone;
};
const Findings RulePair::kNone;

// (old, new) stitch or line numbers of findings matched by position: how far the programme's
// numbering moved there. Sorted by the old number.
class Shifts {
 public:
  void Add(long old_key, long new_key) { pairs_.emplace_back(old_key, new_key); }
  void Sort() { std::sort(pairs_.begin(), pairs_.end()); }
  bool Empty() const { return pairs_.empty(); }
  /// The shift at the nearest pair by old number (the earlier one on a tie); 0 when none.
  long At(long old_key) const {
    if (pairs_.empty()) return 0;
    auto it = std::lower_bound(pairs_.begin(), pairs_.end(), std::make_pair(old_key, LONG_MIN));
    if (it == pairs_.end()) --it;
    if (it != pairs_.begin() && old_key - std::prev(it)->first <= it->first - old_key) --it;
    return it->second - it->first;
  }

 private:
  std::vector<std::pair<long, long>> pairs_;
};

double Distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// Position matches of one rule: the closest pairs of one subject first (ties in finding order).
void MatchByPosition(RulePair& r, double tolerance_mm, Shifts& stitches, Shifts& lines) {
  const Findings &old = r.Old(), &neu = r.New();
  std::vector<std::tuple<double, int, int>> candidates;
  for (std::size_t i = 0; i < old.size(); ++i) {
    if (!old[i].position_mm) continue;
    for (std::size_t j = 0; j < neu.size(); ++j) {
      if (!neu[j].position_mm || neu[j].subject != old[i].subject) continue;
      const double d = Distance(*old[i].position_mm, *neu[j].position_mm);
      if (d <= tolerance_mm) candidates.emplace_back(d, int(i), int(j));
    }
  }
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [d, i, j] : candidates) {
    if (r.new_of_old[i] >= 0 || r.old_of_new[j] >= 0) continue;
    r.Pair(i, j, FindingMatch::kPosition);
    if (old[i].stitch > 0 && neu[j].stitch > 0) stitches.Add(old[i].stitch, neu[j].stitch);
    if (old[i].line > 0 && neu[j].line > 0) lines.Add(old[i].line, neu[j].line);
  }
}

// Which fallback a finding without a position is matched by.
FindingMatch FallbackOf(const Finding& f, bool line_shifts_known) {
  if (f.position_mm) return FindingMatch::kNone;
  if (f.stitch > 0) return FindingMatch::kStitch;
  if (f.line > 0 && line_shifts_known) return FindingMatch::kLine;
  return FindingMatch::kOrder;
}

// Findings without a position on either side: by stitch or line number shifted as at the
// nearest position match, else the k-th of a subject with the k-th.
void MatchWithoutPosition(RulePair& r, const Shifts& stitches, const Shifts& lines) {
  const Findings &old = r.Old(), &neu = r.New();
  // (how, subject, key) -> the unmatched new findings of that key, in order.
  std::map<std::tuple<FindingMatch, std::string, long>, std::vector<int>> open;
  std::map<std::string, long> order_seen;
  for (std::size_t j = 0; j < neu.size(); ++j) {
    const FindingMatch how = FallbackOf(neu[j], !lines.Empty());
    if (how == FindingMatch::kNone || r.old_of_new[j] >= 0) continue;
    const long key = how == FindingMatch::kStitch ? neu[j].stitch
                     : how == FindingMatch::kLine ? neu[j].line
                                                  : order_seen[neu[j].subject]++;
    open[{how, neu[j].subject, key}].push_back(int(j));
  }
  std::map<std::string, long> order_old;
  for (std::size_t i = 0; i < old.size(); ++i) {
    const FindingMatch how = FallbackOf(old[i], !lines.Empty());
    if (how == FindingMatch::kNone || r.new_of_old[i] >= 0) continue;
    const long key = how == FindingMatch::kStitch ? old[i].stitch + stitches.At(old[i].stitch)
                     : how == FindingMatch::kLine ? old[i].line + lines.At(old[i].line)
                                                  : order_old[old[i].subject]++;
    auto it = open.find({how, old[i].subject, key});
    if (it == open.end() || it->second.empty()) continue;
    r.Pair(int(i), it->second.front(), how);
    it->second.erase(it->second.begin());
  }
}

bool Changed(const Finding& old, const Finding& neu, double value_tolerance_pct) {
  if (old.severity != neu.severity) return true;
  return std::abs(neu.value - old.value) > value_tolerance_pct / 100.0 * std::abs(old.value);
}

// The index of the last matched finding of a side (-1: none): a truncated report's findings
// past it are not compared.
int LastMatched(const std::vector<int>& partner) {
  for (int k = int(partner.size()) - 1; k >= 0; --k) {
    if (partner[k] >= 0) return k;
  }
  return -1;
}

RuleCountDiff Counts(const RulePair& r) {
  RuleCountDiff c;
  c.id = r.new_rule ? r.new_rule->id : r.old_rule->id;
  if (r.old_rule) {
    c.in_old = true;
    c.old_errors = r.old_rule->errors;
    c.old_warnings = r.old_rule->warnings;
    c.old_truncated = r.old_rule->truncated;
  }
  if (r.new_rule) {
    c.in_new = true;
    c.new_errors = r.new_rule->errors;
    c.new_warnings = r.new_rule->warnings;
    c.new_truncated = r.new_rule->truncated;
  }
  return c;
}

// One rule's appeared, disappeared and changed findings, in the new report's order (each
// disappeared one after the new finding matched to the last matched old one before it).
void EmitRule(const RulePair& r, const DiffOptions& options, RuleCountDiff& counts,
              std::vector<FindingDiff>& out) {
  const Findings &old = r.Old(), &neu = r.New();
  const int old_last = LastMatched(r.new_of_old), new_last = LastMatched(r.old_of_new);
  // ((new index, 0 = new-side entry / 1 = disappeared, old index), entry)
  std::vector<std::pair<std::tuple<int, int, int>, FindingDiff>> entries;
  for (std::size_t j = 0; j < neu.size(); ++j) {
    const int i = r.old_of_new[j];
    FindingDiff d;
    d.new_finding = neu[j];
    if (i < 0) {
      if (counts.old_truncated && int(j) > new_last) {
        ++counts.new_past_cap;
        continue;
      }
      d.change = FindingChange::kAppeared;
    } else {
      if (!Changed(old[i], neu[j], options.value_tolerance_pct)) continue;
      d.change = FindingChange::kChanged;
      d.match = r.match_of_new[j];
      d.old_finding = old[i];
    }
    entries.emplace_back(std::make_tuple(int(j), 0, 0), std::move(d));
  }
  int after = -1;  // the new finding matched to the last matched old one so far
  for (std::size_t i = 0; i < old.size(); ++i) {
    if (r.new_of_old[i] >= 0) {
      after = std::max(after, r.new_of_old[i]);
      continue;
    }
    if (counts.new_truncated && int(i) > old_last) {
      ++counts.old_past_cap;
      continue;
    }
    FindingDiff d;
    d.change = FindingChange::kDisappeared;
    d.old_finding = old[i];
    entries.emplace_back(std::make_tuple(after, 1, int(i)), std::move(d));
  }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& e : entries) out.push_back(std::move(e.second));
}

DiffSide SideOf(const Report& r) {
  return {r.program_file, r.verdict,  r.lines,        r.stitches,
          r.errors,       r.warnings, r.cycle_time_s, r.cycle_time_timed_s};
}

// The rules of both reports, the new report's order first.
std::vector<RulePair> PairRules(const Report& old, const Report& neu) {
  std::vector<RulePair> pairs;
  std::vector<bool> taken(old.rules.size(), false);
  for (const RuleSummary& rule : neu.rules) {
    RulePair p;
    p.new_rule = &rule;
    for (std::size_t k = 0; k < old.rules.size(); ++k) {
      if (!taken[k] && old.rules[k].id == rule.id) {
        p.old_rule = &old.rules[k];
        taken[k] = true;
        break;
      }
    }
    pairs.push_back(p);
  }
  for (std::size_t k = 0; k < old.rules.size(); ++k) {
    if (taken[k]) continue;
    RulePair p;
    p.old_rule = &old.rules[k];
    pairs.push_back(p);
  }
  for (RulePair& p : pairs) {
    p.new_of_old.assign(p.Old().size(), -1);
    p.old_of_new.assign(p.New().size(), -1);
    p.match_of_new.assign(p.New().size(), FindingMatch::kNone);
  }
  return pairs;
}

}  // namespace

ReportDiff DiffReports(const Report& old, const Report& neu, const DiffOptions& options) {
  ReportDiff diff;
  diff.scene_file = neu.scene_file;
  diff.scene_name = neu.scene_name;
  diff.head = neu.head;
  diff.options = options;
  diff.old_side = SideOf(old);
  diff.new_side = SideOf(neu);
  std::vector<RulePair> pairs = PairRules(old, neu);
  // Position matches of every rule first: they say how stitch and line numbers moved.
  Shifts stitches, lines;
  for (RulePair& p : pairs) MatchByPosition(p, options.position_tolerance_mm, stitches, lines);
  stitches.Sort();
  lines.Sort();
  for (RulePair& p : pairs) {
    MatchWithoutPosition(p, stitches, lines);
    RuleCountDiff counts = Counts(p);
    EmitRule(p, options, counts, diff.findings);
    if (counts.Truncated() && counts.new_errors > counts.old_errors) diff.new_errors = true;
    diff.rules.push_back(std::move(counts));
  }
  for (const FindingDiff& d : diff.findings) {
    switch (d.change) {
      case FindingChange::kAppeared:
        ++diff.appeared;
        if (d.new_finding->severity == FindingSeverity::kError) diff.new_errors = true;
        break;
      case FindingChange::kDisappeared:
        ++diff.disappeared;
        break;
      case FindingChange::kChanged:
        ++diff.changed;
        if (d.new_finding->severity == FindingSeverity::kError &&
            d.old_finding->severity == FindingSeverity::kWarning) {
          diff.new_errors = true;
        }
        break;
    }
  }
  return diff;
}

}  // namespace stitchsim::verify
