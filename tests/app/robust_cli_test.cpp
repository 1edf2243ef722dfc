// Inputs that must not break the command line (issue 10 items 7, 8, 9, 12): directories,
// FIFOs and devices as inputs; paths out of the scene's folder; tiny inputs that ask for huge
// work; outputs that are links, devices, or named twice. Each run is bounded by `timeout`
// (a hang fails as exit 124) and, outside sanitizer builds, by a 4 GB address-space limit.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kBinary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

std::string Slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct CliRun {
  int exit_code = -1;  // -1: killed by a signal
  std::string out, err;
};

class RobustCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("stitchsim_robust_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // `stitchsim <args>` through the shell (args are shell words), within `seconds`.
  CliRun Cli(const std::string& args, int seconds = 60) {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    std::string cmd = kSanitized ? "" : "ulimit -v 4000000; ";
    cmd += "timeout " + std::to_string(seconds) + " " + kBinary.string() + " " + args + " >" +
           out.string() + " 2>" + err.string();
    const int status = std::system(("sh -c '" + cmd + "'").c_str());
    CliRun r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = Slurp(out);
    r.err = Slurp(err);
    fs::remove(out);
    fs::remove(err);
    return r;
  }

  fs::path Write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  // flat_straight with `from` replaced by `to` (same line count), written into the folder.
  fs::path FlatScene(const std::string& from = "", const std::string& to = "") {
    std::string text = Slurp(kSource / "scenes" / "flat_straight.yaml");
    if (!from.empty()) text.replace(text.find(from), from.size(), to);
    return Write("flat.yaml", text);
  }

  fs::path dir_;
};

std::string Describe(const CliRun& r) {
  return "exit " + std::to_string(r.exit_code) + "\n--- stdout\n" + r.out + "--- stderr\n" + r.err;
}

// ---- item 7 ---------------------------------------------------------------------------------

TEST_F(RobustCli, ADirectoryAsSceneOrProgrammeIsBadInputNotACrash) {
  fs::create_directories(dir_ / "scene.yaml");
  fs::create_directories(dir_ / "prog.nc");
  const fs::path flat = kSource / "scenes" / "flat_straight.yaml";
  CliRun r = Cli("plan stitch --scene " + (dir_ / "scene.yaml").string() + " -o " +
                 (dir_ / "o.nc").string());
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_NE(r.err.find("scene-not-a-file"), std::string::npos) << Describe(r);
  r = Cli("verify " + (dir_ / "prog.nc").string() + " --scene " + flat.string());
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_NE(r.err.find("directory"), std::string::npos) << Describe(r);
  EXPECT_EQ(r.err.find("empty"), std::string::npos) << Describe(r);
}

TEST_F(RobustCli, AFifoAsSceneDoesNotHang) {
  ASSERT_EQ(::mkfifo((dir_ / "scene.yaml").c_str(), 0600), 0);
  const CliRun r = Cli(
      "plan stitch --scene " + (dir_ / "scene.yaml").string() + " -o " + (dir_ / "o.nc").string(),
      20);
  EXPECT_EQ(r.exit_code, 2) << Describe(r);  // 124: hung in open()
  EXPECT_NE(r.err.find("FIFO"), std::string::npos) << Describe(r);
}

// ---- item 8 ---------------------------------------------------------------------------------

TEST_F(RobustCli, AnStlOutsideTheSceneFolderIsRefusedUnlessAllowed) {
  Write("outside/plate.stl",
        "solid p\nfacet normal 0 0 1\nouter loop\nvertex -500 -400 0\nvertex 500 -400 0\n"
        "vertex 500 400 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
        "vertex -500 -400 0\nvertex 500 400 0\nvertex -500 400 0\nendloop\nendfacet\n"
        "endsolid p\n");
  const std::string plane = "  type: plane\n  size: [1000, 600]\n";
  std::string text = Slurp(kSource / "scenes" / "flat_straight.yaml");
  text.replace(text.find(plane), plane.size(), "  type: mesh\n  file: ../outside/plate.stl\n");
  const fs::path scene = Write("scene/s.yaml", text);
  const std::string args =
      "plan stitch --scene " + scene.string() + " -o " + (dir_ / "o.nc").string();
  CliRun r = Cli(args);
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_NE(r.err.find(scene.string() + ":11:"), std::string::npos) << Describe(r);
  EXPECT_NE(r.err.find("scene-path-outside"), std::string::npos) << Describe(r);
  EXPECT_FALSE(fs::exists(dir_ / "o.nc"));
  r = Cli(args + " --allow-outside-paths");
  EXPECT_EQ(r.exit_code, 0) << Describe(r);
  EXPECT_TRUE(fs::exists(dir_ / "o.nc"));
}

// ---- item 9 ---------------------------------------------------------------------------------

TEST_F(RobustCli, ATinyStitchLengthIsRefusedUpFront) {
  const fs::path scene = FlatScene("nominal_length: 5", "nominal_length: 0.000001");
  const CliRun r = Cli("plan stitch --scene " + scene.string() + " -o " + (dir_ / "o.nc").string());
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_NE(r.err.find("scene-too-many-stitches"), std::string::npos) << Describe(r);
  EXPECT_NE(r.err.find(scene.string() + ":19:"), std::string::npos) << Describe(r);
  EXPECT_FALSE(fs::exists(dir_ / "o.nc"));
}

