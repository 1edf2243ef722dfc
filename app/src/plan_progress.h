#pragma once
// Progress of `plan` and `sequence` on stderr (docs/ci.md, "Progress in CI logs"): a
// planner's PlanProgress callback feeds a common Progress made at its first call, when the
// total is known. `--quiet` leaves the callback null, so the planner pays nothing.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "stitchsim/common/progress.h"
#include "stitchsim/planner/plan_progress.h"
#include "stitchsim/planner/ply_planner.h"

namespace stitchsim::app {

/// Adds `--quiet` (no progress on stderr) to a subcommand.
void AddQuietFlag(CLI::App& cmd, bool& quiet);

/// One line on stdout, after `indent`: a ply plan's shortest tow piece and what the planner
/// did to the pieces and restarts the head cannot lay (plan ply, and per ply plan laminate).
void PrintTowPieceFixes(const planner::PlyPlan& plan, const char* indent);

/// One run's progress line: "plan raster: 40 % (...)". Without a terminal a run shorter than
/// a second prints nothing at all (a short plan stays out of the log); on one, a bar and a
/// final line.
class PlanProgressPrinter {
 public:
  PlanProgressPrinter(std::string what, std::string unit, bool quiet);
  ~PlanProgressPrinter() = default;
  PlanProgressPrinter(const PlanProgressPrinter&) = delete;
  PlanProgressPrinter& operator=(const PlanProgressPrinter&) = delete;

  /// For a planner's options: null when quiet. Valid while this printer lives.
  planner::PlanProgress Callback();
  /// `done` so far of `total` (0: unknown); the first call fixes the total.
  void Update(double done, double total);
  /// The final line (nothing for a short run without a terminal, or before any Update).
  void Finish();

 private:
  const std::string what_, unit_;
  const bool quiet_;
  std::unique_ptr<Progress> progress_;
  double reported_ = 0.0;  ///< what was passed to progress_ so far, in the planner's unit
};

}  // namespace stitchsim::app
