#pragma once
// The extension point of the verifier: a Rule has an id, limits from the head/scene spec,
// and checks over the trace. Adding a rule = one new class + one line in MakeRules.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::verify {

/// A closed needle window: the needles went in and came out again.
struct WindowRecord {
  long stitch = 0;
  int entry_line = 0;  ///< line where the needles entered
  int exit_line = 0;   ///< line where they left
  process::WindowMetrics metrics;
  trace::TraceSample exit_sample;  ///< the last sample of the window (for snapshots)
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
};

/// Points a rule asks the overview snapshot to draw, by label ("afp_laid", "afp_gap", ...),
/// part frame, mm; bounded (thinned evenly) by the rule.
struct DrawnPoints {
  std::string label;
  std::vector<Eigen::Vector3d> points_mm;
};

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

  const RuleSummary& Summary() const { return summary_; }
  /// The trace sample at the worst finding, for the close-up snapshot.
  const std::optional<trace::TraceSample>& WorstSample() const { return worst_sample_; }

 protected:
  Rule(std::string id, std::string description, std::string unit);
  /// Counts one checked item and records a finding when `value` exceeds a limit
  /// (upper-bound check). `what()` names the measured quantity; it is only called for a
  /// finding, so the hot path formats nothing. Returns the severity recorded, if any.
  template <typename WhatFn>
  std::optional<FindingSeverity> CheckUpper(double value, int line, long stitch,
                                            const std::string& subject, WhatFn&& what,
                                            const trace::TraceSample* sample) {
    const std::optional<FindingSeverity> sev = Classify(value, line, stitch, sample);
    if (sev) RecordExceeded(*sev, value, line, stitch, subject, what(), sample);
    return sev;
  }
  void Counted() { ++summary_.checked; }
  /// The counting / worst-tracking half of CheckUpper: the severity `value` deserves.
  std::optional<FindingSeverity> Classify(double value, int line, long stitch,
                                          const trace::TraceSample* sample);
  void RecordExceeded(FindingSeverity severity, double value, int line, long stitch,
                      const std::string& subject, const std::string& what,
                      const trace::TraceSample* sample);
  /// Records a finding directly (for yes/no rules). Findings are one per line: a second
  /// finding on a line already reported merges into it (the worse one's value, subject and
  /// message stay; error beats warning, then the larger value over its limit).
  void Record(FindingSeverity severity, double value, double limit, int line, long stitch,
              const std::string& subject, std::string message, const trace::TraceSample* sample);
  /// Tracks the worst value without a finding.
  void Observe(double value, int line, long stitch, const trace::TraceSample* sample);
  /// Adds a subject with its own limits (RuleSummary::subjects); returns its index.
  std::size_t AddSubject(std::string subject, std::optional<double> error_limit,
                         std::optional<double> warning_limit);
  /// Counts one item of subject `index` and tracks its worst value (not the rule's).
  void ObserveSubject(std::size_t index, double value, int line, long stitch);

  RuleSummary summary_;
  std::optional<trace::TraceSample> worst_sample_;

 private:
  /// Severity first, then value over limit (value alone when there is no positive limit).
  static bool Worse(FindingSeverity severity, double value, double limit, const Finding& than);
  /// Line of the last finding recorded and its index in findings (npos when not kept).
  int last_finding_line_ = -1;
  std::size_t last_finding_index_ = static_cast<std::size_t>(-1);
  FindingSeverity last_finding_severity_ = FindingSeverity::kWarning;
  /// Kept findings by line (at most kMaxFindingsPerRule entries), for lines reported out of
  /// order.
  std::unordered_map<int, std::size_t> kept_by_line_;
};

/// Every rule, in report order, with limits from `ctx`.
std::vector<std::unique_ptr<Rule>> MakeRules(const RuleContext& ctx);
/// The rules MakeRules leaves out on purpose (no collision world: the collision.* rules),
/// in registry order, with the reason.
std::vector<SkippedRule> SkippedRules(const RuleContext& ctx);

}  // namespace stitchsim::verify