// A line whose sampling would exceed the executor's bound is a finding on that line.
TEST_F(RobustCli, ALineBeyondTheSamplingBoundIsAFindingNotAnAllocation) {
  const std::string head = "%\nG21 G90\nT1 M6\nG0 X0 Y0 Z0 A0 B0 C-90 U0 V0\nM10\n";
  struct Case {
    std::string name, line;
  };
  for (const Case& c : {Case{"huge_u", "G1 X-295 U999999999 V5 F1500"},
                        Case{"huge_move", "G0 X1000000000 Y0 Z0"}}) {
    SCOPED_TRACE(c.name);
    const fs::path prog = Write(c.name + ".nc", head + c.line + "\nM30\n%\n");
    const fs::path report = dir_ / (c.name + ".json");
    const CliRun r =
        Cli("verify " + prog.string() + " --no-collision --scene " +
            (kSource / "scenes" / "flat_straight.yaml").string() + " --report " + report.string());
    ASSERT_EQ(r.exit_code, 1) << Describe(r);
    const auto j = nlohmann::json::parse(Slurp(report));
    bool found = false;
    for (const auto& rule : j.at("rules")) {
      if (rule.at("id") != "program.line_sampling") continue;
      ASSERT_FALSE(rule.at("findings").empty());
      EXPECT_EQ(rule.at("findings")[0].at("line"), 6);
      found = true;
    }
    EXPECT_TRUE(found) << Slurp(report);
  }
}

// ---- item 12 ---------------------------------------------------------------------------------

TEST_F(RobustCli, TheSameFileForTwoReportsIsRefusedBeforeAnythingRuns) {
  const fs::path prog = Write("p.nc", "%\nG21 G90\nT1 M6\nG0 X0 Y0 Z0 A0 B0 C-90 U0 V0\nM30\n%\n");
  const fs::path same = dir_ / "r.out";
  const CliRun r = Cli("verify " + prog.string() + " --scene " +
                       (kSource / "scenes" / "flat_straight.yaml").string() + " --report " +
                       same.string() + " --junit " + (dir_ / "." / "r.out").string());
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_NE(r.err.find("io-same-output"), std::string::npos) << Describe(r);
  EXPECT_FALSE(fs::exists(same));
}

TEST_F(RobustCli, APlantedTemporaryLinkIsNeverWrittenThrough) {
  const fs::path victim = Write("victim.txt", "keep me\n");
  const fs::path out = dir_ / "o.nc";
  fs::create_symlink(victim, dir_ / "o.nc.tmp");
  const CliRun r = Cli("plan raster --scene " + (kSource / "scenes" / "wing_cover.yaml").string() +
                       " --region 0,0,10,10 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << Describe(r);
  EXPECT_EQ(Slurp(victim), "keep me\n");
  EXPECT_NE(Slurp(out).find("G1"), std::string::npos);
  // Nothing else was left in the folder: the output, the victim and the planted link.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) {
    (void)e;
    ++entries;
  }
  EXPECT_EQ(entries, 3);
}

// A symlink to a regular file replaces that file and stays a link; a directory is refused.
TEST_F(RobustCli, AnOutputLinkIsFollowedAndADirectoryRefused) {
  const fs::path real = Write("real.nc", "old\n");
  fs::create_symlink(real, dir_ / "link.nc");
  const std::string plan =
      "plan stitch --scene " + (kSource / "scenes" / "flat_straight.yaml").string() + " -o ";
  CliRun r = Cli(plan + (dir_ / "link.nc").string());
  ASSERT_EQ(r.exit_code, 0) << Describe(r);
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.nc"));
  EXPECT_NE(Slurp(real).find("M30"), std::string::npos);
  fs::create_directories(dir_ / "adir.nc");
  r = Cli(plan + (dir_ / "adir.nc").string());
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_NE(r.err.find("io-write"), std::string::npos) << Describe(r);
  EXPECT_TRUE(fs::is_directory(dir_ / "adir.nc"));
}

// A FIFO (like /dev/stdout on a pipe) is written through, never replaced by a renamed file.
TEST_F(RobustCli, AnOutputThatIsAFifoIsWrittenThroughNotReplaced) {
  const fs::path fifo = dir_ / "fifo.nc", copy = dir_ / "copy.nc";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string cmd = "timeout 60 cat " + fifo.string() + " > " + copy.string() +
                          " & timeout 60 " + kBinary.string() + " plan stitch --scene " +
                          (kSource / "scenes" / "flat_straight.yaml").string() + " -o " +
                          fifo.string() + " >/dev/null 2>&1; wait";
  ASSERT_EQ(std::system(("sh -c '" + cmd + "'").c_str()), 0);
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
  const std::string text = Slurp(copy);
  EXPECT_NE(text.find("G1"), std::string::npos) << text;
  EXPECT_NE(text.find("M30"), std::string::npos) << text;
}

TEST_F(RobustCli, AnInterruptedPlanLeavesNoTemporaryBehind) {
  const fs::path out = dir_ / "o.nc";
  const std::string cmd = kBinary.string() + " plan raster --scene " +
                          (kSource / "scenes" / "wing_cover.yaml").string() + " -o " +
                          out.string() + " >/dev/null 2>&1 & pid=$!; sleep 0.5; kill -TERM $pid; " +
                          "wait $pid; echo $? > " + (dir_ / "rc").string();
  ASSERT_EQ(std::system(("sh -c '" + cmd + "'").c_str()), 0);
  const std::string rc = Slurp(dir_ / "rc");
  fs::remove(dir_ / "rc");
  if (rc == "0\n") GTEST_SKIP() << "the plan finished within a second";
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir_)) ADD_FAILURE() << "left behind: " << e.path();
}

}  // namespace
