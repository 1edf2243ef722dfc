// Parser unit tests: fields and columns of one block, the noise the dialect tolerates, and
// errors that need a custom dialect or a very long input (the rest live in tests/data).

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "program_test_util.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::program {
namespace {

using testing::FirstError;
using testing::ParseClean;

TEST(program_parser, ReadsEveryFieldOfABlock) {
  const auto blocks = ParseClean(
      "N5 G21 G90 G1 X1.5 Y-2 Z+3 A.5 B-.5 C0 U5 V5.25 E1 W2 F100 T1 M6 M10 (stitch one)\n");
  ASSERT_EQ(blocks.size(), 1u);
  const Block& b = blocks[0];
  EXPECT_EQ(b.source_line, 1);
  EXPECT_EQ(b.block_number, 5);
  EXPECT_EQ(b.units, LengthUnit::kMillimetre);
  EXPECT_TRUE(b.absolute);
  EXPECT_EQ(b.motion, Motion::kFeed);
  EXPECT_EQ(b[Axis::kX], 1.5);
  EXPECT_EQ(b[Axis::kY], -2.0);
  EXPECT_EQ(b[Axis::kZ], 3.0);
  EXPECT_EQ(b[Axis::kA], 0.5);
  EXPECT_EQ(b[Axis::kB], -0.5);
  EXPECT_EQ(b[Axis::kC], 0.0);
  EXPECT_EQ(b[Axis::kDrive], 5.0);
  EXPECT_EQ(b[Axis::kPathLength], 5.25);
  EXPECT_EQ(b[Axis::kRail], 1.0);
  EXPECT_EQ(b[Axis::kRotator], 2.0);
  EXPECT_EQ(b.feed, 100.0);
  EXPECT_EQ(b.tool, 1);
  EXPECT_FALSE(b.param.has_value());
  EXPECT_EQ(b.m_codes, (std::vector<int>{6, 10}));
  EXPECT_EQ(b.comment, "stitch one");
  EXPECT_EQ(b.columns.first_word, 1);
  EXPECT_EQ(b.columns.motion, 12);
  EXPECT_EQ(b.columns.axes[0], 15);
  EXPECT_EQ(b.columns.m_codes[1], 66);
}

TEST(program_parser, NoiseVariantsGiveTheSameBlocks) {
  const auto canonical = ParseClean("G1 X1 Y2 Z-0.5 F100\n");
  for (const char* variant :
       {"G1X1Y2Z-.5F100\n", "g1 x1 y2 z-0.5 f100\n", "G01 X+1 Y2. Z-0.50 F100\r\n",
        "\tG1\tX1  Y2 Z-.5 F100   \n", "G1 X1 Y2 Z-0.5 F100", "   G1X1 Y2Z-.5 F100"}) {
    EXPECT_EQ(ParseClean(variant), canonical) << variant;
  }
}

TEST(program_parser, CommentsAreJoinedAndTrimmed) {
  const auto blocks = ParseClean("(a) G1 (  b  ) X1 ; c (d)\n;   only comment  \n( )\n");
  ASSERT_EQ(blocks.size(), 2u);  // "( )" holds no text: a blank line
  EXPECT_EQ(blocks[0].comment, "a b c (d)");
  EXPECT_EQ(blocks[0][Axis::kX], 1.0);
  EXPECT_FALSE(blocks[1].HasWords());
  EXPECT_EQ(blocks[1].comment, "only comment");
  EXPECT_EQ(blocks[1].source_line, 2);
}

TEST(program_parser, HeaderEntriesAreExposed) {
  DiagnosticSink sink;
  ProgramHeader header;
  ParseString(
      "(STITCHSIM scene=circle_8in head=rs535 stitch_length_mm=5.000000 mode=decoupled)\n"
      "%\nG21\n(STITCHSIM late=ignored)\nM30\n%\n",
      Dialect::Default(), "h.nc", sink, &header);
  EXPECT_TRUE(sink.Diagnostics().empty()) << testing::Describe(sink);
  ASSERT_EQ(header.entries.size(), 4u);
  EXPECT_EQ(header.Find("scene"), "circle_8in");
  EXPECT_EQ(header.Find("head"), "rs535");
  EXPECT_EQ(header.Find("stitch_length_mm"), "5.000000");
  EXPECT_EQ(header.Find("mode"), "decoupled");
  EXPECT_FALSE(header.Find("late").has_value());
}

TEST(program_parser, NotAHeaderUnlessTheTagStandsAlone) {
  DiagnosticSink sink;
  ProgramHeader header;
  ParseString("(STITCHSIMULATION a b)\n(stitchsim x=1)\nG21\n", Dialect::Default(), "h.nc", sink,
              &header);
  EXPECT_TRUE(sink.Diagnostics().empty()) << testing::Describe(sink);
  EXPECT_TRUE(header.empty());
}

TEST(program_parser, EIsTheRailLetterSoNoExponentInTheDefaultDialect) {
  const auto blocks = ParseClean("G1 X1E3\n");
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0][Axis::kX], 1.0);
  EXPECT_EQ(blocks[0][Axis::kRail], 3.0);
}

