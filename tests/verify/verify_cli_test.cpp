// `stitchsim verify` as CI uses it: exit codes, JSON and JUnit that standard tools read,
// byte-identical reports, reports written whole or not at all, predictable snapshots.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kBinary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";

int RunCli(const std::string& args, const fs::path& stdout_file = "/dev/null") {
  const std::string cmd = kBinary.string() + " " + args + " >" + stdout_file.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int Python(const std::string& code, const fs::path& file) {
  const fs::path script = file.string() + ".check.py";
  std::ofstream(script) << code;
  const std::string cmd = "python3 " + script.string() + " " + file.string();
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string Slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class VerifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // ctest runs each case as its own process, in parallel: one folder per case.
    dir_ = fs::temp_directory_path() /
           ("stitchsim_verify_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    scene_ = (kSource / "scenes/circle_8in.yaml").string();
    ASSERT_EQ(RunCli("plan stitch --scene " + scene_ + " --mode coupled -o " +
                     (dir_ / "coupled.nc").string()),
              0);
    ASSERT_EQ(RunCli("plan stitch --scene " + scene_ + " --mode decoupled -o " +
                     (dir_ / "decoupled.nc").string()),
              0);
  }
  fs::path dir_;
  std::string scene_;
};

TEST_F(VerifyCli, ExitCodesPassFailAndBadInput) {
  EXPECT_EQ(RunCli("verify " + (dir_ / "decoupled.nc").string() + " --scene " + scene_), 0);
  EXPECT_EQ(RunCli("verify " + (dir_ / "coupled.nc").string() + " --scene " + scene_), 1);
  EXPECT_EQ(RunCli("verify " + (dir_ / "missing.nc").string() + " --scene " + scene_), 2);
  std::ofstream(dir_ / "nan.nc") << "%\nG21 G90\nG0 X0 Y0 Z0 A0 B0 C0 U0 V0\nG1 Xnan U5 V5 F1\n%\n";
  EXPECT_EQ(RunCli("verify " + (dir_ / "nan.nc").string() + " --scene " + scene_), 2);
  std::ofstream(dir_ / "empty.nc") << "%\nG21 G90\nT1 M6\nM30\n%\n";
  EXPECT_EQ(RunCli("verify " + (dir_ / "empty.nc").string() + " --scene " + scene_), 1);
}

TEST_F(VerifyCli, ReportsParseWithStandardToolsAndAreByteIdentical) {
  const fs::path json1 = dir_ / "r1.json", json2 = dir_ / "r2.json";
  const fs::path xml1 = dir_ / "j1.xml", xml2 = dir_ / "j2.xml";
  const fs::path out1 = dir_ / "o1.txt", out2 = dir_ / "o2.txt";
  const std::string prog = (dir_ / "coupled.nc").string();
  ASSERT_EQ(RunCli("verify " + prog + " --scene " + scene_ + " --report " + json1.string() +
                       " --junit " + xml1.string(),
                   out1),
            1);
  ASSERT_EQ(RunCli("verify " + prog + " --scene " + scene_ + " --report " + json2.string() +
                       " --junit " + xml2.string(),
                   out2),
            1);
  EXPECT_EQ(Slurp(json1), Slurp(json2));
  EXPECT_EQ(Slurp(xml1), Slurp(xml2));
  EXPECT_EQ(Slurp(out1), Slurp(out2));
  EXPECT_EQ(Python(R"(import json, sys
r = json.load(open(sys.argv[1]))
assert r["verdict"] == "fail", r["verdict"]
rules = {x["id"]: x for x in r["rules"]}
assert rules["needle.side_force"]["errors"] > 0
assert rules["needle.rotation_in_preform"]["errors"] > 0
f = rules["needle.side_force"]["findings"][0]
for k in ("rule", "severity", "line", "stitch", "value", "limit", "unit", "message"):
    assert k in f, k
assert f["line"] > 0 and f["unit"] == "mm"
assert r["counts"]["stitches"] == 255
)",
                   json1),
            0);
  EXPECT_EQ(Python(R"(import sys, xml.etree.ElementTree as E
root = E.parse(sys.argv[1]).getroot()
assert root.tag == "testsuites"
suites = root.findall("testsuite")
assert len(suites) == 1
cases = suites[0].findall("testcase")
names = [c.get("name") for c in cases]
assert "needle.side_force" in names and "kin.reach" in names
failed = [c.get("name") for c in cases if c.find("failure") is not None]
assert "needle.side_force" in failed and "needle.rotation_in_preform" in failed
assert "kin.reach" not in failed
assert int(suites[0].get("failures")) == len(failed)
assert "line " in cases[names.index("needle.side_force")].find("failure").text
)",
                   xml1),
            0);
}

