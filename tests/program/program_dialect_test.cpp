// Dialect tests: the bundled file equals the built-in default, a custom dialect changes what
// the reader and writer do, and bad dialect files give located diagnostics.

#include <gtest/gtest.h>

#include <string>

#include "program_test_util.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {
namespace {

using testing::Describe;

TEST(program_dialect, BundledFileEqualsBuiltInDefault) {
  DiagnosticSink sink;
  const auto loaded = LoadDialect(testing::SourceDir() / "models/dialect/default.yaml", sink);
  ASSERT_TRUE(loaded.has_value()) << Describe(sink);
  EXPECT_TRUE(sink.Diagnostics().empty()) << Describe(sink);
  EXPECT_EQ(*loaded, Dialect::Default());
}

TEST(program_dialect, DefaultIsValid) {
  DiagnosticSink sink;
  EXPECT_TRUE(ValidateDialect(Dialect::Default(), "<default>", sink)) << Describe(sink);
}

TEST(program_dialect, CodeMeanings) {
  const Dialect& d = Dialect::Default();
  EXPECT_EQ(d.MeaningOfG(0), GMeaning::kRapid);
  EXPECT_EQ(d.MeaningOfG(1), GMeaning::kFeed);
  EXPECT_EQ(d.MeaningOfG(20), GMeaning::kInch);
  EXPECT_EQ(d.MeaningOfG(21), GMeaning::kMillimetre);
  EXPECT_EQ(d.MeaningOfG(90), GMeaning::kAbsolute);
  EXPECT_EQ(d.MeaningOfG(91), GMeaning::kUnsupportedDistanceMode);
  EXPECT_EQ(d.MeaningOfG(2), GMeaning::kUnsupportedMotion);
  EXPECT_EQ(d.MeaningOfG(17), GMeaning::kUnknown);
  EXPECT_EQ(d.MeaningOfM(6), MMeaning::kToolChange);
  EXPECT_EQ(d.MeaningOfM(10), MMeaning::kStitchOn);
  EXPECT_EQ(d.MeaningOfM(11), MMeaning::kStitchOff);
  EXPECT_EQ(d.MeaningOfM(20), MMeaning::kHeadRetract);
  EXPECT_EQ(d.MeaningOfM(21), MMeaning::kHeadLower);
  EXPECT_EQ(d.MeaningOfM(30), MMeaning::kProgramEnd);
  EXPECT_EQ(d.MeaningOfM(60), MMeaning::kHeadSection);
  EXPECT_EQ(d.MeaningOfM(100), MMeaning::kUserMacro);
  EXPECT_EQ(d.MeaningOfM(199), MMeaning::kUserMacro);
  EXPECT_EQ(d.MeaningOfM(200), MMeaning::kUnknown);
  ASSERT_NE(d.FindTool(1), nullptr);
  EXPECT_EQ(d.FindTool(1)->head, "rs535");
  EXPECT_EQ(d.FindTool(2)->head, "rs566");
  EXPECT_EQ(d.FindTool(3)->head, "afp");
  EXPECT_EQ(d.FindTool(4), nullptr);
}

// The letters are data: move the drive axis to D and the programme text follows.
TEST(program_dialect, CustomDialectMovesTheDriveAxisToD) {
  DiagnosticSink sink;
  const auto custom = LoadDialectFromString(
      "name: drive_on_d\nletters:\n  drive: \"D\"\ndecimals:\n  length: 3\n", "custom.yaml", sink);
  ASSERT_TRUE(custom.has_value()) << Describe(sink);
  EXPECT_EQ(custom->axis_letters[static_cast<int>(Axis::kDrive)], 'D');
  EXPECT_EQ(custom->axis_letters[static_cast<int>(Axis::kX)], 'X');  // untouched keys keep defaults

  const auto blocks = testing::ParseClean("G1 X1 D5 V5 F100\n", *custom);
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0][Axis::kDrive], 5.0);
  EXPECT_EQ(testing::FirstError("G1 X1 U5\n", *custom).code, "gcode-unknown-word");
  EXPECT_EQ(testing::FirstError("G1 X1 D5\n").code, "gcode-unknown-word");

  Block b = blocks[0];
  b[Axis::kX] = 1.23456;
  const std::string text = WriteProgramString(std::vector<Block>{b}, *custom);
  EXPECT_EQ(text, "%\nG1 X1.235 D5 V5 F100\n%\n");
  b[Axis::kX] = 1.235;
  EXPECT_EQ(testing::ParseClean(text, *custom)[0], b);
}

struct BadDialect {
  const char* yaml;
  const char* code;
  int line;
  int column;
};

class program_bad_dialect : public ::testing::TestWithParam<BadDialect> {};

TEST_P(program_bad_dialect, IsRejectedWithALocatedDiagnostic) {
  const BadDialect& bad = GetParam();
  DiagnosticSink sink;
  EXPECT_FALSE(LoadDialectFromString(bad.yaml, "bad.yaml", sink).has_value());
  ASSERT_FALSE(sink.Diagnostics().empty());
  const Diagnostic& d = sink.Diagnostics().front();
  EXPECT_EQ(d.code, bad.code) << Describe(sink);
  EXPECT_EQ(d.location.file, "bad.yaml");
  EXPECT_EQ(d.location.line, bad.line) << Describe(sink);
  EXPECT_EQ(d.location.column, bad.column) << Describe(sink);
}

INSTANTIATE_TEST_SUITE_P(
    program, program_bad_dialect,
    ::testing::Values(BadDialect{"letters: [X, Y\n", "dialect-yaml-syntax", 2, 1},
                      BadDialect{"name: x\nletterz:\n  x: X\n", "dialect-unknown-key", 2, 1},
                      BadDialect{"letters:\n  drive: \"X\"\n", "dialect-duplicate-letter", 2, 3},
                      BadDialect{"letters:\n  drive: \"G\"\n", "dialect-bad-letter", 2, 3},
                      BadDialect{"letters:\n  drive: dd\n", "dialect-bad-letter", 2, 10},
                      BadDialect{"euler_order: XXY\n", "dialect-bad-euler-order", 1, 1},
                      BadDialect{"m_codes:\n  stitch_on: 6\n", "dialect-duplicate-code", 2, 3},
                      BadDialect{"m_codes:\n  user_macros: [1, 50]\n", "dialect-duplicate-code", 2,
                                 3},
                      BadDialect{"decimals:\n  length: 12\n", "dialect-bad-value", 2, 3},
                      BadDialect{"decimals:\n  length: six\n", "dialect-bad-value", 2, 11},
                      BadDialect{"default_units: furlong\n", "dialect-bad-value", 1, 16},
                      BadDialect{"tools:\n  1: rs535\n  1: afp\n", "dialect-duplicate-code", 3, 3},
                      BadDialect{"- just\n- a list\n", "dialect-bad-value", 1, 1}));

TEST(program_dialect, MissingFileIsReported) {
  DiagnosticSink sink;
  EXPECT_FALSE(LoadDialect("/nonexistent/dialect.yaml", sink).has_value());
  ASSERT_EQ(sink.Diagnostics().size(), 1u);
  EXPECT_EQ(sink.Diagnostics()[0].code, "dialect-file-not-found");
}

}  // namespace
}  // namespace stitchsim::program
