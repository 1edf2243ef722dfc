// A programme's stitch points for drawing: the first move, then every line that advances the
// drive axis U (counted by hand below); a missing file and a programme without moves come back
// as the codes `stitchsim render` prints.
#include "stitchsim/run/program_overlay.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace stitchsim::run {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(ProgramOverlay, TheFirstMoveAndEveryLineThatAdvancesTheDrive) {
  // Lines: G0 (the first move: drawn), G1 Z0 (no U), three with U advancing (drawn), one
  // moving without U (not drawn), one more with U (drawn): 1 + 3 + 1 = 5 points.
  const std::string file = WriteTemp("stitchsim_overlay_test.nc",
                                     "%\n"
                                     "G21 G90\n"
                                     "T1 M6\n"
                                     "G0 X0 Y0 Z10 A0 B0 C0 U0 V0\n"
                                     "M10\n"
                                     "G1 Z0 F3000\n"
                                     "G1 X5 U5 V5\n"
                                     "G1 X10 U10 V10\n"
                                     "G1 X15 U15 V15\n"
                                     "G1 X15 Y5\n"
                                     "G1 X15 Y10 U20 V20\n"
                                     "M11\n"
                                     "M30\n"
                                     "%\n");
  DiagnosticSink sink;
  const ProgramOverlay o = ProgramStitchOverlay(file, sink);
  EXPECT_TRUE(o.status.ok) << o.status.code << ": " << o.status.message;
  EXPECT_FALSE(sink.HasErrors());
  const std::vector<Eigen::Vector3d> expected = {
      {0, 0, 10}, {5, 0, 0}, {10, 0, 0}, {15, 0, 0}, {15, 10, 0}};
  ASSERT_EQ(o.stitch_points_part_mm.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_TRUE(o.stitch_points_part_mm[i].isApprox(expected[i], 1e-9)) << i;
  }
  ASSERT_TRUE(o.first_tool_in_part_mm.has_value());
  EXPECT_TRUE(o.first_tool_in_part_mm->translation().isApprox(expected.front(), 1e-9));
  std::filesystem::remove(file);
}

TEST(ProgramOverlay, MissingFileAndNoMovesComeBackAsCodes) {
  DiagnosticSink sink;
  const ProgramOverlay missing = ProgramStitchOverlay("/nonexistent/stitchsim.nc", sink);
  EXPECT_FALSE(missing.status.ok);
  EXPECT_EQ(missing.status.code, "io-missing-file");
  const std::string file = WriteTemp("stitchsim_overlay_empty.nc", "%\nG21 G90\nT1 M6\nM30\n%\n");
  const ProgramOverlay empty = ProgramStitchOverlay(file, sink);
  EXPECT_FALSE(empty.status.ok);
  EXPECT_EQ(empty.status.code, "program-empty");
  EXPECT_EQ(empty.status.message, file + ": the programme has no moves to draw");
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace stitchsim::run
