#pragma once
// The extension point of the verifier: a Rule has an id, limits from the head/scene spec,
// and checks over the trace. Adding a rule = one new class and its registry entry in its own
// file + one line in the registry (verify/src/rules.cpp; rule_registry.h).

#include <Eigen/Geometry>
#include <deque>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/value_series.h"

namespace stitchsim::verify {

namespace detail {
struct RuleMaking;  // what the factories of one MakeRules call share (detail/rule_registry.h)
}  // namespace detail

/// A closed needle window: the needles went in and came out again.
struct WindowRecord {
  long stitch = 0;
  int entry_line = 0;  ///< line where the needles entered
  int exit_line = 0;   ///< line where they left
  process::WindowMetrics metrics;
  trace::TraceSample exit_sample;  ///< the last sample of the window (for snapshots)
  /// Tool pose where the needles entered (part frame, mm; for the snapshot's drift arrows).
  Eigen::Isometry3d entry_tool = Eigen::Isometry3d::Identity();
};

/// The needles pierce the preform: where, and how the head stood.
struct PenetrationRecord {
  long stitch = 0;
  int line = 0;
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< part frame, mm
  std::vector<std::optional<Eigen::Vector3d>> points;      ///< per needle, on the surface
  geom::SurfaceProjection foot;  ///< the tool point projected on the stitching surface
  trace::TraceSample sample;
};

/// What rules may read besides the trace. Rules keep pointers to these, not to the context.
struct RuleContext {
  const scene::Scene* scene = nullptr;
  /// The trace producer's description of the cell (joint limits, speeds, names, the collision
  /// body table); the collision.* rules run only when its collision_checked is set.
  const trace::CellDescription* cell = nullptr;
  const process::ProcessModel* process = nullptr;
  /// The stitch count the programme's header declares (`stitches=N`), if it declares one:
  /// program.stitch_count checks the run makes exactly that many.
  std::optional<long> declared_stitches = std::nullopt;
  /// The controller's acceleration ramp (the dialect's `trajectory.ramp_time_s`, docs/timing.md),
  /// s: the laydown figures' ramps (verify/laydown.h). The time law's default when not given.
  double ramp_time_s = 0.25;
};

/// What a rule's close-up snapshot frames (docs/report-format.md, "Snapshots"; run/close_up.h
/// plans one per family). Declared by the rule's registry entry (rule_registry.h).
enum class CloseUpFamily {
  kNone,        ///< no close-up (program.*, afp.coverage, afp.gap, afp.overlap)
  kCollision,   ///< the two bodies in contact
  kNeedle,      ///< the needles, the drift of their shafts
  kStitch,      ///< the needles, the preform as a section
  kKinematics,  ///< the whole arm, the finding's joint's link
  kConstraint,  ///< from above, the constraint and its crossings
  kAfp,         ///< the head from the side of the roller
};
/// The family's name in snapshots.json ("collision", "needle", ...); "" for kNone.
const char* CloseUpFamilyName(CloseUpFamily family);

/// Points a rule asks the overview snapshot to draw, by label ("afp_laid", "afp_gap", ...),
/// part frame, mm; bounded (thinned evenly) by the rule. A label starting with
/// kCloseUpOnlyLabel ("close_up:afp_roller", ...) is for the rule's close-up only (its worst
/// finding's few points: run/src/close_up_afp.cpp); the overview leaves it out.
struct DrawnPoints {
  std::string label;
  std::vector<Eigen::Vector3d> points_mm;
};
inline constexpr const char* kCloseUpOnlyLabel = "close_up:";
/// True when `d` is for the rule's close-up only (its label starts with kCloseUpOnlyLabel).
inline bool CloseUpOnly(const DrawnPoints& d) { return d.label.rfind(kCloseUpOnlyLabel, 0) == 0; }

class Rule {
 public:
  virtual ~Rule() = default;
  virtual void OnLine(const trace::LineRecord&) {}
  virtual void OnSample(const trace::TraceSample&) {}
  virtual void OnWindow(const WindowRecord&) {}
  virtual void OnPenetration(const PenetrationRecord&) {}
  virtual void Finish(const RuleContext&) {}

  /// What the rule draws on the overview snapshot (most rules: nothing).
  virtual std::vector<DrawnPoints> Drawings() const { return {}; }
  /// After Finish: the rule's own laydown figures (afp.compaction: the stack thickness;
  /// afp.fiber_angle: the worst deviation) into `figures` (per ply, then the whole, ply 0),
  /// for the report's laydown section. Most rules add nothing.
  virtual void AddLaydownFigures(std::vector<LaydownFigures>& /*figures*/) const {}

