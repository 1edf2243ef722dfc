#include "stitchsim/verify/rule.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace stitchsim::verify {

Rule::Rule(std::string id, std::string description, std::string unit) {
  summary_.id = std::move(id);
  summary_.description = std::move(description);
  summary_.unit = std::move(unit);
}

void Rule::SetWorstSample(const trace::TraceSample& sample) {
  worst_sample_ = sample;
  if (window_entry_ != nullptr) {
    worst_entry_tool_ = *window_entry_;
  } else {
    worst_entry_tool_.reset();
  }
}

void Rule::Observe(double value, int line, long stitch, const trace::TraceSample* sample) {
  series_.Add(line, value);
  if (!summary_.worst_value || value > *summary_.worst_value) {
    summary_.worst_value = value;
    summary_.worst_line = line;
    summary_.worst_stitch = stitch;
    if (sample != nullptr) SetWorstSample(*sample);
  }
}

bool Rule::Worse(FindingSeverity severity, double value, double limit, const Finding& than) {
  if (severity != than.severity) return severity == FindingSeverity::kError;
  if (limit > 0.0 && than.limit > 0.0) return value / limit > than.value / than.limit;
  return value > than.value;
}

Rule::LineFinding* Rule::RecentFinding(int line) {
  for (auto it = recent_lines_.rbegin(); it != recent_lines_.rend(); ++it) {
    if (it->line == line) return &*it;
  }
  return nullptr;
}

void Rule::Record(FindingSeverity severity, double value, double limit, int line, long stitch,
                  const std::string& subject, std::string message, const trace::TraceSample* sample,
                  const Eigen::Vector3d* position) {
  // One finding per line: find the line's finding, if it was reported already (kept or not).
  LineFinding* seen = RecentFinding(line);
  bool was_error = false;
  if (seen != nullptr) {
    was_error = seen->severity == FindingSeverity::kError;
    if (!was_error && severity == FindingSeverity::kError) {
      --summary_.warnings;
      ++summary_.errors;
      seen->severity = FindingSeverity::kError;
    }
  } else if (severity == FindingSeverity::kError) {
    ++summary_.errors;
  } else {
    ++summary_.warnings;
  }
  // The close-up goes to the first error (or a warning if there is no error).
  const bool first_error =
      severity == FindingSeverity::kError && !was_error && summary_.errors == 1;
  if (sample != nullptr && (first_error || !worst_sample_)) SetWorstSample(*sample);
  Finding f;
  f.rule = summary_.id;
  f.severity = severity;
  f.line = line;
  f.stitch = stitch;
  f.value = value;
  f.limit = limit;
  f.unit = summary_.unit;
  f.subject = subject;
  f.message = std::move(message);
  if (position != nullptr || sample != nullptr) {
    const Eigen::Vector3d& p = position != nullptr ? *position : sample->tool_part.translation();
    f.position_mm = std::array<double, 3>{p.x(), p.y(), p.z()};
  }
  if (seen != nullptr) {
    const std::size_t index = seen->index;
    if (index >= summary_.findings.size()) return;
    Finding& kept = summary_.findings[index];
    if (Worse(severity, value, limit, kept)) {
      if (!f.position_mm) f.position_mm = kept.position_mm;
      kept = std::move(f);
    } else if (!kept.position_mm) {
      kept.position_mm = f.position_mm;
    }
    return;
  }
  LineFinding entry{line, severity, static_cast<std::size_t>(-1)};
  if (summary_.findings.size() >= kMaxFindingsPerRule) {
    summary_.truncated = true;
  } else {
    entry.index = summary_.findings.size();
    summary_.findings.push_back(std::move(f));
  }
  recent_lines_.push_back(entry);
  if (recent_lines_.size() > kRecentFindingLines) recent_lines_.pop_front();
}

std::size_t Rule::AddSubject(std::string subject, std::optional<double> error_limit,
                             std::optional<double> warning_limit) {
  SubjectFigure figure;
  figure.subject = std::move(subject);
  figure.error_limit = error_limit;
  figure.warning_limit = warning_limit;
  summary_.subjects.push_back(std::move(figure));
  return summary_.subjects.size() - 1;
}

void Rule::ObserveSubject(std::size_t index, double value, int line, long stitch) {
  SubjectFigure& figure = summary_.subjects[index];
  ++figure.checked;
  if (!figure.worst_value || value > *figure.worst_value) {
    figure.worst_value = value;
    figure.worst_line = line;
    figure.worst_stitch = stitch;
  }
}

void Rule::ObserveSmallest(double value, int line, std::size_t index) {
  ++summary_.checked;
  if (!summary_.worst_value || value < *summary_.worst_value) {
    summary_.worst_value = value;
    summary_.worst_line = line;
  }
  SubjectFigure& figure = summary_.subjects[index];
  ++figure.checked;
  if (!figure.worst_value || value < *figure.worst_value) {
    figure.worst_value = value;
    figure.worst_line = line;
  }
}

