#pragma once
// Shared by the CLI tests of the app_test executable: reading a file whole, and one scratch
// folder per test process (ctest runs each case as its own process, in parallel), removed
// at exit.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace stitchsim::app::testing {

inline std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline const std::filesystem::path& ScratchDir() {
  namespace fs = std::filesystem;
  static const fs::path dir = [] {
    const fs::path d =
        fs::temp_directory_path() / ("stitchsim_app_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  // Destroyed before `dir` (constructed after it): removes the folder at exit.
  static const struct Cleanup {
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup;
  return dir;
}

}  // namespace stitchsim::app::testing
