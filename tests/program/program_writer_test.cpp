// Writer tests: canonical text, number formatting, and the round trip parse(write(p)) == p.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "program_test_util.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {
namespace {

std::string WriteOne(const Block& block, const Dialect& dialect = Dialect::Default()) {
  std::ostringstream out;
  {
    ProgramWriter writer(out, dialect);
    writer.Write(block);
  }
  return out.str();
}

TEST(program_writer, CanonicalWordOrderAndSpacing) {
  Block b;
  b.comment = "stitch 1";
  b.m_codes = {10, 100};
  b.tool = 1;
  b.feed = 3000.0;
  b[Axis::kDrive] = 5.0;
  b[Axis::kPathLength] = 5.0;
  b[Axis::kC] = -2.818;
  b[Axis::kX] = 12.5;
  b[Axis::kRail] = 2500.25;
  b[Axis::kRotator] = 90.0;
  b.motion = Motion::kFeed;
  b.absolute = true;
  b.units = LengthUnit::kMillimetre;
  b.block_number = 7;
  EXPECT_EQ(WriteOne(b),
            "N7 G21 G90 G1 X12.5 C-2.818 U5 V5 E2500.25 W90 F3000 T1 M10 M100 (stitch 1)\n");
}

TEST(program_writer, NumbersUseDialectDecimalsTrimmedAndNoNegativeZero) {
  const auto x = [](double v) {
    Block b;
    b[Axis::kX] = v;
    return WriteOne(b);
  };
  EXPECT_EQ(x(12.5), "X12.5\n");
  EXPECT_EQ(x(3.0), "X3\n");
  EXPECT_EQ(x(-0.0), "X0\n");
  EXPECT_EQ(x(-1e-7), "X0\n");
  EXPECT_EQ(x(0.1234567), "X0.123457\n");
  EXPECT_EQ(x(-0.000001), "X-0.000001\n");
  EXPECT_EQ(x(999999999.999999), "X999999999.999999\n");
  EXPECT_EQ(x(-1e9), "X-1000000000\n");
  EXPECT_EQ(x(100.0), "X100\n");
  Block f;
  f.feed = 1234.56789;
  EXPECT_EQ(WriteOne(f), "F1234.568\n");
}

TEST(program_writer, CommentStyles) {
  Block b;
  b.comment = "needle (cooling)";
  EXPECT_EQ(WriteOne(b), "; needle (cooling)\n");
  b.comment = "plain; text";
  EXPECT_EQ(WriteOne(b), "(plain; text)\n");
  b.comment.clear();
  EXPECT_EQ(WriteOne(b), "");  // nothing to write
}

TEST(program_writer, MarksHeaderAndParam) {
  ProgramHeader header;
  header.entries = {{"scene", "circle_8in"}, {"head", "rs535"}, {"stitch_length_mm", "5.000000"}};
  Block section;
  section.m_codes = {60};
  section.param = 2;
  const std::string text =
      WriteProgramString(std::vector<Block>{section}, Dialect::Default(), header);
  EXPECT_EQ(text,
            "%\n(STITCHSIM scene=circle_8in head=rs535 stitch_length_mm=5.000000)\nM60 P2\n%\n");
  DiagnosticSink sink;
  ProgramHeader parsed;
  const auto blocks = ParseString(text, Dialect::Default(), "w.nc", sink, &parsed);
  EXPECT_TRUE(sink.Diagnostics().empty()) << testing::Describe(sink);
  EXPECT_EQ(parsed, header);
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[1], section);
}

// Random blocks with values on the dialect's decimal grid: writing then parsing gives them back.
TEST(program_writer, RoundTripOfRandomBlocks) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> value(-5000.0, 5000.0);
  std::uniform_int_distribution<int> coin(0, 3);
  std::vector<Block> blocks;
  for (int i = 0; i < 2000; ++i) {
    Block b;
    for (std::size_t a = 0; a < kAxisCount; ++a) {
      if (coin(rng) == 0) continue;
      b.axes[a] = std::round(value(rng) * 1e6) / 1e6;
    }
    if (coin(rng) == 0) b.feed = (std::round(std::fabs(value(rng)) * 1e3) + 1000.0) / 1e3;
    if (coin(rng) == 0) b.motion = coin(rng) < 2 ? Motion::kRapid : Motion::kFeed;
    if (coin(rng) == 0) b.block_number = i;
    if (coin(rng) == 0) b.m_codes = {100 + coin(rng)};
    if (coin(rng) == 0) b.comment = "note " + std::to_string(i);
    if (i == 0) b.units = LengthUnit::kMillimetre;
    blocks.push_back(b);
  }
  const std::string text = WriteProgramString(blocks, Dialect::Default());
  DiagnosticSink sink;
  const auto parsed = ParseString(text, Dialect::Default(), "rt.nc", sink);
  EXPECT_TRUE(sink.Diagnostics().empty()) << testing::Describe(sink);
  std::vector<Block> expected;
  for (const Block& b : blocks) {
    if (b.HasWords() || !b.comment.empty()) expected.push_back(b);
  }
  ASSERT_EQ(parsed.size(), expected.size());
  for (std::size_t i = 0; i < parsed.size(); ++i) ASSERT_EQ(parsed[i], expected[i]) << i;
  // Writing is idempotent on parsed programmes.
  EXPECT_EQ(WriteProgramString(parsed, Dialect::Default()), text);
}

TEST(program_writer, LargeOutputIsFlushedInOrder) {
  std::ostringstream out;
  {
    ProgramWriter writer(out, Dialect::Default());
    Block b;
    for (int i = 0; i < 100000; ++i) {
      b[Axis::kDrive] = i;
      writer.Write(b);
    }
    EXPECT_EQ(writer.LinesWritten(), 100000u);
  }
  std::istringstream in(out.str());
  std::string line;
  int i = 0;
  while (std::getline(in, line)) ASSERT_EQ(line, "U" + std::to_string(i++));
  EXPECT_EQ(i, 100000);
}

}  // namespace
}  // namespace stitchsim::program
