// Rules about the programme as a whole.
#include <nlohmann/json.hpp>
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

 protected:
  void AbsorbExtra(const Rule& later) override {
    const auto& l = dynamic_cast<const StitchCountRule&>(later);
    made_ += l.made_;
    if (l.last_line_ != 0) last_line_ = l.last_line_;
  }
  void ResetExtra() override {
    made_ = 0;
    last_line_ = 0;
  }
  void SaveExtra(nlohmann::json& extra) const override {
    extra["made"] = made_;
    extra["last_line"] = last_line_;
  }
  bool LoadExtra(const nlohmann::json& extra) override {
    const long made = extra.at("made").get<long>();
    last_line_ = extra.at("last_line").get<int>();
    made_ = made;
    return true;
  }

 private:
  long declared_;      ///< config
  long made_ = 0;      ///< accumulator: needle entries
  int last_line_ = 0;  ///< accumulator: the last line seen (0: none), where a finding goes
};

}  // namespace

std::unique_ptr<Rule> MakeStitchCountRule(const RuleContext& ctx) {
  return std::make_unique<StitchCountRule>(ctx);
}

}  // namespace stitchsim::verify
