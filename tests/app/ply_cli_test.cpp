// `stitchsim plan ply` (issue 12, S8): the bundled panel's plies planned and verified clean;
// a bad ply is exit 2 at its file:line with no output; an unknown ply name is exit 2; so is a
// laminate that stacks an unknown ply (issue 29).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kPanel = kSource / "scenes" / "afp_panel.yaml";

using testing::CliRun;

CliRun Cli(const std::string& args) { return testing::RunCli(args, "ply"); }

TEST(PlanPly, BundledPanelPliesPlanAndVerifyClean) {
  for (const std::string ply : {"skin_0", "skin_45"}) {
    const fs::path nc = testing::ScratchDir() / (ply + ".nc");
    const fs::path csv = testing::ScratchDir() / (ply + ".csv");
    const CliRun plan = Cli("plan ply --scene " + kPanel.string() + " --ply " + ply + " -o " +
                            nc.string() + " --tows-csv " + csv.string());
    ASSERT_EQ(plan.exit_code, 0) << plan.out << plan.err;
    EXPECT_NE(plan.out.find("courses"), std::string::npos) << plan.out;
    EXPECT_NE(plan.out.find("min steering radius"), std::string::npos) << plan.out;
    EXPECT_TRUE(fs::exists(csv));
    const CliRun verify = Cli("verify --scene " + kPanel.string() + " " + nc.string());
    EXPECT_EQ(verify.exit_code, 0) << verify.out << verify.err;
  }
}

// Done-when 1 on a STEP part: the panel's surface exported with `export-step` (in inches, so
// the reader converts) and read back through the `step` kind (same (u, v) for a CAD surface,
// so the plies' boundaries stand); both plies plan and verify clean, and the report lists the
// gap, overlap and steering figures.
TEST(PlanPly, PliesOnTheStepPartOfThePanelPlanAndVerifyClean) {
  const fs::path dir = testing::ScratchDir() / "step_panel";
  fs::create_directories(dir);
  const fs::path part = dir / "panel.step";
  const CliRun exported =
      Cli("export-step --scene " + kPanel.string() + " -o " + part.string() + " --unit inch");
  ASSERT_EQ(exported.exit_code, 0) << exported.out << exported.err;
  std::string text = testing::ReadText(kPanel);
  const std::size_t from = text.find("\nsurface:\n"), to = text.find("\npreform:");
  ASSERT_TRUE(from != std::string::npos && to != std::string::npos && from < to);
  text.replace(from + 1, to - from, "surface: {type: step, file: panel.step, face: 0}\n");
  const fs::path scene = dir / "panel_step.yaml";
  std::ofstream(scene) << text;
  for (const std::string ply : {"skin_0", "skin_45"}) {
    const fs::path nc = dir / (ply + ".nc");
    const CliRun plan =
        Cli("plan ply --scene " + scene.string() + " --ply " + ply + " -o " + nc.string());
    ASSERT_EQ(plan.exit_code, 0) << plan.out << plan.err;
    const CliRun verify = Cli("verify --scene " + scene.string() + " " + nc.string());
    EXPECT_EQ(verify.exit_code, 0) << verify.out << verify.err;
    for (const char* rule : {"afp.gap", "afp.overlap", "afp.steering_radius", "afp.coverage",
                             "afp.compaction", "collision.head_mold", "kin.reach"}) {
      EXPECT_NE(verify.out.find(rule), std::string::npos) << rule << "\n" << verify.out;
    }
  }
}

// Done-when 1 on the seed's wing: a 0 and a 45 deg ply on the upper skin of
// scenes/naca_wing.yaml plan and verify clean with every rule (afp, kinematic, collision).
// The 45 deg ply once left a bare corner (9.5 % of the ply: its offsets stopped where the
// extension of a course lost the skin near the trailing edge); afp.coverage caught it.
TEST(PlanPly, WingPliesPlanAndVerifyClean) {
  const fs::path wing = kSource / "scenes" / "naca_wing.yaml";
  for (const std::string ply : {"upper_0", "upper_45"}) {
    const fs::path nc = testing::ScratchDir() / ("wing_" + ply + ".nc");
    const CliRun plan =
        Cli("plan ply --scene " + wing.string() + " --ply " + ply + " -o " + nc.string());
    ASSERT_EQ(plan.exit_code, 0) << plan.out << plan.err;
    const CliRun verify = Cli("verify --scene " + wing.string() + " " + nc.string());
    EXPECT_EQ(verify.exit_code, 0) << verify.out << verify.err;
    EXPECT_NE(verify.out.find(ply + " bare"), std::string::npos) << verify.out;
  }
}

