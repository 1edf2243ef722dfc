// The file corpus: every good/*.nc parses clean and survives parse(write(parse(f))); every
// bad/<code>.nc fails first with <code> at the line:col its "; expect L:C" line names.

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "program_test_util.h"
#include "stitchsim/program/diagnostic_codes.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {
namespace {

namespace fs = std::filesystem;
using testing::Describe;

std::vector<fs::path> FilesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".nc") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(program_corpus, GoodFilesParseCleanAndRoundTrip) {
  const auto files = FilesIn(testing::ProgramDataDir() / "good");
  EXPECT_GE(files.size(), 30u);
  for (const fs::path& path : files) {
    SCOPED_TRACE(path.filename().string());
    const std::string text = testing::ReadOrFail(path);
    DiagnosticSink sink;
    ProgramHeader header;
    const auto blocks = testing::ParseAndTrack(text, sink, Dialect::Default(), &header);
    EXPECT_TRUE(sink.Diagnostics().empty()) << Describe(sink);
    EXPECT_FALSE(blocks.empty());

    // Header comment lines are blocks, so they are written (and re-read) with the rest.
    const std::string written = WriteProgramString(blocks, Dialect::Default());
    DiagnosticSink sink2;
    ProgramHeader header2;
    const auto reparsed = testing::ParseAndTrack(written, sink2, Dialect::Default(), &header2);
    EXPECT_TRUE(sink2.Diagnostics().empty()) << Describe(sink2) << written;
    EXPECT_EQ(reparsed, blocks) << written;
    EXPECT_EQ(header2, header);
    EXPECT_EQ(WriteProgramString(reparsed, Dialect::Default()), written);
  }
}

// "; expect L:C" on the first line.
bool ParseExpectation(const std::string& text, int& line, int& column) {
  constexpr std::string_view kTag = "; expect ";
  if (text.compare(0, kTag.size(), kTag) != 0) return false;
  const char* p = text.data() + kTag.size();
  const char* end = text.data() + text.size();
  auto r = std::from_chars(p, end, line);
  if (r.ec != std::errc() || r.ptr == end || *r.ptr != ':') return false;
  r = std::from_chars(r.ptr + 1, end, column);
  return r.ec == std::errc();
}

TEST(program_corpus, BadFilesFailWithTheirCodeAtTheirLocation) {
  const auto files = FilesIn(testing::ProgramDataDir() / "bad");
  std::set<std::string> codes;
  const auto all = AllProgramDiagnosticCodes();
  for (const fs::path& path : files) {
    const std::string code = path.stem().string();
    SCOPED_TRACE(path.filename().string());
    codes.insert(code);
    EXPECT_NE(std::find(all.begin(), all.end(), code), all.end()) << "not a listed code";
    const std::string text = testing::ReadOrFail(path);
    int line = 0;
    int column = 0;
    ASSERT_TRUE(ParseExpectation(text, line, column)) << "first line must be '; expect L:C'";
    DiagnosticSink sink;
    testing::ParseAndTrack(text, sink, Dialect::Default());
    ASSERT_TRUE(sink.HasErrors());
    const Diagnostic& first = sink.Diagnostics().front();
    EXPECT_EQ(first.severity, Severity::kError);
    EXPECT_EQ(first.code, code) << Describe(sink);
    EXPECT_EQ(first.location.line, line) << Describe(sink);
    EXPECT_EQ(first.location.column, column) << Describe(sink);
  }
  EXPECT_GE(codes.size(), 25u);
  // Every code has a bad file, except those that need a non-default dialect to occur, or
  // 2e9 lines (gcode-too-many-lines: reader_test.cpp gives it a small limit).
  const std::set<std::string> needs_custom_dialect = {"gcode-exponent-not-allowed",
                                                      "gcode-too-many-lines"};
  for (std::string_view code : all) {
    EXPECT_TRUE(codes.count(std::string(code)) || needs_custom_dialect.count(std::string(code)))
        << "no bad file for " << code;
  }
}

TEST(program_corpus, EveryCodeIsDocumented) {
  const std::string doc = testing::ReadOrFail(testing::SourceDir() / "docs/program-format.md");
  for (const auto list : {AllProgramDiagnosticCodes(), AllDialectDiagnosticCodes()}) {
    for (std::string_view code : list) {
      EXPECT_NE(doc.find("`" + std::string(code) + "`"), std::string::npos)
          << code << " is not in docs/program-format.md";
    }
  }
  std::set<std::string_view> distinct(AllProgramDiagnosticCodes().begin(),
                                      AllProgramDiagnosticCodes().end());
  EXPECT_EQ(distinct.size(), AllProgramDiagnosticCodes().size());
}

}  // namespace
}  // namespace stitchsim::program