TEST(program_parser, ExponentIsAnErrorWhenEIsNotALetter) {
  Dialect dialect = Dialect::Default();
  dialect.axis_letters[static_cast<int>(Axis::kRail)] = 'R';
  for (const char* line : {"G1 X1e3\n", "G1 X1.5E-3\n", "G1 X1E+2\n"}) {
    const Diagnostic d = FirstError(line, dialect);
    EXPECT_EQ(d.code, "gcode-exponent-not-allowed") << line;
    EXPECT_EQ(d.location.column, line[5] == 'e' || line[5] == 'E' ? 6 : 8) << line;
  }
  EXPECT_EQ(FirstError("G1 X1 E3\n", dialect).code, "gcode-unknown-word");
}

TEST(program_parser, IntegerWordsRejectSignsFractionsAndOverflow) {
  EXPECT_EQ(FirstError("N10.5 G21\n").code, "gcode-fractional-code");
  EXPECT_EQ(FirstError("G21 T1.5\n").code, "gcode-fractional-code");
  EXPECT_EQ(FirstError("G1.\n").code, "gcode-fractional-code");
  EXPECT_EQ(FirstError("M-6\n").code, "gcode-signed-code");
  EXPECT_EQ(FirstError("G+1\n").code, "gcode-signed-code");
  EXPECT_EQ(FirstError("N1234567890 G21\n").code, "gcode-number-overflow");
  EXPECT_EQ(FirstError("Ginf\n").code, "gcode-nan");
  EXPECT_EQ(FirstError("G\n").code, "gcode-missing-value");
}

TEST(program_parser, RealWordsRejectMalformedNumbers) {
  EXPECT_EQ(FirstError("G1 X-\n").code, "gcode-bad-number");
  EXPECT_EQ(FirstError("G1 X.\n").code, "gcode-bad-number");
  EXPECT_EQ(FirstError("G1 X1-2\n").code, "gcode-bad-number");
  EXPECT_EQ(FirstError("G1 X-inf\n").code, "gcode-nan");
  EXPECT_EQ(FirstError("G1 XNaN\n").code, "gcode-nan");
  EXPECT_EQ(FirstError("G1 X1000000000.1\n").code, "gcode-number-overflow");
  EXPECT_EQ(FirstError(std::string("G1 X1") + std::string(400, '0') + "\n").code,
            "gcode-number-overflow");
  // Exactly 1e9 is allowed.
  EXPECT_EQ(ParseClean("G1 X-1000000000\n")[0][Axis::kX], -1e9);
}

TEST(program_parser, InvalidCharactersPointAtTheByte) {
  const Diagnostic tab_ok = FirstError("G21\t(tab\tinside)\n");
  EXPECT_TRUE(tab_ok.code.empty()) << tab_ok.code;
  Diagnostic d = FirstError(std::string("G21 X1\x01") + "\n");
  EXPECT_EQ(d.code, "gcode-invalid-character");
  EXPECT_EQ(d.location.column, 7);
  d = FirstError("G21 #1=5\n");
  EXPECT_EQ(d.code, "gcode-invalid-character");
  EXPECT_EQ(d.location.column, 5);
  d = FirstError("G21 %\n");
  EXPECT_EQ(d.code, "gcode-invalid-character");
  d = FirstError("G21\rG90\n");
  EXPECT_EQ(d.code, "gcode-invalid-character");
  EXPECT_EQ(d.location.column, 4);
}

TEST(program_parser, ErrorLinesAreSkippedAndParsingContinues) {
  DiagnosticSink sink;
  const auto blocks = ParseString("G21\nG1 X1 Q2\nG90\n", Dialect::Default(), "t.nc", sink);
  ASSERT_EQ(sink.ErrorCount(), 1u);
  EXPECT_EQ(FormatDiagnostic(sink.Diagnostics()[0]),
            "t.nc:2:7: error[gcode-unknown-word]: unknown word letter 'Q' in dialect 'default'");
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[1].source_line, 3);
}

