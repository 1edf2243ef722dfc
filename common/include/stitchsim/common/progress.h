#pragma once
// Progress of a long run on stderr: on a terminal a bar redrawn in place (percent, rate,
// time left); without one (CI logs) a plain line at every 10 % and at least every 10 s.
// Debian 12 packages no C++ progress-bar library (p-ranav/indicators is not in bookworm),
// so this is our own and kept small.

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

namespace stitchsim {

class Progress {
 public:
  struct Options {
    bool enabled = true;                ///< false: prints nothing (--quiet)
    std::optional<bool> terminal;       ///< default: isatty(fileno(out))
    std::FILE* out = stderr;            ///< where lines go; never stdout for a command's output
    double plain_interval_s = 10.0;     ///< without a terminal: a line at least this often ...
    double plain_step_fraction = 0.10;  ///< ... and at every 10 % of the total (0: never)
    /// Without a terminal: no line at all during the first this many seconds, and no final line
    /// for a run shorter than that (a short run stays out of the log). 0: every line.
    double plain_min_run_s = 0.0;
    std::function<double()> clock;  ///< seconds, monotonic; default steady_clock (tests fake it)
  };

  /// `what`: the line's prefix ("verify"), `unit`: what is counted ("lines"), `total` > 0 (if 0:
  /// no percent / time left, only counts and rate).
  Progress(std::string what, std::string unit, double total, Options options);
  ~Progress();  // Finish() if not finished
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Thread-safe: several worker threads add what they completed; cheap when nothing is due
  /// (an atomic add, and a clock read only at each 0.1 % of the total, or every 4096 calls when
  /// the total is unknown).
  void Add(double done);
  /// A line is due when 10 s passed even if Add is not called: call Tick() from a loop that
  /// waits (e.g. every ~0.5 s while workers run).
  void Tick();
  /// The final line (plain) / clears the bar (terminal) and prints the final line:
  /// "verify: 1675015 lines in 24.1 s (69500 lines/s)". Later calls do nothing.
  void Finish();

  /// What was added so far (in `unit`s).
  double Done() const { return done_.load(std::memory_order_relaxed); }

 private:
  void ReportLocked();  // mutex_ held: prints a line or redraws the bar if one is due
  void PrintPlainLocked(double done, double now_s);
  void DrawBarLocked(double done, double now_s);
  double NextCheck(double done) const;
  std::int64_t StepIndex(double done) const;  ///< plain_step_fraction steps in `done`
  std::string RateText(double done, double elapsed_s) const;

  const std::string what_, unit_;
  const double total_;                   ///< in `unit`s; 0 = unknown
  const Options options_;                ///< as given, clock filled in
  const bool terminal_;                  ///< bar redrawn in place, else plain lines
  const double start_s_;                 ///< clock at construction, s
  std::atomic<double> done_{0.0};        ///< in `unit`s, added by Add()
  std::atomic<double> next_check_{0.0};  ///< Add() reports when done_ reaches this (total > 0)
  std::atomic<std::uint64_t> calls_{0};  ///< Add() calls, for the check when total is unknown
  std::atomic<bool> finished_{false};

  std::mutex mutex_;             ///< guards the fields below and the output
  double last_line_s_;           ///< clock at the last plain line (or the start), s
  double last_draw_s_ = -1e300;  ///< clock at the last bar redraw, s
  std::int64_t last_step_ = 0;   ///< index of the last plain_step_fraction step printed
  std::size_t bar_width_ = 0;    ///< characters of the bar on screen now (to clear it)
};

}  // namespace stitchsim
