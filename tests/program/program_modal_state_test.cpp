// Modal state tests: unit conversion, carry forward, feed, tools, M-code state, and the
// semantic errors the tracker reports.

#include <gtest/gtest.h>

#include <sstream>

#include "program_test_util.h"
#include "stitchsim/program/modal_state.h"

namespace stitchsim::program {
namespace {

using testing::Describe;

struct Tracked {
  DiagnosticSink sink;
  std::vector<MachineState> states;  // after each block
  std::vector<Step> steps;
};

void Track(std::string_view text, Tracked& t) {
  const auto blocks = ParseString(text, Dialect::Default(), "m.nc", t.sink);
  ModalState modal(Dialect::Default(), "m.nc", t.sink);
  for (const Block& block : blocks) {
    t.steps.push_back(modal.Update(block));
    t.states.push_back(modal.State());
  }
}

TEST(program_modal_state, InchesBecomeMillimetresAnglesStayDegrees) {
  Tracked t;
  Track("G20 G90 G1 X1 Y-2 Z0.5 A10 B20 C30 U0.2 V0.2 E100 W45 F10\n", t);
  ASSERT_TRUE(t.sink.Diagnostics().empty()) << Describe(t.sink);
  const MachineState& s = t.states.back();
  EXPECT_EQ(s.units, LengthUnit::kInch);
  EXPECT_DOUBLE_EQ(*s[Axis::kX], 25.4);
  EXPECT_DOUBLE_EQ(*s[Axis::kY], -50.8);
  EXPECT_DOUBLE_EQ(*s[Axis::kZ], 12.7);
  EXPECT_DOUBLE_EQ(*s[Axis::kDrive], 5.08);
  EXPECT_DOUBLE_EQ(*s[Axis::kPathLength], 5.08);
  EXPECT_DOUBLE_EQ(*s[Axis::kRail], 2540.0);
  EXPECT_EQ(*s[Axis::kA], 10.0);
  EXPECT_EQ(*s[Axis::kB], 20.0);
  EXPECT_EQ(*s[Axis::kC], 30.0);
  EXPECT_EQ(*s[Axis::kRotator], 45.0);
  EXPECT_DOUBLE_EQ(*s.feed_mm_per_min, 254.0);
}

TEST(program_modal_state, UnitsAreModalAndApplyToTheirOwnBlock) {
  Tracked t;
  Track("G0 X1\nG20 X1\nX2 F5\nG21 X3\n", t);
  ASSERT_TRUE(t.sink.Diagnostics().empty()) << Describe(t.sink);
  EXPECT_DOUBLE_EQ(*t.states[0][Axis::kX], 1.0);  // default mm
  EXPECT_DOUBLE_EQ(*t.states[1][Axis::kX], 25.4);
  EXPECT_DOUBLE_EQ(*t.states[2][Axis::kX], 50.8);
  EXPECT_DOUBLE_EQ(*t.states[2].feed_mm_per_min, 127.0);
  EXPECT_DOUBLE_EQ(*t.states[3][Axis::kX], 3.0);
  // Feed keeps its mm/min value when the units change.
  EXPECT_DOUBLE_EQ(*t.states[3].feed_mm_per_min, 127.0);
}

TEST(program_modal_state, CarriesForwardAxesMotionAndFeed) {
  Tracked t;
  Track("G1 X1 Y2 F100\nZ3\nG0 A5\nX4\n", t);
  ASSERT_TRUE(t.sink.Diagnostics().empty()) << Describe(t.sink);
  const MachineState& s = t.states[1];
  EXPECT_EQ(s[Axis::kX], 1.0);
  EXPECT_EQ(s[Axis::kY], 2.0);
  EXPECT_EQ(s[Axis::kZ], 3.0);
  EXPECT_FALSE(s[Axis::kA].has_value());  // unknown until set
  EXPECT_EQ(s.motion, Motion::kFeed);
  EXPECT_EQ(s.feed_mm_per_min, 100.0);
  EXPECT_EQ(t.steps[1].motion, Motion::kFeed);
  EXPECT_TRUE(t.steps[1].is_move);
  EXPECT_EQ(t.steps[3].motion, Motion::kRapid);
  EXPECT_EQ(t.states[3][Axis::kA], 5.0);
  EXPECT_EQ(t.states[3][Axis::kX], 4.0);
}

TEST(program_modal_state, PreviousIsTheStateBeforeTheBlock) {
  DiagnosticSink sink;
  const auto blocks = ParseString("G1 X1 F100\nX2\n", Dialect::Default(), "m.nc", sink);
  ModalState modal(Dialect::Default(), "m.nc", sink);
  modal.Update(blocks[0]);
  modal.Update(blocks[1]);
  EXPECT_EQ(modal.Previous()[Axis::kX], 1.0);
  EXPECT_EQ(modal.State()[Axis::kX], 2.0);
  EXPECT_FALSE(modal.AnglesRad().has_value());
}

TEST(program_modal_state, ToolsStitchingRetractSectionsMacrosAndEnd) {
  Tracked t;
  Track(
      "T2\nM6\nM10 M100\nM20\nM21 M11\nM60 P3 M150 M199\nT1 M6 M30\n(comment after end is fine)\n",
      t);
  ASSERT_TRUE(t.sink.Diagnostics().empty()) << Describe(t.sink);
  EXPECT_EQ(t.states[0].selected_tool, 2);
  EXPECT_FALSE(t.states[0].active_tool.has_value());
  EXPECT_EQ(t.states[1].active_tool, 2);
  EXPECT_TRUE(t.steps[1].tool_changed);
  EXPECT_TRUE(t.states[2].stitching);
  EXPECT_EQ(t.steps[2].user_macros, (std::vector<int>{100}));
  EXPECT_TRUE(t.states[3].head_retracted);
  EXPECT_FALSE(t.states[4].head_retracted);
  EXPECT_FALSE(t.states[4].stitching);
  EXPECT_EQ(t.steps[5].head_section, 3);
  EXPECT_EQ(t.states[5].head_section, 3);
  EXPECT_EQ(t.steps[5].user_macros, (std::vector<int>{150, 199}));
  EXPECT_EQ(t.states[6].active_tool, 1);
  EXPECT_TRUE(t.steps[6].program_end);
  EXPECT_TRUE(t.states[6].program_ended);
}

TEST(program_modal_state, SemanticErrorsPointAtTheWord) {
  const auto expect = [](std::string_view text, const char* code, int line, int column) {
    const Diagnostic d = testing::FirstError(text);
    EXPECT_EQ(d.code, code) << text;
    EXPECT_EQ(d.location.line, line) << text;
    EXPECT_EQ(d.location.column, column) << text;
  };
  expect("G21\n  X1\n", "gcode-no-motion-mode", 2, 3);
  expect("G21 G1 M10 Y1\n", "gcode-missing-feed", 1, 12);
  expect("G21 M6\n", "gcode-missing-tool", 1, 5);
  expect("M30\n N5 G0 X1\n", "gcode-code-after-program-end", 2, 2);
}

TEST(program_modal_state, AnglesInRadians) {
  DiagnosticSink sink;
  const auto blocks = ParseString("G0 A90 B-45 C180\n", Dialect::Default(), "m.nc", sink);
  ModalState modal(Dialect::Default(), "m.nc", sink);
  modal.Update(blocks[0]);
  const auto angles = modal.AnglesRad();
  ASSERT_TRUE(angles.has_value());
  EXPECT_DOUBLE_EQ((*angles)[0], kPi / 2);
  EXPECT_DOUBLE_EQ((*angles)[1], -kPi / 4);
  EXPECT_DOUBLE_EQ((*angles)[2], kPi);
}

TEST(program_modal_state, CheckProgramSummarisesAGoodFile) {
  std::istringstream in(
      "(STITCHSIM scene=s head=rs535)\n%\nG21 G90\nT1 M6\nG0 X0 Y0 Z0\nG1 X5 F100\nM30\n%\n");
  DiagnosticSink sink;
  const CheckSummary summary = CheckProgram(in, Dialect::Default(), "c.nc", sink);
  EXPECT_TRUE(summary.ok) << Describe(sink);
  EXPECT_EQ(summary.lines, 8);
  EXPECT_EQ(summary.blocks, 6u);
  EXPECT_EQ(summary.moves, 2u);
  EXPECT_EQ(summary.header.Find("head"), "rs535");
}

// AFP structure (docs/program-format.md, "Fibre placement"): the tow mask, ply and course
// are modal and applied before the block's move.
TEST(program_modal_state, TowCodesSetAndClearTheMaskBeforeTheMove) {
  Tracked t;
  Track("G21 G90 T3 M6\nM70 P2\nM71 P5\nM62 P0 G1 X1 F100\nM63 P16\nM63 P1 X2\nM62 P16\n"
        "M72\nM63 P0\n",
        t);
  ASSERT_TRUE(t.sink.Diagnostics().empty()) << Describe(t.sink);
  EXPECT_EQ(t.states[0].ply, 0);
  EXPECT_EQ(t.states[1].ply, 2);
  EXPECT_EQ(t.states[2].course, 5);
  EXPECT_EQ(t.states[3].tows, ~std::uint64_t{0});
  EXPECT_TRUE(t.steps[3].tows_changed);
  EXPECT_TRUE(t.steps[3].is_move);
  EXPECT_EQ(t.states[4].tows, ~std::uint64_t{0} & ~(std::uint64_t{1} << 15));
  EXPECT_EQ(t.states[5].tows, ~std::uint64_t{0} & ~(std::uint64_t{1} << 15) & ~std::uint64_t{1});
  EXPECT_EQ(t.states[6].tows, ~std::uint64_t{0} & ~std::uint64_t{1});
  EXPECT_EQ(t.states[7].course, 0);
  EXPECT_EQ(t.states[7].ply, 2);
  EXPECT_EQ(t.states[8].tows, 0u);
  EXPECT_FALSE(t.steps[7].tows_changed);
}

TEST(program_modal_state, AfpStructureErrorsNameTheirLine) {
  const struct {
    const char* text;
    const char* code;
    int line;
  } cases[] = {
      {"M71 P1\nM71 P2\n", "gcode-afp-structure", 2},
      {"M72\n", "gcode-afp-structure", 1},
      {"M71 P1\nM70 P1\n", "gcode-afp-structure", 2},
      {"M62 P65\n", "gcode-missing-parameter", 1},
      {"M62\n", "gcode-missing-parameter", 1},
      {"M70 P0\n", "gcode-missing-parameter", 1},
      {"M62 M63 P1\n", "gcode-conflicting-modes", 1},
      {"M62 M71 P1\n", "gcode-conflicting-modes", 1},
      {"M71 M72 P1\n", "gcode-conflicting-modes", 1},
      {"G0 X1 P1\n", "gcode-unexpected-parameter", 1},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    Tracked t;
    Track(c.text, t);
    ASSERT_TRUE(t.sink.HasErrors());
    EXPECT_EQ(t.sink.Diagnostics().front().code, c.code) << Describe(t.sink);
    EXPECT_EQ(t.sink.Diagnostics().front().location.line, c.line) << Describe(t.sink);
  }
}

}  // namespace
}  // namespace stitchsim::program