TEST_F(VerifyCli, BadInputWritesNoReport) {
  const fs::path json = dir_ / "bad.json";
  std::ofstream(dir_ / "bad.nc") << "%\nG21 G90\nG0 X0 Y0 Z0 A0 B0 C0 U0 V0\nG1 Q5\n%\n";
  EXPECT_EQ(RunCli("verify " + (dir_ / "bad.nc").string() + " --scene " + scene_ + " --report " +
                   json.string()),
            2);
  EXPECT_FALSE(fs::exists(json));
  // Reports are a set: when the JUnit file cannot be written, the JSON is not left behind.
  EXPECT_EQ(RunCli("verify " + (dir_ / "decoupled.nc").string() + " --scene " + scene_ +
                   " --report " + json.string() + " --junit /proc/stitchsim_nowhere/j.xml"),
            2);
  EXPECT_FALSE(fs::exists(json));
}

TEST_F(VerifyCli, SnapshotsHavePredictableNames) {
  const fs::path snaps = dir_ / "snaps";
  ASSERT_EQ(RunCli("verify " + (dir_ / "coupled.nc").string() + " --scene " + scene_ +
                   " --snapshots " + snaps.string()),
            1);
  EXPECT_TRUE(fs::exists(snaps / "overview.png"));
  EXPECT_TRUE(fs::exists(snaps / "needle.side_force.png"));
  EXPECT_TRUE(fs::exists(snaps / "needle.rotation_in_preform.png"));
  EXPECT_FALSE(fs::exists(snaps / "kin.reach.png"));  // only failing rules get a close-up
  EXPECT_GT(fs::file_size(snaps / "overview.png"), 10000u);
}

// A site's post-processor: drive on D, path length on L, Euler order ZYX. The same dialect
// file drives the planner and the verifier, and the text really uses it.
TEST_F(VerifyCli, CustomDialectPlansAndVerifies) {
  const fs::path dialect = dir_ / "site.yaml";
  std::ofstream(dialect) << "name: site\nletters:\n  drive: \"D\"\n  path_length: \"L\"\n"
                            "euler_order: \"ZYX\"\n";
  const fs::path prog = dir_ / "site.nc";
  ASSERT_EQ(RunCli("plan stitch --scene " + scene_ + " --mode decoupled --dialect " +
                   dialect.string() + " -o " + prog.string()),
            0);
  const std::string text = Slurp(prog);
  EXPECT_NE(text.find(" D5.006"), std::string::npos);
  EXPECT_NE(text.find(" L5.006"), std::string::npos);
  EXPECT_EQ(text.find(" U5.006"), std::string::npos);
  EXPECT_EQ(
      RunCli("verify " + prog.string() + " --scene " + scene_ + " --dialect " + dialect.string()),
      0);
  // Read with the default dialect, D and L are unknown words: bad input, exit 2.
  EXPECT_EQ(RunCli("verify " + prog.string() + " --scene " + scene_), 2);
  std::ofstream(dir_ / "broken.yaml") << "letters: [X, Y\n";
  EXPECT_EQ(RunCli("verify " + prog.string() + " --scene " + scene_ + " --dialect " +
                   (dir_ / "broken.yaml").string()),
            2);
}

