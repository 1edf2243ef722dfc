#pragma once
// Shared by the CLI tests of the app_test executable: reading a file whole, and one scratch
// folder per test process (ctest runs each case as its own process, in parallel), removed
// at exit.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
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

/// What one run of the built `stitchsim` printed and returned.
struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

/// Runs `stitchsim <args>` (a shell command line), capturing stdout and stderr in files named
/// after `tag` in the scratch folder.
inline CliRun RunCli(const std::string& args, const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path binary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";
  const fs::path out = ScratchDir() / (tag + "_out.txt"), err = ScratchDir() / (tag + "_err.txt");
  const std::string cmd = binary.string() + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadText(out), ReadText(err)};
}

}  // namespace stitchsim::app::testing
