// Robustness: random bytes and mutated good programmes must never crash or hang the reader
// or the modal state tracker; they only produce located "gcode-*" diagnostics. Inputs that
// happen to parse clean must survive the writer.

#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "program_test_util.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kGcodeAlphabet = "GMNXYZABCUVEWFTPQ0123456789.+-  \t()%;\r\nxyzgm#e";

void CheckOne(const std::string& input) {
  BoundedDiagnosticSink sink(64);
  std::istringstream in(input);
  const CheckSummary summary = CheckProgram(in, Dialect::Default(), "fuzz.nc", sink);
  for (const Diagnostic& d : sink.Diagnostics()) {
    ASSERT_EQ(d.code.rfind("gcode-", 0), 0u) << d.code;
    ASSERT_GE(d.location.line, 1) << FormatDiagnostic(d);
    ASSERT_LE(d.location.line, summary.lines + 1) << FormatDiagnostic(d);
    ASSERT_GE(d.location.column, 1) << FormatDiagnostic(d);
  }
  DiagnosticSink parse_sink;
  const auto blocks = ParseString(input, Dialect::Default(), "fuzz.nc", parse_sink);
  if (!parse_sink.HasErrors()) {
    // Mutations may add decimals beyond the dialect's, which the writer rounds once; from
    // then on text and blocks are fixed points (docs/program-format.md section 8).
    const std::string written = WriteProgramString(blocks, Dialect::Default());
    DiagnosticSink again;
    const auto reparsed = ParseString(written, Dialect::Default(), "rt.nc", again);
    ASSERT_FALSE(again.HasErrors()) << testing::Describe(again);
    ASSERT_EQ(reparsed.size(), blocks.size()) << input;
    const std::string rewritten = WriteProgramString(reparsed, Dialect::Default());
    ASSERT_EQ(rewritten, written) << input;
    DiagnosticSink third;
    ASSERT_EQ(ParseString(rewritten, Dialect::Default(), "rt.nc", third), reparsed) << input;
  }
}

TEST(program_fuzz, RandomBytes) {
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> length(0, 400);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> pick(0, kGcodeAlphabet.size() - 1);
  for (int round = 0; round < 20000; ++round) {
    std::string input(static_cast<std::size_t>(length(rng)), '\0');
    const bool gcode_like = round % 2 == 0;
    for (char& c : input) {
      c = gcode_like ? kGcodeAlphabet[pick(rng)] : static_cast<char>(byte(rng));
    }
    ASSERT_NO_FATAL_FAILURE(CheckOne(input)) << "round " << round;
  }
}

TEST(program_fuzz, MutatedGoodProgrammes) {
  std::vector<std::string> corpus;
  for (const auto& entry : fs::directory_iterator(testing::ProgramDataDir() / "good")) {
    corpus.push_back(testing::ReadOrFail(entry.path()));
  }
  ASSERT_FALSE(corpus.empty());
  std::mt19937 rng(777);
  std::uniform_int_distribution<std::size_t> pick(0, kGcodeAlphabet.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> edits(1, 4);
  for (int round = 0; round < 20000; ++round) {
    std::string input = corpus[static_cast<std::size_t>(round) % corpus.size()];
    const int n = edits(rng);
    for (int e = 0; e < n && !input.empty(); ++e) {
      std::uniform_int_distribution<std::size_t> at(0, input.size() - 1);
      const std::size_t i = at(rng);
      switch (rng() % 5) {
        case 0:
          input[i] = kGcodeAlphabet[pick(rng)];
          break;
        case 1:
          input.insert(input.begin() + static_cast<std::ptrdiff_t>(i), kGcodeAlphabet[pick(rng)]);
          break;
        case 2:
          input.erase(i, 1);
          break;
        case 3:
          input[i] = static_cast<char>(byte(rng));
          break;
        default:
          input.resize(i);
          break;
      }
    }
    ASSERT_NO_FATAL_FAILURE(CheckOne(input)) << "round " << round;
  }
}

}  // namespace
}  // namespace stitchsim::program