  const RuleSummary& Summary() const { return summary_; }
  /// The trace sample at the worst finding, for the close-up snapshot.
  const std::optional<trace::TraceSample>& WorstSample() const { return worst_sample_; }
  /// For a worst sample inside a needle window (needle.* rules): the tool pose where the
  /// needles entered the preform in that window (part frame, mm); else empty.
  const std::optional<Eigen::Isometry3d>& WorstEntryTool() const { return worst_entry_tool_; }
  /// The values the rule checked along the programme (its unit, against its own limits), for
  /// plots; an accumulator (merged, reset, saved with the partial).
  const ValueSeries& Series() const { return series_; }
  /// The series' values must stay above the limits (collision.clearance, afp.steering_radius).
  bool LowerBound() const { return worst_is_smallest_; }
  /// What the rule's close-up snapshot frames (its registry entry's; kNone for a rule not
  /// made by MakeRules).
  CloseUpFamily CloseUp() const { return close_up_; }

  // Chunked runs (Verifier::Absorb, ResetAccumulators, Carry, SavePartial). A rule's state is
  // config (limits, from the context), accumulators (the summary, its findings, the worst
  // sample and the rule's own counters: merged) and carry (what one line hands the next:
  // SaveCarry).

  /// Folds `later` (the same rule over the part right after this one's) into this one: the
  /// summary and the base bookkeeping generically, then AbsorbExtra; the carry becomes
  /// later's. Throws std::logic_error for another rule, or for a rule that judges the
  /// programme as a whole (!Mergeable()) when `later` saw anything (Verifier::Absorb takes
  /// such a rule over whole when only `later` saw something).
  void Absorb(const Rule& later);
  /// Every accumulator to its initial value (then ResetExtra); the carry stays. Throws
  /// std::logic_error for a rule that is not Mergeable() and saw something.
  void ResetAccumulators();
  /// Appends the state the rule carries from one line to the next, as bytes.
  virtual void SaveCarry(std::string& /*out*/) const {}
  /// The accumulators (not the carry, not the worst sample) as JSON, and back (replacing
  /// them). LoadPartial returns false with `error` set when `j` is not this rule's (id, unit,
  /// limits, subjects) or is malformed; nothing changes then. SavePartial throws
  /// std::logic_error for a rule that is not Mergeable() and saw something.
  nlohmann::json SavePartial() const;
  bool LoadPartial(const nlohmann::json& j, std::string& error);
  /// True once the rule counted anything or was given a line or sample since the last reset.
  bool SawAnything() const;
  /// False for a rule that judges the programme as a whole (the afp.* rules: coverage and
  /// course edges are judged over a ply): it cannot be split into parts.
  bool Mergeable() const { return mergeable_; }

 protected:
  Rule(std::string id, std::string description, std::string unit);
  /// The rule's own accumulators (`later` is the same rule type): merge them; take over
  /// later's carry.
  virtual void AbsorbExtra(const Rule& /*later*/) {}
  /// The rule's own accumulators to their initial values (not the carry).
  virtual void ResetExtra() {}
  /// The rule's own accumulators into `extra` (an object), and back; false if malformed
  /// (then nothing changes).
  virtual void SaveExtra(nlohmann::json& /*extra*/) const {}
  virtual bool LoadExtra(const nlohmann::json& /*extra*/) { return true; }
  /// Counts one checked item and records a finding when `value` exceeds a limit
  /// (upper-bound check). `what()` names the measured quantity; it is only called for a
  /// finding, so the hot path formats nothing. Returns the severity recorded, if any.
  /// `position` (part frame, mm; may be null): where the value was measured, for a finding
  /// made without a sample (afp.gap's edge point); else the sample's tool point.
  template <typename WhatFn>
  std::optional<FindingSeverity> CheckUpper(double value, int line, long stitch,
                                            const std::string& subject, WhatFn&& what,
                                            const trace::TraceSample* sample,
                                            const Eigen::Vector3d* position = nullptr) {
    const std::optional<FindingSeverity> sev = Classify(value, line, stitch, sample);
    if (sev) RecordExceeded(*sev, value, line, stitch, subject, what(), sample, position);
    return sev;
  }
  void Counted() { ++summary_.checked; }
  /// The counting / worst-tracking half of CheckUpper: the severity `value` deserves.
  std::optional<FindingSeverity> Classify(double value, int line, long stitch,
                                          const trace::TraceSample* sample);
  void RecordExceeded(FindingSeverity severity, double value, int line, long stitch,
                      const std::string& subject, const std::string& what,
                      const trace::TraceSample* sample, const Eigen::Vector3d* position = nullptr);
  /// Records a finding directly (for yes/no rules). Findings are one per line: a second
  /// finding on a line already reported merges into it (the worse one's value, subject and
  /// message stay; error beats warning, then the larger value over its limit).
  /// The finding's position_mm is `position` (part frame, mm) when given, else the sample's tool
  /// point; a line's finding kept from an earlier record takes the later one's position when it
  /// had none.
  void Record(FindingSeverity severity, double value, double limit, int line, long stitch,
              const std::string& subject, std::string message, const trace::TraceSample* sample,
              const Eigen::Vector3d* position = nullptr);
  /// Adds a value to the plotted series only (rules that track their worst themselves).
  void Plot(int line, double value) { series_.Add(line, value); }
  /// Tracks the worst value without a finding (and plots it).
  void Observe(double value, int line, long stitch, const trace::TraceSample* sample);
  /// Counts one item of subject `index` and tracks the smallest value, the rule's and the
  /// subject's (a lower-bound rule that records its own findings, e.g. afp.steering_radius).
  void ObserveSmallest(double value, int line, std::size_t index);
  /// Adds a subject with its own limits (RuleSummary::subjects); returns its index.
  std::size_t AddSubject(std::string subject, std::optional<double> error_limit,
                         std::optional<double> warning_limit);
  /// Counts one item of subject `index` and tracks its worst value (not the rule's).
  void ObserveSubject(std::size_t index, double value, int line, long stitch);

