// `stitchsim verify` on programmes that do not fit what they claim (issue S6 items 3, 4, 11):
// cut short, written for another scene or head, piped in. Through the CLI, as CI runs it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kBinary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";

struct CliRun {
  int exit = -1;
  std::string output;  // stdout and stderr
};

CliRun Cli(const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "cli.out";
  const std::string cmd =
      "cd " + dir.string() + " && " + kBinary.string() + " " + args + " >" + out.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(out);
  std::ostringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  return r;
}

std::vector<std::string> Lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

void Write(const fs::path& file, const std::vector<std::string>& lines) {
  std::ofstream out(file);
  for (const auto& l : lines) out << l << "\n";
}

class VerifyInput : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per case under this build (ctest runs cases in parallel; other checkouts'
    // builds on the same machine do not share it).
    dir_ = fs::path(STITCHSIM_BINARY_DIR) / "verify_input_test" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    scene_ = (kSource / "scenes/flat_straight.yaml").string();
    ASSERT_EQ(Cli("plan stitch --scene " + scene_ + " --mode decoupled -o prog.nc", dir_).exit, 0);
    lines_ = Lines(dir_ / "prog.nc");
    ASSERT_GT(lines_.size(), 200u);
  }
  fs::path dir_;
  std::string scene_;
  std::vector<std::string> lines_;
};

// Item 3: cut at line 60 with the '%' lines dropped, the programme still parses; it must not
// pass. The error names the last line read.
TEST_F(VerifyInput, ProgrammeCutShortIsAnErrorAtItsLastLine) {
  std::vector<std::string> cut;
  for (std::size_t i = 0; i < 60; ++i) {
    if (lines_[i] != "%") cut.push_back(lines_[i]);
  }
  Write(dir_ / "cut.nc", cut);
  const CliRun r = Cli("verify cut.nc --scene " + scene_, dir_);
  EXPECT_EQ(r.exit, 2) << r.output;
  EXPECT_NE(
      r.output.find("cut.nc:" + std::to_string(cut.size()) + ":1: error[exec-missing-program-end]"),
      std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("PASS"), std::string::npos);
}

// Item 3: with its opening '%' kept, the missing closing '%' is reported where the text
// stops, not at 1:1.
TEST_F(VerifyInput, MissingClosingPercentPointsAtTheEnd) {
  ASSERT_EQ(lines_.front(), "%");
  Write(dir_ / "cut.nc", std::vector<std::string>(lines_.begin(), lines_.begin() + 60));
  const CliRun r = Cli("verify cut.nc --scene " + scene_, dir_);
  EXPECT_EQ(r.exit, 2) << r.output;
  EXPECT_NE(r.output.find("cut.nc:60:1: error[gcode-missing-end]"), std::string::npos) << r.output;
}

// Item 3: a cut programme given its end again (M30) runs, but makes fewer stitches than its
// header declares: a finding on the last motion line.
TEST_F(VerifyInput, FewerStitchesThanDeclaredIsAFinding) {
  std::vector<std::string> cut(lines_.begin(), lines_.begin() + 60);
  cut.push_back("M11");
  cut.push_back("M30");
  cut.push_back("%");
  Write(dir_ / "cut.nc", cut);
  const CliRun r = Cli("verify cut.nc --scene " + scene_ + " --report r.json", dir_);
  EXPECT_EQ(r.exit, 1) << r.output;
  std::ifstream json_in(dir_ / "r.json");
  const nlohmann::json report = nlohmann::json::parse(json_in);
  // The header says 120 stitches; lines 7..60 hold 27 decoupled stitches (a translation and a
  // rotation line each) after the start line: the last motion line is 60.
  const nlohmann::json* finding = nullptr;
  for (const auto& rule : report["rules"]) {
    if (rule["id"] == "program.stitch_count" && rule["findings"].size() == 1) {
      finding = &rule["findings"][0];
    }
  }
  ASSERT_NE(finding, nullptr) << report.dump(1).substr(0, 4000);
  EXPECT_EQ((*finding)["line"], 60);
  EXPECT_EQ((*finding)["value"], 27.0);
  EXPECT_EQ((*finding)["limit"], 120.0);
  EXPECT_EQ((*finding)["severity"], "error");

  // The whole programme makes what it declares; a header claiming one more does not.
  std::vector<std::string> more = lines_;
  for (auto& l : more) {
    const auto at = l.find("stitches=120");
    if (at != std::string::npos) l.replace(at, 12, "stitches=121");
  }
  Write(dir_ / "more.nc", more);
  EXPECT_EQ(Cli("verify prog.nc --scene " + scene_, dir_).exit, 0);
  EXPECT_EQ(Cli("verify more.nc --scene " + scene_, dir_).exit, 1);
}

