#pragma once
// Shared by the fuzz targets in tests/fuzz: property checks that abort with a message (so
// libFuzzer and the replay driver both stop on them), and a per-process scratch folder for
// the loaders that only read files.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>

#include "stitchsim/common/diagnostics.h"

namespace stitchsim::fuzz {

/// Aborts with `what` (and the first diagnostics) when `ok` is false: a broken property is a
/// crash to the fuzzer.
inline void Require(bool ok, std::string_view what, const DiagnosticSink* sink = nullptr) {
  if (ok) return;
  std::fprintf(stderr, "fuzz property violated: %.*s\n", static_cast<int>(what.size()),
               what.data());
  if (sink != nullptr) {
    for (const Diagnostic& d : sink->Diagnostics()) {
      std::fprintf(stderr, "  %s\n", FormatDiagnostic(d).c_str());
    }
  }
  std::abort();
}

/// Every diagnostic has a code starting with one of `prefixes` (e.g. "gcode-"), a message and
/// no negative position.
inline void RequireCodes(const DiagnosticSink& sink,
                         std::initializer_list<std::string_view> prefixes) {
  for (const Diagnostic& d : sink.Diagnostics()) {
    bool known = false;
    for (std::string_view p : prefixes) known = known || d.code.rfind(p, 0) == 0;
    Require(known, "diagnostic code outside the loader's families: " + d.code, &sink);
    Require(!d.message.empty(), "diagnostic without a message: " + d.code, &sink);
    Require(d.location.line >= 0 && d.location.column >= 0, "negative line or column", &sink);
  }
}

/// A folder private to this process (removed at exit) for loaders that take paths.
inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "stitchsim-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(ScratchDir(), ec);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

/// Writes `data` to `name` in the scratch folder and returns its path.
inline std::filesystem::path WriteScratch(const std::string& name, const std::uint8_t* data,
                                          std::size_t size) {
  const std::filesystem::path path = ScratchDir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  Require(static_cast<bool>(out), "cannot write the scratch file " + path.string());
  return path;
}

}  // namespace stitchsim::fuzz