  RuleSummary summary_;
  std::optional<trace::TraceSample> worst_sample_;
  ValueSeries series_;
  /// The worst value is the smallest (a lower-bound rule that tracks its worst itself, e.g.
  /// collision.clearance): merging keeps the smaller.
  bool worst_is_smallest_ = false;
  /// Cleared by a rule that judges the programme as a whole (see Mergeable).
  bool mergeable_ = true;

 private:
  friend class Verifier;  // marks saw_input_
  // Sets close_up_ from the rule's registry entry.
  friend std::vector<std::unique_ptr<Rule>> MakeRules(const RuleContext& ctx,
                                                      detail::RuleMaking& making);

  /// A line that had a finding: its severity so far and the finding's index (npos when the
  /// finding was not kept, past kMaxFindingsPerRule).
  struct LineFinding {
    int line = 0;
    FindingSeverity severity = FindingSeverity::kWarning;
    std::size_t index = static_cast<std::size_t>(-1);
  };
  /// worst_sample_ = `sample`, with the entry pose of the window being judged (if any).
  void SetWorstSample(const trace::TraceSample& sample);

  /// Lines recorded this many distinct lines ago or fewer are one finding with a new one.
  static constexpr std::size_t kRecentFindingLines = 64;

  /// Severity first, then value over limit (value alone when there is no positive limit).
  static bool Worse(FindingSeverity severity, double value, double limit, const Finding& than);
  LineFinding* RecentFinding(int line);
  void AbsorbSummary(const RuleSummary& later);

  /// The last kRecentFindingLines lines that had a finding, oldest first, kept or not: the
  /// one-finding-per-line merge looks here, so it does not depend on the findings cap (a line
  /// reported again after another line counts once, before and after the cap alike, and the
  /// counts of a programme verified in parts add up to the whole's).
  std::deque<LineFinding> recent_lines_;
  /// Given a line or sample since the last reset (set by the verifier).
  bool saw_input_ = false;
  /// Set by the verifier while OnWindow runs: the window's entry tool pose (part frame, mm).
  const Eigen::Isometry3d* window_entry_ = nullptr;
  std::optional<Eigen::Isometry3d> worst_entry_tool_;  ///< see WorstEntryTool
  CloseUpFamily close_up_ = CloseUpFamily::kNone;      ///< config: see CloseUp
};

/// Every rule that runs in `ctx` (rule_registry.h: RulePresence::kRuns), in report order, with
/// limits from `ctx`.
std::vector<std::unique_ptr<Rule>> MakeRules(const RuleContext& ctx);
/// The same, the factories sharing `making` (detail/rule_registry.h: the afp.* rules' one
/// sampler, which the verifier reads too).
std::vector<std::unique_ptr<Rule>> MakeRules(const RuleContext& ctx, detail::RuleMaking& making);
/// The rules MakeRules leaves out on purpose (RulePresence::kSkipped: no collision world, no
/// timed trajectory, no payload data), in registry order, with the reason.
std::vector<SkippedRule> SkippedRules(const RuleContext& ctx);

}  // namespace stitchsim::verify