// Item 4: a programme for another scene, or another head, is bad input naming both, unless
// overridden on purpose.
TEST_F(VerifyInput, ProgrammeForAnotherSceneOrHeadIsRefused) {
  const std::string circle = (kSource / "scenes/circle_8in.yaml").string();
  ASSERT_EQ(Cli("plan stitch --scene " + circle + " -o circle.nc", dir_).exit, 0);
  CliRun r = Cli("verify circle.nc --scene " + scene_, dir_);
  EXPECT_EQ(r.exit, 2) << r.output;
  EXPECT_NE(r.output.find("error[program-scene-mismatch]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'circle_8in'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'flat_straight'"), std::string::npos) << r.output;
  r = Cli("verify circle.nc --allow-mismatch --scene " + scene_, dir_);
  EXPECT_NE(r.exit, 2) << r.output;

  // T2 M6 mounts the RS566 on the RS535 scene; the header says rs566 too.
  std::vector<std::string> rs566 = lines_;
  for (auto& l : rs566) {
    if (l == "T1 M6") l = "T2 M6";
  }
  Write(dir_ / "t2.nc", rs566);
  r = Cli("verify t2.nc --scene " + scene_, dir_);
  EXPECT_EQ(r.exit, 2) << r.output;
  EXPECT_NE(r.output.find("t2.nc:4:1: error[exec-head-mismatch]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'rs566'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'rs535'"), std::string::npos) << r.output;
  for (auto& l : rs566) {
    const auto at = l.find("head=rs535");
    if (at != std::string::npos) l.replace(at, 10, "head=rs566");
  }
  Write(dir_ / "t2h.nc", rs566);
  r = Cli("verify t2h.nc --scene " + scene_, dir_);
  EXPECT_EQ(r.exit, 2) << r.output;
  EXPECT_NE(r.output.find("t2h.nc:2:1: error[program-head-mismatch]"), std::string::npos)
      << r.output;

  // An AFP programme (T3) is not run as an RS535 one.
  const std::string afp = (kSource / "scenes/afp_concave_cylinder.yaml").string();
  ASSERT_EQ(Cli("plan afp --scene " + afp + " --lay-angle 45 --incline 10 -o afp.nc", dir_).exit,
            0);
  std::vector<std::string> afp_lines = Lines(dir_ / "afp.nc");
  for (auto& l : afp_lines) {  // keep only the tool change to show the T3 check alone
    if (l.rfind("(STITCHSIM", 0) == 0) l = "(an AFP programme without its header)";
  }
  Write(dir_ / "afp_bare.nc", afp_lines);
  r = Cli("verify afp_bare.nc --scene " + scene_, dir_);
  EXPECT_EQ(r.exit, 2) << r.output;
  EXPECT_NE(r.output.find("error[exec-head-mismatch]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'afp'"), std::string::npos) << r.output;
}

// Item 3/4: header values that are not numbers are bad input at their line.
TEST_F(VerifyInput, MalformedHeaderValueIsBadInputAtItsLine) {
  std::vector<std::string> bad = lines_;
  for (auto& l : bad) {
    const auto at = l.find("stitches=120");
    if (at != std::string::npos) l.replace(at, 12, "stitches=many");
  }
  Write(dir_ / "bad.nc", bad);
  const CliRun r = Cli("verify bad.nc --scene " + scene_, dir_);
  EXPECT_EQ(r.exit, 2) << r.output;
  EXPECT_NE(r.output.find("bad.nc:2:1: error[gcode-bad-header]"), std::string::npos) << r.output;
}

// Item 11: the programme is read once, so a pipe verifies exactly like the file.
TEST_F(VerifyInput, PipedProgrammeVerifiesLikeTheFile) {
  const CliRun file = Cli("verify prog.nc --scene " + scene_ + " --report file.json", dir_);
  const CliRun piped =
      Cli("verify /dev/stdin --scene " + scene_ + " --report pipe.json < prog.nc", dir_);
  EXPECT_EQ(file.exit, 0) << file.output;
  EXPECT_EQ(piped.exit, 0) << piped.output;
  const std::string piped_cmd = "cat prog.nc | " + kBinary.string() +
                                " verify /dev/stdin --scene " + scene_ +
                                " --report cat.json > cat.out 2>&1";
  ASSERT_EQ(std::system(("cd " + dir_.string() + " && " + piped_cmd).c_str()), 0)
      << Lines(dir_ / "cat.out").size();
  // Only the programme's name differs.
  auto body = [&](const char* name) {
    std::ifstream in(dir_ / name);
    nlohmann::json j = nlohmann::json::parse(in);
    j.erase("program");
    return j.dump(1);
  };
  EXPECT_EQ(body("file.json"), body("cat.json"));
  EXPECT_EQ(body("file.json"), body("pipe.json"));
}

}  // namespace
