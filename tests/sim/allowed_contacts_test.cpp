// Allowed contacts come from the head files (docs/collision.md, "Allowed contacts"): the
// bundled heads' process contacts verify clean; a head file without the needle's entry turns
// the needle in the preform into a finding; a name that is no geom of the head, or a bad
// `with`, is bad input at its file:line (exit 2). Real MuJoCo, FCL and the stitchsim binary.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sim_test_support.h"
#include "stitchsim/scene/head_spec.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/collision.h"

namespace stitchsim::sim {
namespace {

namespace fs = std::filesystem;

fs::path SourceDir() { return fs::path(STITCHSIM_SOURCE_DIR); }

fs::path TestDir() {
  const fs::path dir = fs::temp_directory_path() / "stitchsim_allowed_contacts_test";
  fs::create_directories(dir);
  return dir;
}

std::string Slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int RunCli(const std::string& args, const fs::path& out) {
  const std::string cmd = (fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim").string() + " " +
                          args + " >" + out.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// `text` with its first `from` replaced by `to` (which must be there).
std::string Replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// 1-based line of the first `what` in `text`.
int LineOf(const std::string& text, const std::string& what) {
  const auto at = text.find(what);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

// A copy of the bundled RS535 head file named `name`, `from` replaced by `to`, its MJCF named
// by absolute path; returns the copy's text.
std::string WriteRs535Copy(const std::string& name, const std::string& from,
                           const std::string& to) {
  const fs::path heads = SourceDir() / "models" / "heads";
  std::string text = Slurp(heads / "rs535.yaml");
  text = Replaced(text, "mjcf: rs535.xml", "mjcf: " + (heads / "rs535.xml").string());
  if (!from.empty()) text = Replaced(text, from, to);
  std::ofstream(TestDir() / (name + ".yaml")) << text;
  return text;
}

// flat_straight.yaml with the head `head_name` (a file in TestDir()); returns the scene file.
fs::path WriteFlatScene(const std::string& head_name) {
  const fs::path scene = TestDir() / ("flat_" + head_name + ".yaml");
  std::ofstream(scene) << Replaced(Slurp(SourceDir() / "scenes" / "flat_straight.yaml"),
                                   "head: rs535",
                                   "head: " + (TestDir() / (head_name + ".yaml")).string());
  return scene;
}

// Plans the decoupled row of `scene` and verifies it; the exit code, output in `out`.
int PlanAndVerify(const fs::path& scene, const std::string& tag, std::string& out) {
  const fs::path nc = TestDir() / (tag + ".nc");
  const fs::path log = TestDir() / (tag + ".txt");
  const int plan = RunCli(
      "plan stitch --scene " + scene.string() + " --path row --mode decoupled -o " + nc.string(),
      log);
  EXPECT_EQ(plan, 0) << Slurp(log);
  const int rc = RunCli("verify " + nc.string() + " --scene " + scene.string() + " --quiet", log);
  out = Slurp(log);
  return rc;
}

const char* const kInsertionEntry = "  - {head: needle_insertion, with: [preform, mold]}\n";

TEST(AllowedContactsTest, BundledHeadsListTheirProcessContacts) {
  DiagnosticSink sink;
  const auto rs535 = scene::LoadHeadSpec(scene::ResolveHeadFile("rs535", {}), sink);
  const auto rs566 = scene::LoadHeadSpec(scene::ResolveHeadFile("rs566", {}), sink);
  const auto afp = scene::LoadHeadSpec(scene::ResolveHeadFile("afp", {}), sink);
  ASSERT_TRUE(rs535 && rs566 && afp) << testing::FormatAll(sink);
  ASSERT_EQ(rs535->allowed_contacts.size(), 3u);
  EXPECT_EQ(rs535->allowed_contacts[0].head, "needle_insertion");
  EXPECT_TRUE(rs535->allowed_contacts[0].preform && rs535->allowed_contacts[0].mold);
  EXPECT_EQ(rs535->allowed_contacts[2].head, "presser_foot");
  EXPECT_TRUE(rs535->allowed_contacts[2].preform);
  EXPECT_FALSE(rs535->allowed_contacts[2].mold);
  EXPECT_EQ(rs535->allowed_contacts[2].where.line,
            LineOf(Slurp(rs535->file), "{head: presser_foot"));
  EXPECT_EQ(rs566->allowed_contacts.size(), 4u);
  ASSERT_EQ(afp->allowed_contacts.size(), 1u);
  EXPECT_EQ(afp->allowed_contacts[0].head, "roller");
}

TEST(AllowedContactsTest, PatternsMatchWholeNamesWithStars) {
  scene::AllowedContact c;
  c.head = "needle_*";
  EXPECT_TRUE(c.Matches("needle_catcher"));
  EXPECT_TRUE(c.Matches("needle_"));
  EXPECT_FALSE(c.Matches("needle"));
  EXPECT_FALSE(c.Matches("a_needle_catcher"));
  c.head = "*arm*";
  EXPECT_TRUE(c.Matches("cframe_lower_arm"));
  EXPECT_TRUE(c.Matches("arm"));
  EXPECT_FALSE(c.Matches("head_body"));
  c.head = "needle";
  EXPECT_TRUE(c.Matches("needle"));
  EXPECT_FALSE(c.Matches("needle_bar"));
  c.head = "n*d*e";
  EXPECT_TRUE(c.Matches("needle"));
  EXPECT_FALSE(c.Matches("needles"));
}

// The control: the copy with every entry verifies the row clean, so the finding below comes
// from the removed entry alone.
TEST(AllowedContactsTest, RemovingTheNeedleEntryMakesTheNeedleInThePreformAFinding) {
  WriteRs535Copy("rs535_all", "", "");
  std::string clean;
  EXPECT_EQ(PlanAndVerify(WriteFlatScene("rs535_all"), "all", clean), 0) << clean;
  EXPECT_EQ(clean.rfind("PASS", 0), 0u) << clean;

  WriteRs535Copy("rs535_no_insertion", kInsertionEntry, "");
  std::string out;
  EXPECT_EQ(PlanAndVerify(WriteFlatScene("rs535_no_insertion"), "no_insertion", out), 1) << out;
  EXPECT_NE(out.find("collision.head_mold"), std::string::npos) << out;
  EXPECT_NE(out.find("head:needle_insertion hits preform"), std::string::npos) << out;
  EXPECT_EQ(out.find("head:needle_catcher"), std::string::npos) << out;
}

// A pattern that names no geom of the head's MJCF: CollisionWorld::Create reports it at the
// entry's line of the head file, and `verify` exits 2.
TEST(AllowedContactsTest, UnknownHeadGeomIsBadInputAtItsLine) {
  const std::string text =
      WriteRs535Copy("rs535_typo", "{head: needle_insertion,", "{head: needle_insertoin,");
  const fs::path head = TestDir() / "rs535_typo.yaml";
  const fs::path scene = WriteFlatScene("rs535_typo");
  DiagnosticSink sink;
  const auto s = scene::LoadScene(scene, sink);
  ASSERT_TRUE(s) << testing::FormatAll(sink);
  const auto robot = LoadRobotModel(s->cell_urdf, sink);
  ASSERT_TRUE(robot) << testing::FormatAll(sink);
  EXPECT_EQ(CollisionWorld::Create(*s, *robot, sink), nullptr);
  ASSERT_EQ(sink.Diagnostics().size(), 1u) << testing::FormatAll(sink);
  const Diagnostic& d = sink.Diagnostics().front();
  EXPECT_EQ(d.code, "head-unknown-body");
  EXPECT_EQ(d.location.file, head.string());
  EXPECT_EQ(d.location.line, LineOf(text, "{head: needle_insertoin"));
  EXPECT_NE(d.message.find("'needle_insertoin'"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("needle_catcher"), std::string::npos) << d.message;

  // The CLI: exit 2 with file:line.
  const fs::path nc = TestDir() / "typo.nc";
  std::ofstream(nc) << "%\nG21 G90\nT1 M6\nG0 X-300 Y0 Z0 A0 B0 C-90 U0 V0\nM30\n%\n";
  const fs::path log = TestDir() / "typo.txt";
  EXPECT_EQ(RunCli("verify " + nc.string() + " --scene " + scene.string() + " --quiet", log), 2)
      << Slurp(log);
  const std::string where =
      head.string() + ":" + std::to_string(LineOf(text, "{head: needle_insertoin")) + ":";
  EXPECT_NE(Slurp(log).find(where), std::string::npos) << Slurp(log);
  EXPECT_NE(Slurp(log).find("head-unknown-body"), std::string::npos) << Slurp(log);
}

TEST(AllowedContactsTest, BadEntriesAreHeadErrorsAtTheirLine) {
  struct Case {
    std::string to, code, at;
  };
  for (const Case& c :
       {Case{"  - {head: presser_foot, with: laminate}\n", "head-bad-value",
             "{head: presser_foot, with: laminate}"},
        Case{"  - {head: presser_foot, with: []}\n", "head-bad-value",
             "{head: presser_foot, with: []}"},
        Case{"  - {head: presser_foot}\n", "head-missing-key", "{head: presser_foot}"},
        Case{"  - {head: presser_foot, with: preform, by: hand}\n", "head-unknown-key",
             "{head: presser_foot, with: preform, by: hand}"},
        Case{"  - presser_foot\n", "head-type", "  - presser_foot\n"}}) {
    const std::string text =
        WriteRs535Copy("rs535_bad", "  - {head: presser_foot, with: preform}\n", c.to);
    DiagnosticSink sink;
    EXPECT_FALSE(scene::LoadHeadSpec(TestDir() / "rs535_bad.yaml", sink)) << c.to;
    ASSERT_TRUE(sink.HasErrors()) << c.to;
    const Diagnostic& d = sink.Diagnostics().front();
    EXPECT_EQ(d.code, c.code) << c.to << testing::FormatAll(sink);
    EXPECT_EQ(d.location.line, LineOf(text, c.at)) << c.to << testing::FormatAll(sink);
  }
}

}  // namespace
}  // namespace stitchsim::sim
