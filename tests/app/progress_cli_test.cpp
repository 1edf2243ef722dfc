// Progress of `plan` and `sequence` (S11, docs/ci.md): it goes to stderr only, as plain
// "<command>: ..." lines without a terminal; `--quiet` silences it; the programme written is
// byte for byte the same either way.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::ReadText;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

CliRun Cli(const std::string& args, const std::string& tag) {
  return testing::RunCli(args, "progress_" + tag);
}

// Every stderr line is a progress line of `what` (a short run may print none; `plan ply`
// names the ply after the command: "plan ply skin_45: ...").
void ExpectOnlyProgress(const std::string& err, const std::string& what) {
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    EXPECT_EQ(line.rfind(what, 0), 0u) << line;
    EXPECT_NE(line.find(": "), std::string::npos) << line;
    EXPECT_EQ(line.find('\r'), std::string::npos) << "no bar without a terminal: " << line;
  }
}

// Runs `args -o OUT` with and without --quiet: same exit, same programme, same stdout but for
// the wall time some summaries print; stderr empty when quiet, progress lines otherwise.
void ExpectQuietChangesOnlyStderr(const std::string& args, const std::string& what,
                                  const std::string& tag) {
  SCOPED_TRACE(tag);
  const fs::path loud_out = testing::ScratchDir() / (tag + "_loud.nc");
  const fs::path quiet_out = testing::ScratchDir() / (tag + "_quiet.nc");
  const CliRun loud = Cli(args + " -o " + loud_out.string(), tag + "_loud");
  const CliRun quiet = Cli(args + " -o " + quiet_out.string() + " --quiet", tag + "_quiet");
  ASSERT_EQ(loud.exit_code, 0) << loud.out << loud.err;
  ASSERT_EQ(quiet.exit_code, 0) << quiet.out << quiet.err;
  const std::string programme = ReadText(loud_out);
  EXPECT_FALSE(programme.empty());
  EXPECT_EQ(programme, ReadText(quiet_out));
  EXPECT_EQ(quiet.err, "");
  ExpectOnlyProgress(loud.err, what);
}

TEST(Progress, PlanRasterWritesTheSameProgrammeQuietOrNot) {
  // A 12 x 12 in window of the wing cover, two heads, serpentine.
  ExpectQuietChangesOnlyStderr("plan raster --scene " +
                                   (kSource / "scenes" / "wing_cover.yaml").string() +
                                   " --strategy serpentine --heads 2 --region -46,-21,-34,-9",
                               "plan raster", "raster");
}

TEST(Progress, PlanStitchAndPlyWriteTheSameProgrammeQuietOrNot) {
  ExpectQuietChangesOnlyStderr(
      "plan stitch --scene " + (kSource / "scenes" / "circle_8in.yaml").string() + " --mode auto",
      "plan stitch", "stitch");
  ExpectQuietChangesOnlyStderr("plan ply --scene " +
                                   (kSource / "scenes" / "afp_panel.yaml").string() +
                                   " --ply skin_0 --ply skin_45",
                               "plan ply", "ply");
}

TEST(Progress, SequenceWritesTheSameProgrammeQuietOrNot) {
  const fs::path panel = kSource / "scenes" / "afp_panel.yaml";
  const fs::path plies = testing::ScratchDir() / "progress_plies.nc";
  const CliRun plan = Cli("plan ply --quiet --scene " + panel.string() +
                              " --ply skin_0 --ply skin_45 -o " + plies.string(),
                          "plies");
  ASSERT_EQ(plan.exit_code, 0) << plan.out << plan.err;
  EXPECT_EQ(plan.err, "");
  ExpectQuietChangesOnlyStderr(
      "sequence " + plies.string() + " --scene " + panel.string() + " --bidirectional", "sequence",
      "sequence");
}

TEST(Progress, EveryPlanSubcommandAndSequenceTakeQuiet) {
  for (const std::string command :
       {"plan stitch", "plan afp", "plan raster", "plan ply", "sequence"}) {
    const CliRun help = Cli(command + " --help", "help");
    EXPECT_EQ(help.exit_code, 0) << command;
    EXPECT_NE(help.out.find("--quiet"), std::string::npos) << command << "\n" << help.out;
  }
}

}  // namespace
}  // namespace stitchsim::app