TEST(program_parser, EmptyInputIsAnEmptyProgramme) {
  const Diagnostic d = FirstError("");
  EXPECT_EQ(d.code, "gcode-empty-program");
  EXPECT_EQ(d.location.line, 1);
  EXPECT_EQ(FirstError("\n\n(only a comment)\n").code, "gcode-empty-program");
}

TEST(program_parser, PercentMarks) {
  EXPECT_TRUE(FirstError("%\nG21\n%\n\n  \n").code.empty());
  EXPECT_TRUE(FirstError("G21\n%\n").code.empty());
  EXPECT_EQ(FirstError("%\nG21\n%\n(late)\n").code, "gcode-text-after-end");
  EXPECT_EQ(FirstError("%\nG21\n%\n%\n").code, "gcode-text-after-end");
}

// Lines that straddle the reader's 64 KiB chunks and lines far beyond the length limit.
TEST(program_parser, StreamsAcrossChunkBoundaries) {
  std::string text = "%\nG21 G90 G1 F1000\n";
  const int kLines = 60000;
  for (int i = 0; i < kLines; ++i) {
    text += "X" + std::to_string(i) + ".125 Y-" + std::to_string(i % 977) + " Z0.5 A1 B2 C3 U" +
            std::to_string(i) + " V" + std::to_string(i) + "\n";
  }
  text += "M30\n%\n";
  ASSERT_GT(text.size(), std::size_t{2} << 20);
  DiagnosticSink sink;
  std::istringstream in(text);
  ProgramReader reader(in, Dialect::Default(), "big.nc", sink);
  Block block;
  ASSERT_TRUE(reader.Next(block));
  int i = 0;
  while (reader.Next(block) && block.HasAxisWords()) {
    ASSERT_EQ(block[Axis::kX], i + 0.125) << "line " << block.source_line;
    ASSERT_EQ(block[Axis::kDrive], i);
    ++i;
  }
  EXPECT_EQ(i, kLines);
  EXPECT_FALSE(reader.Next(block));
  EXPECT_TRUE(sink.Diagnostics().empty()) << testing::Describe(sink);
  EXPECT_EQ(reader.BytesRead(), text.size());
  EXPECT_EQ(reader.LineCount(), kLines + 4);
}

TEST(program_parser, HugeLineIsReportedOnceAndSkipped) {
  std::string text = "G21\n(" + std::string(3u << 20, 'x') + ")\nG90\n";
  DiagnosticSink sink;
  const auto blocks = ParseString(text, Dialect::Default(), "t.nc", sink);
  ASSERT_EQ(sink.Diagnostics().size(), 1u) << testing::Describe(sink);
  EXPECT_EQ(sink.Diagnostics()[0].code, "gcode-line-too-long");
  EXPECT_EQ(sink.Diagnostics()[0].location.line, 2);
  EXPECT_EQ(sink.Diagnostics()[0].location.column, 1025);
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_TRUE(blocks[1].absolute);
}

TEST(program_parser, LineAtTheLimitIsAccepted) {
  const std::string comment(1022, 'c');
  const auto blocks = ParseClean("G21 G90\n(" + comment + ")\r\n");
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[1].comment, comment);
}

// The line counter is an int: a programme longer than the limit (2e9 lines by default, here
// 4) is one error at the last line counted, and reading stops there; it never wraps.
TEST(program_parser, MoreLinesThanTheLimitStopWithOneError) {
  std::istringstream in("G21 G90\nG1 X1 F100\nG1 X2\nG1 X3\nG1 X4\nG1 X5\n");
  DiagnosticSink sink;
  ProgramReader reader(in, Dialect::Default(), "long.nc", sink, 4);
  Block block;
  int blocks = 0;
  while (reader.Next(block)) ++blocks;
  EXPECT_EQ(blocks, 4);
  ASSERT_EQ(sink.Diagnostics().size(), 1u) << testing::Describe(sink);
  EXPECT_EQ(sink.Diagnostics()[0].code, "gcode-too-many-lines");
  EXPECT_EQ(sink.Diagnostics()[0].location.line, 4);
  EXPECT_EQ(reader.LineCount(), 4);
  EXPECT_FALSE(reader.Next(block));
  EXPECT_EQ(sink.Diagnostics().size(), 1u);
}

}  // namespace
}  // namespace stitchsim::program