// Item 15: --no-collision is visible: the headline names the skipped rules, the JSON lists
// them, JUnit marks them <skipped/>. Without the flag the same three ids are rules that ran.
TEST_F(VerifyCli, SkippedRulesAreNamedInEveryReport) {
  const std::string prog = (dir_ / "decoupled.nc").string();
  const fs::path json = dir_ / "s.json", xml = dir_ / "s.xml", out = dir_ / "s.txt";
  ASSERT_EQ(RunCli("verify " + prog + " --scene " + scene_ + " --no-collision --report " +
                       json.string() + " --junit " + xml.string(),
                   out),
            0);
  const std::string text = Slurp(out);
  EXPECT_NE(text.substr(0, text.find('\n'))
                .find(" 3 skipped (--no-collision: collision.head_mold, collision.robot_cell, "
                      "collision.clearance)"),
            std::string::npos)
      << text;
  EXPECT_EQ(Python(R"(import json, sys
r = json.load(open(sys.argv[1]))
ids = ["collision.head_mold", "collision.robot_cell", "collision.clearance"]
assert [s["id"] for s in r["skipped_rules"]] == ids, r["skipped_rules"]
assert all(s["reason"] == "--no-collision" for s in r["skipped_rules"])
assert not set(ids) & {x["id"] for x in r["rules"]}
)",
                   json),
            0);
  EXPECT_EQ(Python(R"(import sys, xml.etree.ElementTree as E
suite = E.parse(sys.argv[1]).getroot().find("testsuite")
skipped = [c.get("name") for c in suite.findall("testcase") if c.find("skipped") is not None]
assert skipped == ["collision.head_mold", "collision.robot_cell", "collision.clearance"], skipped
assert suite.get("skipped") == "3"
assert int(suite.get("tests")) == len(suite.findall("testcase"))
)",
                   xml),
            0);
  const fs::path full = dir_ / "full.json";
  ASSERT_EQ(RunCli("verify " + prog + " --scene " + scene_ + " --report " + full.string()), 0);
  EXPECT_EQ(Python(R"(import json, sys
r = json.load(open(sys.argv[1]))
assert r["skipped_rules"] == []
ids = [x["id"] for x in r["rules"]]
assert [i for i in ids if i.startswith("collision.")] == [
    "collision.head_mold", "collision.robot_cell", "collision.clearance"], ids
)",
                   full),
            0);
}

// Item 16: JUnit names what was checked: programme, scene, head and the tool version (the
// CMake project version) as testsuite properties, and the programme in the suite name, so
// two programmes' reports merged in one CI view stay apart.
TEST_F(VerifyCli, JunitNamesProgrammeSceneHeadAndVersion) {
  const std::string cmake = Slurp(kSource / "CMakeLists.txt");
  const std::string tag = "project(stitchsim VERSION ";
  ASSERT_NE(cmake.find(tag), std::string::npos);
  const std::size_t at = cmake.find(tag) + tag.size();
  const std::string version = cmake.substr(at, cmake.find(' ', at) - at);
  const fs::path version_out = dir_ / "version.txt";
  ASSERT_EQ(RunCli("--version", version_out), 0);
  EXPECT_EQ(Slurp(version_out), "stitchsim " + version + "\n");
  for (const char* name : {"coupled", "decoupled"}) {
    const fs::path xml = dir_ / (std::string(name) + ".xml");
    const std::string prog = (dir_ / (std::string(name) + ".nc")).string();
    RunCli("verify " + prog + " --scene " + scene_ + " --junit " + xml.string());
    std::ofstream(dir_ / "expect.txt") << prog << "\n" << scene_ << "\n" << version << "\n";
    EXPECT_EQ(Python(R"(import sys, os, xml.etree.ElementTree as E
prog, scene_file, version = open(os.path.join(os.path.dirname(sys.argv[1]), "expect.txt")).read().split("\n")[:3]
suite = E.parse(sys.argv[1]).getroot().find("testsuite")
props = {p.get("name"): p.get("value") for p in suite.find("properties").findall("property")}
assert props == {"program": prog, "scene": "circle_8in", "scene_file": scene_file,
                 "head": "rs535", "stitchsim_version": version}, props
name = suite.get("name")
assert name.startswith("stitchsim.circle_8in.") and name.endswith(os.path.basename(prog).replace(".", "_")), name
assert all(c.get("classname") == name for c in suite.findall("testcase"))
)",
                     xml),
              0)
        << name;
  }
}

}  // namespace
