// Rules about the programme as a whole.
#include <string>

#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

// A programme that declares how many stitches it makes must make exactly that many: a
// programme cut short (or edited) still parses, and every stitch it does make may pass.
class StitchCountRule final : public Rule {
 public:
  explicit StitchCountRule(const RuleContext& ctx)
      : Rule("program.stitch_count",
             "the programme makes as many stitches as its header declares (stitches=N)", ""),
        declared_(*ctx.declared_stitches) {
    summary_.error_limit = static_cast<double>(declared_);
  }
  void OnLine(const trace::LineRecord& line) override { last_line_ = line.source_line; }
  void OnSample(const trace::TraceSample& s) override {
    if (s.event == trace::SampleEvent::kNeedleEntry) ++made_;
  }
  void Finish(const RuleContext&) override {
    Counted();
    Observe(static_cast<double>(made_), last_line_, 0, nullptr);
    if (made_ == declared_) return;
    Record(FindingSeverity::kError, static_cast<double>(made_), static_cast<double>(declared_),
           last_line_, 0, "programme",
           "the header declares " + std::to_string(declared_) +
               " stitches but the programme makes " + std::to_string(made_) +
               " (cut short or edited?); the last motion is on this line",
           nullptr);
  }

 private:
  long declared_;
  long made_ = 0;
  int last_line_ = 0;
};

}  // namespace

std::unique_ptr<Rule> MakeStitchCountRule(const RuleContext& ctx) {
  return std::make_unique<StitchCountRule>(ctx);
}

}  // namespace stitchsim::verify
