#pragma once
// Small pieces shared by the benchmark programs: an output sink that only counts bytes, and
// the process's resident memory.

#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <streambuf>

namespace stitchsim::bench {

/// Discards output, counting bytes.
class CountingSink : public std::streambuf {
 public:
  std::uint64_t bytes = 0;

 protected:
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += static_cast<std::uint64_t>(n);
    return n;
  }
  int_type overflow(int_type c) override {
    ++bytes;
    return c;
  }
};

/// Peak resident set size of this process so far (KiB).
inline long PeakRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

/// Resident set size now (KiB).
inline long CurrentRssKb() {
  std::ifstream in("/proc/self/statm");
  long pages = 0, resident = 0;
  in >> pages >> resident;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

}  // namespace stitchsim::bench
