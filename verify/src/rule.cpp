#include "stitchsim/verify/rule.h"

#include <cmath>
#include <cstdio>

namespace stitchsim::verify {

Rule::Rule(std::string id, std::string description, std::string unit) {
  summary_.id = std::move(id);
  summary_.description = std::move(description);
  summary_.unit = std::move(unit);
}

void Rule::Observe(double value, int line, long stitch, const trace::TraceSample* sample) {
  if (!summary_.worst_value || value > *summary_.worst_value) {
    summary_.worst_value = value;
    summary_.worst_line = line;
    summary_.worst_stitch = stitch;
    if (sample != nullptr) worst_sample_ = *sample;
  }
}

bool Rule::Worse(FindingSeverity severity, double value, double limit, const Finding& than) {
  if (severity != than.severity) return severity == FindingSeverity::kError;
  if (limit > 0.0 && than.limit > 0.0) return value / limit > than.value / than.limit;
  return value > than.value;
}

void Rule::Record(FindingSeverity severity, double value, double limit, int line, long stitch,
                  const std::string& subject, std::string message,
                  const trace::TraceSample* sample) {
  // One finding per line: find the line's finding, if it was reported already.
  std::size_t index = static_cast<std::size_t>(-1);
  bool seen = false;
  if (line == last_finding_line_) {
    seen = true;
    index = last_finding_index_;
  } else if (const auto it = kept_by_line_.find(line); it != kept_by_line_.end()) {
    seen = true;
    index = it->second;
  }
  bool was_error = false;
  if (seen) {
    const FindingSeverity before = index < summary_.findings.size()
                                       ? summary_.findings[index].severity
                                       : last_finding_severity_;
    was_error = before == FindingSeverity::kError;
    if (!was_error && severity == FindingSeverity::kError) {
      --summary_.warnings;
      ++summary_.errors;
    }
  } else if (severity == FindingSeverity::kError) {
    ++summary_.errors;
  } else {
    ++summary_.warnings;
  }
  last_finding_line_ = line;
  last_finding_severity_ = was_error ? FindingSeverity::kError : severity;
  // The close-up goes to the first error (or a warning if there is no error).
  const bool first_error =
      severity == FindingSeverity::kError && !was_error && summary_.errors == 1;
  if (sample != nullptr && (first_error || !worst_sample_)) worst_sample_ = *sample;
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
  if (seen) {
    last_finding_index_ = index;
    if (index < summary_.findings.size() && Worse(severity, value, limit, summary_.findings[index]))
      summary_.findings[index] = std::move(f);
    return;
  }
  if (summary_.findings.size() >= kMaxFindingsPerRule) {
    summary_.truncated = true;
    last_finding_index_ = static_cast<std::size_t>(-1);
    return;
  }
  last_finding_index_ = summary_.findings.size();
  kept_by_line_.emplace(line, last_finding_index_);
  summary_.findings.push_back(std::move(f));
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
  if (sample != nullptr && new_worst && (sev || !worst_sample_)) worst_sample_ = *sample;
  return sev;
}

void Rule::RecordExceeded(FindingSeverity severity, double value, int line, long stitch,
                          const std::string& subject, const std::string& what,
                          const trace::TraceSample* sample) {
  const double limit =
      severity == FindingSeverity::kError ? *summary_.error_limit : *summary_.warning_limit;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%s %.4g %s exceeds the %s limit of %.4g %s", what.c_str(), value,
                summary_.unit.c_str(), severity == FindingSeverity::kError ? "error" : "warning",
                limit, summary_.unit.c_str());
  // Classify already kept the snapshot sample at the worst value.
  Record(severity, value, limit, line, stitch, subject, buf, sample);
}

}  // namespace stitchsim::verify