// `plan ply --ply skin_0` on `scene`: exit 2 with error[`code`] at `scene`:`line` on stderr,
// and `nc` not written.
CliRun ExpectPlanRefused(const fs::path& scene, const fs::path& nc, int line,
                         const std::string& code) {
  const CliRun r = Cli("plan ply --scene " + scene.string() + " --ply skin_0 -o " + nc.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(scene.string() + ":" + std::to_string(line) + ":"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("error[" + code + "]"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(nc));
  return r;
}

TEST(PlanPly, BadPlyIsExit2AtItsLineAndWritesNothing) {
  const std::string text = testing::ReadText(kPanel);
  const std::string key = "    coverage: 50";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  const int line =
      static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n')) + 1;
  const fs::path scene = testing::ScratchDir() / "bad_ply.yaml";
  std::ofstream(scene) << text.substr(0, at) << "    coverage: 30" << text.substr(at + key.size());
  const fs::path nc = testing::ScratchDir() / "bad_ply.nc";
  ExpectPlanRefused(scene, nc, line, "scene-bad-ply");
}

// A head whose minimum steering radius the panel's tows go below: a finding of the plan,
// exit 1, with the programme written (the plan is well-formed).
TEST(PlanPly, SteeringBelowTheHeadsLimitIsExit1) {
  const fs::path dir = testing::ScratchDir();
  std::string head = testing::ReadText(kSource / "models" / "heads" / "afp.yaml");
  const std::string radius = "min_steering_radius_mm: 635";
  ASSERT_NE(head.find(radius), std::string::npos);
  head.replace(head.find(radius), radius.size(), "min_steering_radius_mm: 10000000");
  const std::string mjcf = "mjcf: afp.xml";
  ASSERT_NE(head.find(mjcf), std::string::npos);
  head.replace(head.find(mjcf), mjcf.size(),
               "mjcf: " + (kSource / "models" / "heads" / "afp.xml").string());
  std::ofstream(dir / "afp_strict.yaml") << head;
  std::string scene = testing::ReadText(kPanel);
  scene.replace(scene.find("head: afp\n"), 10, "head: afp_strict.yaml\n");
  std::ofstream(dir / "strict_panel.yaml") << scene;
  const fs::path nc = dir / "strict.nc";
  const CliRun r = Cli("plan ply --scene " + (dir / "strict_panel.yaml").string() +
                       " --ply skin_45 -o " + nc.string());
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("error[ply-steering-radius]"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(nc));
}

// Issue 29, Done-when 5: a laminate that stacks a ply the scene does not define is refused
// when the scene is read: exit 2, the stack entry's file:line on stderr, nothing written.
TEST(PlanPly, LaminateWithAnUnknownPlyIsExit2AtItsLine) {
  const std::string text = testing::ReadText(kPanel);
  const std::string laminate =
      "laminates:\n  - name: skin\n    rosette: {origin: [0, 0, 100], direction: [1, 0, 0]}\n"
      "    stagger: {offset: 10, plies_before_repeat: 2}\n    stack:\n      - skin_0\n"
      "      - skin_90\n";
  const int line = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 7;
  ASSERT_EQ(text.back(), '\n');
  const fs::path scene = testing::ScratchDir() / "bad_laminate.yaml";
  std::ofstream(scene) << text << laminate;
  const fs::path nc = testing::ScratchDir() / "bad_laminate.nc";
  const CliRun r = ExpectPlanRefused(scene, nc, line, "scene-bad-laminate");
  EXPECT_NE(r.err.find("unknown ply 'skin_90'"), std::string::npos) << r.err;
}

TEST(PlanPly, UnknownPlyIsExit2) {
  const fs::path nc = testing::ScratchDir() / "none.nc";
  const CliRun r = Cli("plan ply --scene " + kPanel.string() + " --ply skin_90 -o " + nc.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("plan-unknown-ply"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("skin_0, skin_45"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(nc));
}

}  // namespace
}  // namespace stitchsim::app
