#pragma once
// The verifier: a TraceSink that follows the stitch cycle (needle windows, penetrations) and
// runs every rule over the streamed trace. Memory does not grow with programme length
// (findings are capped per rule; counts stay exact).

#include <memory>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/sim/trace.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {

/// One stitch as the verifier saw it (for the overview snapshot).
struct StitchMark {
  Eigen::Vector3f position_mm;  ///< tool point at needle entry, part frame
  std::uint8_t severity = 0;    ///< 0 clean, 1 warning, 2 error
};

class Verifier : public sim::TraceSink {
 public:
  /// `ctx` members must outlive the verifier. With `keep_stitch_marks`, every stitch's
  /// position and worst severity is kept for the overview snapshot (13 bytes a stitch).
  Verifier(const RuleContext& ctx, bool keep_stitch_marks);

  void OnLine(const sim::LineRecord& line) override;
  void OnSample(const sim::TraceSample& sample) override;

  /// Closes the trace and fills the report's rules, counts and verdict.
  void Finish(Report& report);

  const std::vector<std::unique_ptr<Rule>>& Rules() const { return rules_; }
  const std::vector<StitchMark>& StitchMarks() const { return marks_; }

 private:
  void CloseWindow();
  void MarkStitch(long stitch, std::size_t errors_before, std::size_t warnings_before);

  RuleContext ctx_;
  std::vector<std::unique_ptr<Rule>> rules_;
  process::NeedleWindow window_;
  long window_stitch_ = 0;
  int window_entry_line_ = 0;
  sim::TraceSample last_in_sample_;
  bool keep_marks_ = false;
  std::vector<StitchMark> marks_;
  long stitches_ = 0;
};

}  // namespace stitchsim::verify
