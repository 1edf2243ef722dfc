#pragma once
// The verifier: a TraceSink that follows the stitch cycle (needle windows, penetrations) and
// runs every rule over the streamed trace. Memory does not grow with programme length
// (findings are capped per rule; counts stay exact).

#include <cstdint>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/afp_laid_material.h"
#include "stitchsim/verify/laydown.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {

namespace detail {
class LaidMaterialBuilder;  // verify/src/afp_laid_material_builder.h
}  // namespace detail

/// One stitch as the verifier saw it (for the overview snapshot).
struct StitchMark {
  Eigen::Vector3f position_mm =
      Eigen::Vector3f::Zero();  ///< tool point at needle entry, part frame
  std::uint8_t severity = 0;    ///< 0 clean, 1 warning, 2 error
  int line = 0;                 ///< programme line of the needle entry
};

class Verifier : public trace::TraceSink {
 public:
  /// What `ctx` points to must outlive the verifier (`ctx` itself is copied: a temporary is
  /// fine). With `keep_stitch_marks`, every stitch's position and worst severity is kept for
  /// the overview snapshot (13 bytes a stitch); with an AFP head, what the programme laid
  /// instead (Laid(); afp_laid_material.h gives its bytes).
  Verifier(const RuleContext& ctx, bool keep_stitch_marks);
  ~Verifier() override;
  /// Rules refer to the verifier's own copy of the context: it stays where it is.
  Verifier(const Verifier&) = delete;
  Verifier& operator=(const Verifier&) = delete;

  void OnLine(const trace::LineRecord& line) override;
  void OnSample(const trace::TraceSample& sample) override;

  /// Closes the trace and fills the report's rules, counts and verdict.
  void Finish(Report& report);

  const std::vector<std::unique_ptr<Rule>>& Rules() const { return rules_; }
  const std::vector<StitchMark>& StitchMarks() const { return marks_; }
  /// What the programme laid (afp_laid_material.h), complete after Finish; empty unless the
  /// verifier keeps stitch marks and the head is AFP.
  const LaidMaterial& Laid() const;

  // Chunked runs: a programme cut at lines where the needles are out (stitching off or the head
  // retracted) into parts, each verified by its own verifier, merged in programme order.

  /// Chunked runs: starts counting afresh after a warm-up (every rule's summary, findings,
  /// worst sample and extra counters to their initial values; the stitch count and marks'
  /// severities too); the state carried across lines (Carry()) stays. Throws
  /// std::logic_error when an afp.* rule saw something (see Rule::Mergeable).
  void ResetAccumulators();
  /// The state the verifier and its rules carry from one line to the next (needle window,
  /// kin.joint_speed's last sample, stitch.length's last penetration, ...), as bytes: two
  /// verifiers with equal Carry() give equal results on the same lines that follow. Line-local
  /// state counts only while its line is the last one seen. A verifier whose afp.* rules saw
  /// something carries bytes no other verifier's equal (those rules carry whole plies).
  std::string Carry() const;
  /// Folds `later` (a verifier over the part of the programme right after this one's) into
  /// this one: afterwards this verifier's Finish gives the report of one verifier over both
  /// parts (and its carry is later's; `later` may have lost rules to it). Throws
  /// std::logic_error for another rule set, for a rule that cannot be merged (the AFP rules,
  /// whose coverage judges a ply as a whole, when both parts saw something) or when this
  /// part ends with the needles in the preform; nothing has changed then.
  void Absorb(Verifier& later);
  /// Accumulated state (not the carry, no stitch marks, no TraceSample) as JSON and back
  /// (verify --shard writes it, report merge reads it into a fresh verifier of the same
  /// scene and programme, then Absorbs). SavePartial throws std::logic_error with the needles
  /// in the preform (CloseNeedleWindow first) or when an afp.* rule saw something.
  /// LoadPartial (into a fresh verifier) replaces the accumulated state; it returns false
  /// with `error` set for JSON that does not fit (other format or version, other rules or
  /// limits, other scene, malformed, or cut short: pass nlohmann::json::parse(text, nullptr,
  /// false)), and then resets the accumulators.
  nlohmann::json SavePartial() const;
  bool LoadPartial(const nlohmann::json& j, std::string& error);
  /// True once any rule has counted anything or any line/sample was seen since the last reset.
  bool SawAnything() const;
  /// Closes an open needle window as Finish does (a trace that ends with the needles in):
  /// for the last part of a programme before SavePartial.
  void CloseNeedleWindow() {
    if (window_.Active()) CloseWindow();
  }

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
  /// A line or sample was given since the last reset.
  bool saw_input_ = false;
  /// Tells this verifier's carry from any other's (see Carry, afp.* rules).
  std::uint64_t instance_;
  /// AFP heads: the laydown figures (report.laydown); null for a stitching head. Like the
  /// afp.* rules it judges the programme whole (AFP programmes are verified in one part).
  std::unique_ptr<LaydownMeter> laydown_;
  /// AFP heads with keep_stitch_marks: fills Laid(); null otherwise.
  std::unique_ptr<detail::LaidMaterialBuilder> laid_;
};

}  // namespace stitchsim::verify
