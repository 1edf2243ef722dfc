// program.line_sampling: a line the executor cannot sample within the documented bound
// (limits::kMaxSamplesPerLine) is a finding on that line; nothing else about it is checked.
#include <cstdio>
#include <memory>
#include <string>

#include "detail/rule_registry.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

class LineSamplingRule final : public Rule {
 public:
  LineSamplingRule()
      : Rule("program.line_sampling",
             "every motion line can be sampled within the executor's bound (docs/limits.md)",
             "samples") {
    summary_.error_limit = limits::kMaxSamplesPerLine;
  }
  void OnLine(const trace::LineRecord& l) override {
    Counted();
    Observe(l.samples_needed, l.source_line, 0, nullptr);
    if (!l.over_sample_limit) return;
    char buf[200];
    std::snprintf(buf, sizeof(buf),
                  "the line needs %.4g trace samples, more than the %.4g one line may take; "
                  "it was not checked (split it into shorter lines)",
                  l.samples_needed, limits::kMaxSamplesPerLine);
    Record(FindingSeverity::kError, l.samples_needed, limits::kMaxSamplesPerLine, l.source_line, 0,
           "line " + std::to_string(l.source_line), buf, nullptr);
  }
};

}  // namespace

RuleEntry LineSamplingRuleEntry() {
  return {"program.line_sampling", CloseUpFamily::kNone, detail::RunsAlways,
          detail::Make<LineSamplingRule>};
}

}  // namespace stitchsim::verify
