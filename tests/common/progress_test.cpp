// Progress: plain lines at every 10 % and every 10 s, a terminal bar redrawn in place, silence
// when disabled, exact counts from several threads. A fake clock makes every line exact.
#include "stitchsim/common/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace stitchsim {
namespace {

// A FILE* writing to memory (open_memstream).
class MemoryFile {
 public:
  MemoryFile() : file_(open_memstream(&data_, &size_)) {}
  ~MemoryFile() {
    std::fclose(file_);
    std::free(data_);
  }
  std::FILE* file() { return file_; }
  std::string Text() {
    std::fflush(file_);
    return std::string(data_, size_);
  }

 private:
  char* data_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* file_;
};

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t begin = 0;
  for (std::size_t end; (end = text.find('\n', begin)) != std::string::npos; begin = end + 1) {
    lines.push_back(text.substr(begin, end - begin));
  }
  return lines;
}

Progress::Options Plain(MemoryFile& out, const double& clock_s) {
  Progress::Options options;
  options.terminal = false;
  options.out = out.file();
  options.clock = [&clock_s] { return clock_s; };
  return options;
}

TEST(Progress, PlainLineAtEveryTenPercent) {
  MemoryFile out;
  double t = 0.0;
  Progress progress("verify", "lines", 1000, Plain(out, t));
  for (int i = 1; i <= 1000; ++i) {
    t = i / 100.0;  // 100 lines/s
    progress.Add(1);
  }
  progress.Finish();
  const std::vector<std::string> lines = Lines(out.Text());
  ASSERT_EQ(lines.size(), 10u) << out.Text();
  for (int k = 1; k <= 9; ++k) {
    // At k * 10 %: k * 100 lines after k s; (10 - k) s left at 100 lines/s.
    EXPECT_EQ(lines[k - 1], "verify: " + std::to_string(10 * k) + " % (" + std::to_string(100 * k) +
                                " of 1000 lines), 100 lines/s, " + std::to_string(10 - k) +
                                " s left");
  }
  EXPECT_EQ(lines[9], "verify: 1000 lines in 10.0 s (100 lines/s)");
}

TEST(Progress, TickPrintsALineEveryTenSecondsWithoutAdd) {
  MemoryFile out;
  double t = 0.0;
  Progress progress("plan", "rows", 1000, Plain(out, t));
  progress.Add(1);
  t = 5.0;
  progress.Tick();
  EXPECT_EQ(out.Text(), "");
  t = 10.0;
  progress.Tick();
  // 1 row in 10 s: 0.1 rows/s, 999 rows left = 9990 s = 2 h 46 min 30 s.
  EXPECT_EQ(out.Text(), "plan: 0 % (1 of 1000 rows), 0.1 rows/s, 2 h 46 min left\n");
  t = 19.5;
  progress.Tick();
  EXPECT_EQ(Lines(out.Text()).size(), 1u);
  t = 20.0;
  progress.Tick();
  const std::vector<std::string> lines = Lines(out.Text());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1], "plan: 0 % (1 of 1000 rows), 0.05 rows/s, 5 h 33 min left");
}

TEST(Progress, UnknownTotalPrintsCountsAndRate) {
  MemoryFile out;
  double t = 0.0;
  Progress progress("verify", "lines", 0, Plain(out, t));
  t = 10.0;
  for (int i = 0; i < 5000; ++i) progress.Add(1);  // the clock is read at the 4096th call
  progress.Finish();
  const std::vector<std::string> lines = Lines(out.Text());
  ASSERT_EQ(lines.size(), 2u) << out.Text();
  EXPECT_EQ(lines[0], "verify: 4096 lines, 410 lines/s");  // 409.6 to three digits
  EXPECT_EQ(lines[1], "verify: 5000 lines in 10.0 s (500 lines/s)");
}

TEST(Progress, PlainMinRunKeepsShortRunsOutOfTheLog) {
  MemoryFile out;
  double t = 0.0;
  Progress::Options options = Plain(out, t);
  options.plain_min_run_s = 1.0;
  {
    Progress progress("plan", "rows", 100, options);
    for (int i = 1; i <= 100; ++i) {
      t = i / 200.0;  // half a second in all
      progress.Add(1);
    }
  }
  EXPECT_EQ(out.Text(), "");
  t = 0.0;
  Progress progress("plan", "rows", 100, options);
  for (int i = 1; i <= 100; ++i) {
    t = i / 50.0;  // two seconds: the 10 % .. 40 % steps fall in the first second
    progress.Add(1);
  }
  progress.Finish();
  const std::vector<std::string> lines = Lines(out.Text());
  ASSERT_EQ(lines.size(), 6u) << out.Text();
  // 50 rows at 1 s: 50 rows/s, 50 left = 1 s.
  EXPECT_EQ(lines[0], "plan: 50 % (50 of 100 rows), 50 rows/s, 1 s left");
  EXPECT_EQ(lines[4].rfind("plan: 90 % (90 of 100 rows)", 0), 0u) << lines[4];
  EXPECT_EQ(lines[5], "plan: 100 rows in 2.0 s (50 rows/s)");
}

