#pragma once
// Helpers shared by the programme tests: parse with a sink that the test then checks, and
// print any diagnostics so a failure says what was wrong.

#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/files.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {

/// gtest printer: a block as canonical text with its source line.
inline void PrintTo(const Block& block, std::ostream* os) {
  std::ostringstream text;
  {
    ProgramWriter writer(text, Dialect::Default());
    writer.Write(block);
  }
  std::string line = text.str();
  if (!line.empty()) line.pop_back();
  *os << "{line " << block.source_line << ": " << line << "}";
}

}  // namespace stitchsim::program

namespace stitchsim::program::testing {

inline std::filesystem::path SourceDir() { return STITCHSIM_SOURCE_DIR; }
inline std::filesystem::path ProgramDataDir() { return SourceDir() / "tests/data/program"; }

inline std::string Describe(const DiagnosticSink& sink) {
  std::string out;
  for (const Diagnostic& d : sink.Diagnostics()) out += FormatDiagnostic(d) + "\n";
  return out;
}

/// Parses `text` and runs every block through ModalState; all diagnostics go to `sink`.
inline std::vector<Block> ParseAndTrack(std::string_view text, DiagnosticSink& sink,
                                        const Dialect& dialect = Dialect::Default(),
                                        ProgramHeader* header = nullptr) {
  std::vector<Block> blocks = ParseString(text, dialect, "test.nc", sink, header);
  ModalState modal(dialect, "test.nc", sink);
  for (const Block& block : blocks) modal.Update(block);
  return blocks;
}

/// Parses `text`, expecting no diagnostics at all.
inline std::vector<Block> ParseClean(std::string_view text,
                                     const Dialect& dialect = Dialect::Default()) {
  DiagnosticSink sink;
  std::vector<Block> blocks = ParseString(text, dialect, "test.nc", sink);
  EXPECT_TRUE(sink.Diagnostics().empty()) << Describe(sink);
  return blocks;
}

/// The first error of parsing `text` (reader and modal state), or an empty Diagnostic.
inline Diagnostic FirstError(std::string_view text, const Dialect& dialect = Dialect::Default()) {
  DiagnosticSink sink;
  ParseAndTrack(text, sink, dialect);
  for (const Diagnostic& d : sink.Diagnostics()) {
    if (d.severity == Severity::kError) return d;
  }
  return {};
}

inline std::string ReadOrFail(const std::filesystem::path& path) {
  const auto text = ReadFile(path);
  EXPECT_TRUE(text.has_value()) << "cannot read " << path;
  return text.value_or("");
}

}  // namespace stitchsim::program::testing
