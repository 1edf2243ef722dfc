#pragma once
// Test helpers shared by the scene tests: scratch folders and files under the temp folder,
// a scene loaded with its first diagnostic, the command line run with its output kept.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "stitchsim/scene/scene.h"

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

/// Writes `text` as <tmp>/stitchsim_<suite>_<pid>/<name> and returns its path.
inline std::filesystem::path WriteTemp(const std::string& suite, const std::string& name,
                                       const std::string& text) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() /
      ("stitchsim_" + suite + "_" + std::to_string(::getpid())) / name;  // tests run in parallel
  Write(p, text);
  return p;
}

/// A scene as loaded, with its first diagnostic (code, line, formatted message) if any.
struct Loaded {
  std::unique_ptr<Scene> scene;
  std::string code;
  int line = 0;
  std::string message;
};
inline Loaded Load(const std::filesystem::path& file) {
  DiagnosticSink sink;
  Loaded out;
  out.scene = LoadScene(file, sink);
  if (!sink.Diagnostics().empty()) {
    out.code = sink.Diagnostics().front().code;
    out.line = sink.Diagnostics().front().location.line;
    out.message = FormatDiagnostic(sink.Diagnostics().front());
  }
  return out;
}

/// Runs `stitchsim args` (the build's binary) with stdout and stderr to `log`; the exit code.
inline int RunCli(const std::string& args, const std::filesystem::path& log) {
  const std::string cmd =
      std::string(STITCHSIM_BINARY_DIR) + "/app/stitchsim " + args + " >" + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The whole text of `p` ("" if it cannot be read).
inline std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace stitchsim::scene::testing