TEST(Progress, DisabledPrintsNothing) {
  MemoryFile out;
  double t = 0.0;
  Progress::Options options = Plain(out, t);
  options.enabled = false;
  {
    Progress progress("verify", "lines", 100, options);
    for (int i = 0; i < 100; ++i) {
      t += 1.0;
      progress.Add(1);
      progress.Tick();
    }
    progress.Finish();
    EXPECT_EQ(progress.Done(), 100.0);
  }
  EXPECT_EQ(out.Text(), "");
}

TEST(Progress, DestructorPrintsTheFinalLineOnce) {
  MemoryFile out;
  double t = 0.0;
  {
    Progress progress("sequence", "courses", 10, Plain(out, t));
    progress.Add(4);
    t = 125.0;
  }
  // The step line at 40 % comes at time 0: no rate, no time left yet.
  EXPECT_EQ(out.Text(),
            "sequence: 40 % (4 of 10 courses)\n"
            "sequence: 4 courses in 2 min 05 s (0.032 courses/s)\n");
}

TEST(Progress, TwoThreadsCountExactly) {
  MemoryFile out;
  double t = 0.0;
  Progress::Options options;
  options.terminal = false;
  options.out = out.file();
  options.clock = [&t] { return t += 1e-3; };  // called only under the Progress's lock
  Progress progress("verify", "lines", 2e6, options);
  auto work = [&progress] {
    for (int i = 0; i < 1000000; ++i) progress.Add(1);
  };
  std::thread a(work), b(work);
  a.join();
  b.join();
  EXPECT_EQ(progress.Done(), 2e6);
  progress.Finish();
  // Whole lines, percent rising. A step's line waits for the lock, so normally all nine appear;
  // one may fold into the next if the machine parks a thread for milliseconds (not checked).
  const std::vector<std::string> lines = Lines(out.Text());
  ASSERT_GE(lines.size(), 2u) << out.Text();
  ASSERT_LE(lines.size(), 10u) << out.Text();
  int last_percent = 0;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    ASSERT_EQ(lines[i].rfind("verify: ", 0), 0u) << lines[i];
    const int percent = std::atoi(lines[i].c_str() + 8);
    EXPECT_GT(percent, last_percent) << lines[i];
    EXPECT_LT(percent, 100) << lines[i];
    EXPECT_NE(lines[i].find(" % ("), std::string::npos) << lines[i];
    last_percent = percent;
  }
  EXPECT_EQ(lines.back().rfind("verify: 2000000 lines in ", 0), 0u) << lines.back();
}

TEST(Progress, TerminalRedrawsInPlaceUntilFinish) {
  MemoryFile out;
  double t = 0.0;
  Progress::Options options = Plain(out, t);
  options.terminal = true;
  Progress progress("verify", "lines", 100, options);
  for (int i = 1; i <= 100; ++i) {
    t = i * 0.125;  // 8 lines/s; every Add is 0.125 s after the last redraw
    progress.Add(1);
  }
  const std::string drawn = out.Text();
  EXPECT_EQ(drawn.find('\n'), std::string::npos);
  EXPECT_EQ(std::count(drawn.begin(), drawn.end(), '\r'), 100);
  // No rate nor time left in the first second (start-up would skew them).
  EXPECT_EQ(drawn.rfind("\rverify [....................]   1 % 1/100 lines\r", 0), 0u) << drawn;
  // Half way: 50 lines in 6.25 s, 50 left at 8 lines/s = 6.25 s.
  EXPECT_NE(drawn.find("\rverify [##########..........]  50 % 50/100 lines, 8 lines/s, 6 s left"),
            std::string::npos);
  progress.Finish();
  const std::string text = out.Text();
  const std::string final_line = "verify: 100 lines in 12.5 s (8 lines/s)\n";
  ASSERT_GT(text.size(), drawn.size() + final_line.size());
  EXPECT_EQ(text.substr(text.size() - final_line.size()), final_line);
  // The bar is cleared: a carriage return, blanks, a carriage return, then the final line.
  const std::string clear =
      text.substr(drawn.size(), text.size() - drawn.size() - final_line.size());
  EXPECT_EQ(clear.front(), '\r');
  EXPECT_EQ(clear.back(), '\r');
  EXPECT_EQ(clear.find_first_not_of(' ', 1), clear.size() - 1);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
}

TEST(Progress, TerminalRedrawsAtMostTenTimesASecond) {
  MemoryFile out;
  double t = 0.0;
  Progress::Options options = Plain(out, t);
  options.terminal = true;
  Progress progress("verify", "lines", 128, options);
  for (int i = 1; i <= 128; ++i) {
    t = i / 128.0;  // one second in all
    progress.Add(1);
  }
  const std::string drawn = out.Text();
  // Redraws at i = 1, 14, 27, ..., 118: 13/128 s >= 0.1 s apart.
  EXPECT_EQ(std::count(drawn.begin(), drawn.end(), '\r'), 10);
}

}  // namespace
}  // namespace stitchsim
