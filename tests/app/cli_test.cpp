// Units and the command line (issue 10, item 17): every length option reads one parser with
// unit suffixes and names its default unit; --help shows defaults; an unknown subcommand is
// named with the nearest one; a bare `stitchsim` prints its help.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kBinary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

using testing::ReadText;
const fs::path& Dir() { return testing::ScratchDir(); }

CliRun Cli(const std::string& args) {
  const fs::path out = Dir() / "out.txt", err = Dir() / "err.txt";
  const std::string cmd =
      kBinary.string() + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadText(out), ReadText(err)};
}

TEST(LengthText, BareNumbersTakeTheDefaultUnitSuffixesTheirOwn) {
  EXPECT_EQ(ParseLengthMm("2.5", LengthUnit::kMillimetre), 2.5);
  EXPECT_EQ(ParseLengthMm("2.5mm", LengthUnit::kInch), 2.5);
  EXPECT_EQ(ParseLengthMm("0.1", LengthUnit::kInch), 0.1 * 25.4);
  EXPECT_EQ(ParseLengthMm("0.1in", LengthUnit::kMillimetre), 0.1 * 25.4);
  EXPECT_EQ(ParseLengthMm(" 0.1 inch ", LengthUnit::kMillimetre), 0.1 * 25.4);
  EXPECT_EQ(ParseLengthMm("1e-3m", LengthUnit::kMillimetre), 1.0);
  EXPECT_EQ(ParseLengthMm("+4", LengthUnit::kMillimetre), 4.0);
  EXPECT_EQ(ParseLengthMm("-3mm", LengthUnit::kMillimetre), -3.0);
  for (const char* bad : {"", "mm", "2.5 furlongs", "2.5mmm", "nan", "inf", "1e400", "2..5", "0x10",
                          "5 mm mm", "1e308in"}) {
    EXPECT_FALSE(ParseLengthMm(bad, LengthUnit::kMillimetre).has_value()) << bad;
  }
}

// Two routes to one programme: the same length in inches and in mm plans the same bytes.
TEST(LengthOptions, SuffixedAndBareLengthsPlanTheSameProgramme) {
  const std::string raster = (kSource / "scenes" / "flat_straight.yaml").string();
  const fs::path a = Dir() / "a.nc", b = Dir() / "b.nc";
  ASSERT_EQ(Cli("plan raster --scene " + raster + " --pitch 0.2 --row-spacing 0.5 -o " + a.string())
                .exit_code,
            0);
  ASSERT_EQ(
      Cli("plan raster --scene " + raster + " --pitch 5.08mm --row-spacing 12.7mm -o " + b.string())
          .exit_code,
      0);
  EXPECT_EQ(ReadText(a), ReadText(b));
  const std::string circle = (kSource / "scenes" / "circle_8in.yaml").string();
  ASSERT_EQ(Cli("plan stitch --scene " + circle + " --stitch-length 4 -o " + a.string()).exit_code,
            0);
  ASSERT_EQ(Cli("plan stitch --scene " + circle + " --stitch-length 0.15748031496062992in -o " +
                b.string())
                .exit_code,
            0);
  EXPECT_EQ(ReadText(a), ReadText(b));
  // A length that is not one: exit 2, the option named.
  const CliRun bad =
      Cli("plan stitch --scene " + circle + " --stitch-length 5furlongs -o " + a.string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--stitch-length"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("5furlongs"), std::string::npos) << bad.err;
  EXPECT_EQ(
      Cli("plan stitch --scene " + circle + " --stitch-length -1mm -o " + a.string()).exit_code, 2);
}

TEST(Help, NamesDefaultUnitsAndDefaults) {
  const CliRun raster = Cli("plan raster --help");
  EXPECT_EQ(raster.exit_code, 0);
  for (const char* option : {"--pitch", "--row-spacing", "--margin", "--region"}) {
    const std::size_t at = raster.out.find(option);
    ASSERT_NE(at, std::string::npos) << option;
    const std::string rest = raster.out.substr(at, raster.out.find("\n  -", at + 1) - at);
    EXPECT_NE(rest.find("a bare number is in inches"), std::string::npos) << rest;
  }
  EXPECT_NE(raster.out.find("else 0.1in"), std::string::npos) << raster.out;
  EXPECT_NE(raster.out.find("jump"), std::string::npos);  // --strategy's default
  const CliRun stitch = Cli("plan stitch --help");
  EXPECT_NE(stitch.out.find("a bare number is in millimetres"), std::string::npos) << stitch.out;
  EXPECT_NE(stitch.out.find("=auto"), std::string::npos) << stitch.out;  // --mode's default
  const CliRun afp = Cli("plan afp --help");
  EXPECT_NE(afp.out.find("=5mm"), std::string::npos) << afp.out;
  const CliRun render = Cli("render --help");
  EXPECT_NE(render.out.find("=1280"), std::string::npos) << render.out;
}

TEST(Dispatch, UnknownCommandsAreNamedWithTheNearest) {
  const CliRun typo = Cli("verfy x.nc --scene s.yaml");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("unknown command 'verfy'"), std::string::npos) << typo.err;
  EXPECT_NE(typo.err.find("did you mean 'verify'?"), std::string::npos) << typo.err;
  const CliRun nested = Cli("plan rastr --scene s.yaml -o x.nc");
  EXPECT_EQ(nested.exit_code, 2);
  EXPECT_NE(nested.err.find("did you mean 'raster'?"), std::string::npos) << nested.err;
  const CliRun far = Cli("frobnicate");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
  EXPECT_NE(far.err.find("verify"), std::string::npos) << far.err;  // the commands listed
}