std::optional<FindingSeverity> Rule::Classify(double value, int line, long stitch,
                                              const trace::TraceSample* sample) {
  ++summary_.checked;
  const bool new_worst = !summary_.worst_value || value > *summary_.worst_value;
  Observe(value, line, stitch, nullptr);
  std::optional<FindingSeverity> sev;
  if (summary_.error_limit && value > *summary_.error_limit) {
    sev = FindingSeverity::kError;
  } else if (summary_.warning_limit && value > *summary_.warning_limit) {
    sev = FindingSeverity::kWarning;
  }
  // Keep the snapshot at the worst offending sample.
  if (sample != nullptr && new_worst && (sev || !worst_sample_)) SetWorstSample(*sample);
  return sev;
}

void Rule::RecordExceeded(FindingSeverity severity, double value, int line, long stitch,
                          const std::string& subject, const std::string& what,
                          const trace::TraceSample* sample, const Eigen::Vector3d* position) {
  const double limit =
      severity == FindingSeverity::kError ? *summary_.error_limit : *summary_.warning_limit;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%s %.4g %s exceeds the %s limit of %.4g %s", what.c_str(), value,
                summary_.unit.c_str(), severity == FindingSeverity::kError ? "error" : "warning",
                limit, summary_.unit.c_str());
  // Classify already kept the snapshot sample at the worst value.
  Record(severity, value, limit, line, stitch, subject, buf, sample, position);
}

namespace {

// `later`'s worst replaces `worst` only when it is worse (first occurrence wins ties, as
// Observe does serially).
template <typename Figure>
void AbsorbWorst(Figure& figure, const Figure& later, bool smallest) {
  if (!later.worst_value) return;
  const double value = *later.worst_value;
  const bool worse =
      !figure.worst_value || (smallest ? value < *figure.worst_value : value > *figure.worst_value);
  if (!worse) return;
  figure.worst_value = later.worst_value;
  figure.worst_line = later.worst_line;
  figure.worst_stitch = later.worst_stitch;
}

template <typename Figure>
void ResetWorst(Figure& figure) {
  figure.checked = 0;
  figure.worst_value.reset();
  figure.worst_line = 0;
  figure.worst_stitch = 0;
}

}  // namespace

bool Rule::SawAnything() const {
  if (saw_input_ || summary_.checked > 0 || summary_.errors > 0 || summary_.warnings > 0 ||
      summary_.worst_value || !summary_.findings.empty())
    return true;
  return std::any_of(summary_.subjects.begin(), summary_.subjects.end(),
                     [](const SubjectFigure& f) { return f.checked > 0 || f.worst_value; });
}

void Rule::AbsorbSummary(const RuleSummary& later) {
  summary_.checked += later.checked;
  summary_.errors += later.errors;
  summary_.warnings += later.warnings;
  AbsorbWorst(summary_, later, worst_is_smallest_);
  for (std::size_t i = 0; i < summary_.subjects.size(); ++i) {
    summary_.subjects[i].checked += later.subjects[i].checked;
    AbsorbWorst(summary_.subjects[i], later.subjects[i], worst_is_smallest_);
  }
  // This part's findings, then later's: the first kMaxFindingsPerRule, as one rule keeps.
  for (const Finding& f : later.findings) {
    if (summary_.findings.size() >= kMaxFindingsPerRule) {
      summary_.truncated = true;
      break;
    }
    summary_.findings.push_back(f);
  }
  summary_.truncated = summary_.truncated || later.truncated;
}

void Rule::Absorb(const Rule& later) {
  if (later.summary_.id != summary_.id ||
      later.summary_.subjects.size() != summary_.subjects.size())
    throw std::logic_error("Rule::Absorb: rule " + later.summary_.id + " into " + summary_.id);
  if (!mergeable_) {
    if (!later.SawAnything()) return;
    throw std::logic_error(summary_.id +
                           " judges the programme as a whole and cannot be merged from parts");
  }
  const std::size_t before = summary_.findings.size();
  AbsorbSummary(later.summary_);
  // Later's lines follow this part's: its kept findings moved up by this part's count.
  for (LineFinding e : later.recent_lines_) {
    if (e.index != static_cast<std::size_t>(-1)) {
      e.index =
          before + e.index < kMaxFindingsPerRule ? before + e.index : static_cast<std::size_t>(-1);
    }
    recent_lines_.push_back(e);
    if (recent_lines_.size() > kRecentFindingLines) recent_lines_.pop_front();
  }
  // The close-up: the first error's, else a warning's.
  const bool has_error = summary_.errors - later.summary_.errors > 0;
  if (!has_error && later.worst_sample_ && (later.summary_.errors > 0 || !worst_sample_)) {
    worst_sample_ = later.worst_sample_;
    worst_entry_tool_ = later.worst_entry_tool_;
  }
  saw_input_ = saw_input_ || later.saw_input_;
  series_.Absorb(later.series_);
  AbsorbExtra(later);
}

void Rule::ResetAccumulators() {
  if (!mergeable_ && SawAnything()) {
    throw std::logic_error(summary_.id +
                           " judges the programme as a whole and cannot start afresh");
  }
  summary_.errors = 0;
  summary_.warnings = 0;
  ResetWorst(summary_);
  for (SubjectFigure& f : summary_.subjects) ResetWorst(f);
  summary_.findings.clear();
  summary_.truncated = false;
  worst_sample_.reset();
  worst_entry_tool_.reset();
  recent_lines_.clear();
  saw_input_ = false;
  series_.Clear();
  ResetExtra();
}

}  // namespace stitchsim::verify
