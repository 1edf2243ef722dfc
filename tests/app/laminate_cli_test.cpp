// `stitchsim plan laminate` (issue 29): the bundled panel's two plies stacked as a laminate
// plan into one programme whose header names the laminate, with a line per ply; an unknown
// laminate, a scene without laminates, a stagger a course cannot hold and an output that
// cannot be written are exit 2 with the message (and the scene's file:line where there is one),
// nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;

const fs::path kPanel = fs::path(STITCHSIM_SOURCE_DIR) / "scenes" / "afp_panel.yaml";

using testing::CliRun;

CliRun Cli(const std::string& args) { return testing::RunCli(args, "laminate"); }

// The panel with a laminate `skin` of its two plies, stagger `stagger`; `line` is set to the
// laminate's line.
fs::path PanelWithLaminate(const std::string& stagger, const std::string& file, int& line) {
  const std::string text = testing::ReadText(kPanel);
  line = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 2;
  const fs::path scene = testing::ScratchDir() / file;
  std::ofstream(scene) << text
                       << "laminates:\n  - name: skin\n    rosette: {origin: [0, 0, 100], "
                          "direction: [1, 0, 0]}\n    stagger: "
                       << stagger << "\n    stack:\n      - skin_0\n      - skin_45\n";
  return scene;
}

// `r` is exit 2 with error[`code`] on stderr, and `nc` was not written.
void ExpectRefused(const CliRun& r, const std::string& code, const fs::path& nc) {
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("error[" + code + "]"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(nc));
}

TEST(PlanLaminate, PanelLaminatePlansIntoOneProgramme) {
  int line = 0;
  const fs::path scene =
      PanelWithLaminate("{offset: 10, plies_before_repeat: 1}", "lam.yaml", line);
  const fs::path nc = testing::ScratchDir() / "lam.nc";
  const fs::path csv = testing::ScratchDir() / "lam.csv";
  const CliRun r = Cli("plan laminate --scene " + scene.string() + " --laminate skin -o " +
                       nc.string() + " --tows-csv " + csv.string() + " --jobs 2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("ply 1 'skin_0'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ply 2 'skin_45'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("laminate 'skin' of 2 plies"), std::string::npos) << r.out;
  const std::string programme = testing::ReadText(nc);
  EXPECT_NE(programme.find("laminate=skin"), std::string::npos);
  EXPECT_NE(programme.find("plies=skin_0,skin_45"), std::string::npos);
  EXPECT_EQ(testing::ReadText(csv).rfind("stack,course,tow,segment,", 0), 0u);
}

TEST(PlanLaminate, UnknownLaminateIsExit2) {
  int line = 0;
  const fs::path scene = PanelWithLaminate("{offset: 10, plies_before_repeat: 1}", "u.yaml", line);
  const fs::path nc = testing::ScratchDir() / "unknown.nc";
  const CliRun r =
      Cli("plan laminate --scene " + scene.string() + " --laminate wing -o " + nc.string());
  ExpectRefused(r, "plan-unknown-laminate", nc);
  EXPECT_NE(r.err.find(scene.string() + ":1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no laminate 'wing' (laminates: skin)"), std::string::npos) << r.err;
}

TEST(PlanLaminate, SceneWithoutLaminatesIsExit2) {
  const fs::path nc = testing::ScratchDir() / "none.nc";
  const CliRun r =
      Cli("plan laminate --scene " + kPanel.string() + " --laminate skin -o " + nc.string());
  ExpectRefused(r, "plan-unknown-laminate", nc);
  EXPECT_NE(r.err.find("(laminates: none"), std::string::npos) << r.err;
}

TEST(PlanLaminate, AStaggerTheCourseCannotHoldIsExit2AtTheLaminate) {
  // Two seam positions (plies_before_repeat 1) in a 101.6 mm course are 50.8 mm apart.
  int line = 0;
  const fs::path scene = PanelWithLaminate("{offset: 60, plies_before_repeat: 1}", "s.yaml", line);
  // skin_0 and skin_45 differ in angle: no ply repeats an angle, nothing to stagger.
  const fs::path nc = testing::ScratchDir() / "stagger.nc";
  CliRun r = Cli("plan laminate --scene " + scene.string() + " --laminate skin -o " + nc.string() +
                 " --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  std::string text = testing::ReadText(scene);
  text += "      - skin_0\n";
  std::ofstream(scene) << text;
  fs::remove(nc);
  r = Cli("plan laminate --scene " + scene.string() + " --laminate skin -o " + nc.string() +
          " --quiet");
  ExpectRefused(r, "plan-laminate-stagger", nc);
  EXPECT_NE(r.err.find(scene.string() + ":" + std::to_string(line) + ":"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("50.8 mm apart"), std::string::npos) << r.err;
}

TEST(PlanLaminate, AnOutputThatCannotBeWrittenIsExit2) {
  int line = 0;
  const fs::path scene = PanelWithLaminate("{offset: 10, plies_before_repeat: 1}", "w.yaml", line);
  const fs::path nc = scene / "lam.nc";  // under a file: no folder can be made there
  const CliRun r = Cli("plan laminate --scene " + scene.string() + " --laminate skin -o " +
                       nc.string() + " --quiet");
  ExpectRefused(r, "io-write", nc);
}

}  // namespace
}  // namespace stitchsim::app
