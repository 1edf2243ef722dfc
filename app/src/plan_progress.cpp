#include "plan_progress.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace stitchsim::app {

namespace {
// Without a terminal, nothing from a run shorter than this (s): a short plan stays out of the log.
constexpr double kQuietRunS = 1.0;
}  // namespace

void PrintTowPieceFixes(const planner::PlyPlan& plan, const char* indent) {
  const planner::TowPieceFixes& fix = plan.fixes;
  std::printf(
      "%stow pieces: shortest %.1f mm (minimum %g mm, 0: none), %d short pieces dropped, %d "
      "extended; restarts (minimum %g mm): %d bridged, %d moved\n",
      indent, plan.shortest_piece_mm, plan.min_tow_length_mm, fix.pieces_dropped,
      fix.pieces_extended, plan.min_restart_mm, fix.restarts_bridged, fix.restarts_moved);
}

void AddQuietFlag(CLI::App& cmd, bool& quiet) {
  cmd.add_flag("--quiet", quiet,
               "No progress on stderr (without a terminal: a line every 10 % and 10 s)");
}

PlanProgressPrinter::PlanProgressPrinter(std::string what, std::string unit, bool quiet)
    : what_(std::move(what)), unit_(std::move(unit)), quiet_(quiet) {}

planner::PlanProgress PlanProgressPrinter::Callback() {
  if (quiet_) return nullptr;
  return [this](double done, double total) { Update(done, total); };
}

void PlanProgressPrinter::Update(double done, double total) {
  if (quiet_) return;
  if (!progress_) {
    Progress::Options options;
    options.plain_min_run_s = kQuietRunS;
    progress_ = std::make_unique<Progress>(what_, unit_, total, std::move(options));
  }
  const double delta = std::max(0.0, done - reported_);
  reported_ += delta;
  progress_->Add(delta);
  progress_->Tick();  // planners call back per row or course: a clock read each is cheap
}

void PlanProgressPrinter::Finish() {
  if (progress_) progress_->Finish();
}

}  // namespace stitchsim::app
