#pragma once
// The verifier: a TraceSink that follows the stitch cycle (needle windows, penetrations) and
// runs every rule over the streamed trace. Memory does not grow with programme length
// (findings are capped per rule; counts stay exact).

#include <memory>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {

/// One stitch as the verifier saw it (for the overview snapshot).
struct StitchMark {
  Eigen::Vector3f position_mm;  ///< tool point at needle entry, part frame
  std::uint8_t severity = 0;    ///< 0 clean, 1 warning, 2 error
};

class Verifier : public trace::TraceSink {
 public:
  /// What `ctx` points to must outlive the verifier (`ctx` itself is copied: a temporary is
  /// fine). With `keep_stitch_marks`, every stitch's position and worst severity is kept for
  /// the overview snapshot (13 bytes a stitch).
  Verifier(const RuleContext& ctx, bool keep_stitch_marks);
  /// Rules refer to the verifier's own copy of the context: it stays where it is.
  Verifier(const Verifier&) = delete;
  Verifier& operator=(const Verifier&) = delete;

  void OnLine(const trace::LineRecord& line) override;
  void OnSample(const trace::TraceSample& sample) override;

  /// Closes the trace and fills the report's rules, counts and verdict.
  void Finish(Report& report);

  const std::vector<std::unique_ptr<Rule>>& Rules() const { return rules_; }
  const std::vector<StitchMark>& StitchMarks() const { return marks_; }

 private:
  void CloseWindow();
  const Eigen::Isometry3d* WalkReference(const trace::TraceSample& s);
  void MarkStitch(long stitch, std::size_t errors_before, std::size_t warnings_before);

  RuleContext ctx_;
  std::vector<std::unique_ptr<Rule>> rules_;
  process::NeedleWindow window_;
  long window_stitch_ = 0;
  int window_entry_line_ = 0;
  trace::TraceSample last_in_sample_;
  bool keep_marks_ = false;
  std::vector<StitchMark> marks_;
  long stitches_ = 0;
  /// The current line's commanded poses (part frame, mm) and the last commanded pose made
  /// from them (dynamic runs: the needle walk follows the command, the needles the arm).
  Eigen::Isometry3d line_from_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d line_to_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d commanded_ = Eigen::Isometry3d::Identity();
};

}  // namespace stitchsim::verify
