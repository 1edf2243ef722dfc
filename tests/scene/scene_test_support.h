#pragma once
// Test helpers shared by the scene tests: scratch folders and files under the temp folder.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace stitchsim::scene::testing {

/// A fresh, empty folder per test: <tmp>/stitchsim_<suite>_<pid>/<name>.
inline std::filesystem::path Folder(const std::string& suite, const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("stitchsim_" + suite + "_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// Writes `text` to `p` (binary, parent folders created).
inline void Write(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

/// Writes `text` as <tmp>/stitchsim_<suite>/<name> and returns its path.
inline std::filesystem::path WriteTemp(const std::string& suite, const std::string& name,
                                       const std::string& text) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("stitchsim_" + suite) / name;
  Write(p, text);
  return p;
}

}  // namespace stitchsim::scene::testing