TEST(Dispatch, BareCommandPrintsHelp) {
  const CliRun bare = Cli("");
  EXPECT_EQ(bare.exit_code, 0);
  EXPECT_EQ(bare.err, "");
  EXPECT_NE(bare.out.find("Subcommands:"), std::string::npos) << bare.out;
  EXPECT_NE(bare.out.find("verify"), std::string::npos);
  const CliRun plan = Cli("plan");
  EXPECT_EQ(plan.exit_code, 0);
  EXPECT_NE(plan.out.find("raster"), std::string::npos) << plan.out;
  EXPECT_EQ(Cli("--help").out, bare.out);
}

// Limits (issue 11): a scene's limit override is checked against the limit table. An unknown
// rule, an unknown key or a value in the wrong unit stops `verify` with exit 2 and file:line.
TEST(Limits, BadOverridesStopVerifyWithFileAndLine) {
  const std::string flat = ReadText(kSource / "scenes" / "flat_straight.yaml");
  const int limits_line = static_cast<int>(std::count(flat.begin(), flat.end(), '\n')) + 2;
  const fs::path nc = Dir() / "flat.nc";
  ASSERT_EQ(Cli("plan stitch --scene " + (kSource / "scenes" / "flat_straight.yaml").string() +
                " -o " + nc.string())
                .exit_code,
            0);
  struct Case {
    const char* line;
    const char* code;
  };
  for (const Case& c : {Case{"  needle.sideforce: {error_mm: 0.1}", "scene-unknown-rule"},
                        Case{"  needle.side_force: {eror_mm: 0.1}", "scene-unknown-limit"},
                        Case{"  needle.side_force: {error_mm: 0.1 deg}", "scene-limit-unit"}}) {
    const fs::path scene = Dir() / "bad_limits.yaml";
    std::ofstream(scene) << flat << "limits:\n" << c.line << "\n";
    const CliRun r = Cli("verify " + nc.string() + " --scene " + scene.string());
    EXPECT_EQ(r.exit_code, 2) << c.line << "\n" << r.err;
    EXPECT_NE(r.err.find(scene.string() + ":" + std::to_string(limits_line) + ":"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(std::string("error[") + c.code + "]"), std::string::npos) << r.err;
  }
}

// Two routes to one verdict: a limit written with a unit equals the bare number in the key's
// unit (0.1 in = 2.54 mm of needle walk, less than the 3.5 mm the straight row needs).
TEST(Limits, AUnitSuffixedLimitGivesTheVerdictOfTheBareValue) {
  const std::string flat = ReadText(kSource / "scenes" / "flat_straight.yaml");
  const fs::path nc = Dir() / "flat_units.nc", scene = Dir() / "units.yaml";
  ASSERT_EQ(Cli("plan stitch --scene " + (kSource / "scenes" / "flat_straight.yaml").string() +
                " -o " + nc.string())
                .exit_code,
            0);
  std::string reports[2];
  int exits[2] = {-1, -1};
  const char* values[2] = {"0.1 in", "2.54"};
  for (int i = 0; i < 2; ++i) {
    std::ofstream(scene) << flat << "limits:\n  needle.walk: {error_mm: " << values[i] << "}\n";
    const CliRun r =
        Cli("verify " + nc.string() + " --scene " + scene.string() + " --no-collision");
    exits[i] = r.exit_code;
    reports[i] = r.out;
  }
  EXPECT_EQ(exits[0], 1) << reports[0];  // rule errors: the verdict is fail
  EXPECT_EQ(exits[1], 1) << reports[1];
  EXPECT_EQ(reports[0], reports[1]);
  EXPECT_NE(reports[0].find("2.54 mm"), std::string::npos) << reports[0];
}

}  // namespace
}  // namespace stitchsim::app
