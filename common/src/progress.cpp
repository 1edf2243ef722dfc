#include "stitchsim/common/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

namespace stitchsim {
namespace {

constexpr double kRedrawInterval_s = 0.1;    // a terminal bar: at most ~10 redraws a second
constexpr double kCheckFraction = 1e-3;      // Add() looks at the clock every 0.1 % of the total
constexpr std::uint64_t kCheckCalls = 4096;  // ... or every 4096 calls when the total is unknown
constexpr int kBarChars = 20;
constexpr double kStepEps = 1e-9;     // 0.1 * 1000 is step 1, not 0.99999...
constexpr double kRateAfter_s = 1.0;  // a rate and time left from the first second only (start-up)

double SteadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string Printf(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

// A count of units: whole numbers as such ("1675015").
std::string CountText(double count) { return Printf("%.0f", count); }

// A rate to three significant digits: "69500", "695", "69.5", "0.1".
std::string SignificantText(double value) {
  if (value < 999.5) return Printf("%.3g", value);
  const double unit = std::pow(10.0, std::floor(std::log10(value)) - 2.0);
  return Printf("%.0f", std::round(value / unit) * unit);
}

// A time span: "14 s", "3 min 05 s", "2 h 07 min".
std::string DurationText(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buffer[64];
  if (s < 60) {
    std::snprintf(buffer, sizeof buffer, "%ld s", s);
  } else if (s < 3600) {
    std::snprintf(buffer, sizeof buffer, "%ld min %02ld s", s / 60, s % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  }
  return buffer;
}

Progress::Options WithClock(Progress::Options options) {
  if (!options.clock) options.clock = SteadySeconds;
  return options;
}

bool IsTerminal(const Progress::Options& options) {
  if (options.terminal) return *options.terminal;
  return options.out != nullptr && isatty(fileno(options.out)) == 1;
}

}  // namespace

Progress::Progress(std::string what, std::string unit, double total, Options options)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total > 0.0 ? total : 0.0),
      options_(WithClock(std::move(options))),
      terminal_(IsTerminal(options_)),
      start_s_(options_.clock()),
      last_line_s_(start_s_) {
  if (options_.out == nullptr) finished_ = true;  // nowhere to write: as if disabled
  if (!options_.enabled) finished_ = true;
  next_check_ = NextCheck(0.0);
}

Progress::~Progress() { Finish(); }

std::int64_t Progress::StepIndex(double done) const {
  const double step = total_ * options_.plain_step_fraction;
  return step > 0.0 ? static_cast<std::int64_t>(std::floor(done / step + kStepEps)) : 0;
}

double Progress::NextCheck(double done) const {
  if (total_ <= 0.0) return 1e300;  // only the call count triggers a check
  double next = done + total_ * kCheckFraction;
  const double step = total_ * options_.plain_step_fraction;
  if (!terminal_ && step > 0.0) {
    next = std::min(next, (std::floor(done / step + kStepEps) + 1.0) * step);
  }
  return next;
}

void Progress::Add(double done) {
  const double before = done_.fetch_add(done, std::memory_order_relaxed);
  const double now_done = before + done;
  if (finished_.load(std::memory_order_relaxed)) return;
  if (total_ > 0.0) {
    if (now_done < next_check_.load(std::memory_order_relaxed)) return;
    // Exactly one Add() crosses each step (fetch_add hands out disjoint ranges): it waits for
    // the lock, so a step's line is not lost while another thread prints (10 times a run).
    if (!terminal_ && StepIndex(now_done) > StepIndex(before)) {
      std::lock_guard lock(mutex_);
      ReportLocked();
      return;
    }
  } else if ((calls_.fetch_add(1, std::memory_order_relaxed) + 1) % kCheckCalls != 0) {
    return;
  }
  // Another thread reporting now reads done_ itself, or the next Add() retries.
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (lock.owns_lock()) ReportLocked();
}

void Progress::Tick() {
  if (finished_.load(std::memory_order_relaxed)) return;
  std::lock_guard lock(mutex_);
  ReportLocked();
}

void Progress::ReportLocked() {
  if (finished_) return;
  const double now_s = options_.clock();
  const double done = done_.load(std::memory_order_relaxed);
  next_check_.store(NextCheck(done), std::memory_order_relaxed);
  if (terminal_) {
    if (now_s - last_draw_s_ >= kRedrawInterval_s) DrawBarLocked(done, now_s);
    return;
  }
  const std::int64_t step_index = StepIndex(done);
  if (now_s - start_s_ < options_.plain_min_run_s) {
    last_step_ = std::max(last_step_, step_index);  // the steps passed then are not due later
    return;
  }
  // The step at 100 % is left to Finish()'s final line.
  const bool step_due = step_index > last_step_ && done < total_;
  const bool time_due = now_s - last_line_s_ >= options_.plain_interval_s;
  if (!step_due && !time_due) return;
  last_step_ = std::max(last_step_, step_index);
  PrintPlainLocked(done, now_s);
}

std::string Progress::RateText(double done, double elapsed_s) const {
  if (elapsed_s <= 0.0) return "";
  return SignificantText(done / elapsed_s) + " " + unit_ + "/s";
}

void Progress::PrintPlainLocked(double done, double now_s) {
  last_line_s_ = now_s;
  const double elapsed_s = now_s - start_s_;
  std::string line = what_ + ": ";
  if (total_ > 0.0) {
    line += CountText(std::floor(100.0 * done / total_ + kStepEps)) + " % (" + CountText(done) +
            " of " + CountText(total_) + " " + unit_ + ")";
  } else {
    line += CountText(done) + " " + unit_;
  }
  if (elapsed_s >= kRateAfter_s) line += ", " + RateText(done, elapsed_s);
  if (total_ > 0.0 && done > 0.0 && elapsed_s >= kRateAfter_s) {
    line += ", " + DurationText(std::max(0.0, total_ - done) * elapsed_s / done) + " left";
  }
  line += "\n";
  std::fputs(line.c_str(), options_.out);
  std::fflush(options_.out);
}

void Progress::DrawBarLocked(double done, double now_s) {
  last_draw_s_ = now_s;
  const double elapsed_s = now_s - start_s_;
  std::string line = what_ + " ";
  if (total_ > 0.0) {
    const double fraction = std::clamp(done / total_, 0.0, 1.0);
    const int filled = static_cast<int>(std::floor(fraction * kBarChars + kStepEps));
    line += "[" + std::string(filled, '#') + std::string(kBarChars - filled, '.') + "] " +
            Printf("%3.0f", std::floor(100.0 * fraction + kStepEps)) + " % " + CountText(done) +
            "/" + CountText(total_) + " " + unit_;
  } else {
    line += CountText(done) + " " + unit_;
  }
  if (elapsed_s >= kRateAfter_s) line += ", " + RateText(done, elapsed_s);
  if (total_ > 0.0 && done > 0.0 && elapsed_s >= kRateAfter_s) {
    line += ", " + DurationText(std::max(0.0, total_ - done) * elapsed_s / done) + " left";
  }
  // Pad over what the last redraw left on screen.
  const std::size_t width = line.size();
  if (width < bar_width_) line += std::string(bar_width_ - width, ' ');
  bar_width_ = std::max(bar_width_, width);
  std::fputs(("\r" + line).c_str(), options_.out);
  std::fflush(options_.out);
}

void Progress::Finish() {
  if (finished_.load()) return;
  std::lock_guard lock(mutex_);
  if (finished_.exchange(true)) return;
  const double now_s = options_.clock();
  const double elapsed_s = now_s - start_s_;
  const double done = done_.load();
  if (!terminal_ && elapsed_s < options_.plain_min_run_s) return;
  std::string line;
  if (terminal_ && bar_width_ > 0) line = "\r" + std::string(bar_width_, ' ') + "\r";
  line += what_ + ": " + CountText(done) + " " + unit_ + " in " +
          (elapsed_s < 59.95 ? Printf("%.1f s", elapsed_s) : DurationText(elapsed_s));
  const std::string rate = RateText(done, elapsed_s);
  if (!rate.empty()) line += " (" + rate + ")";
  line += "\n";
  std::fputs(line.c_str(), options_.out);
  std::fflush(options_.out);
}

}  // namespace stitchsim
