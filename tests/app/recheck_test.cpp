// `stitchsim verify --save-trace` and `stitchsim recheck` (issue 11): a saved trace checked
// again gives verify's reports byte for byte; a tightened --limits file gives the tighter
// verdict; a bad trace file is exit 2 naming the file, never a crash.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kBinary = fs::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim";

using testing::ReadText;

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

CliResult Stitchsim(const std::string& args) {
  const fs::path out = testing::ScratchDir() / "out.txt", err = testing::ScratchDir() / "err.txt";
  const std::string cmd =
      kBinary.string() + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadText(out), ReadText(err)};
}

std::string Scene(const std::string& name) {
  return (kSource / "scenes" / (name + ".yaml")).string();
}

// A programme planned, verified with --save-trace; its reports and the trace's path.
struct Saved {
  std::string scene;
  fs::path trace, json, junit;
  CliResult verify;
};

Saved PlanAndSave(const std::string& scene, const std::string& mode) {
  const fs::path dir = testing::ScratchDir() / (scene + "_" + mode);
  fs::create_directories(dir);
  Saved s;
  s.scene = Scene(scene);
  s.trace = dir / "run.trace";
  s.json = dir / "verify.json";
  s.junit = dir / "verify.xml";
  const fs::path program = dir / "p.nc";
  const CliResult plan =
      Stitchsim("plan stitch --scene " + s.scene + " --mode " + mode + " -o " + program.string());
  EXPECT_EQ(plan.exit_code, 0) << plan.err;
  s.verify = Stitchsim("verify " + program.string() + " --scene " + s.scene + " --report " +
                       s.json.string() + " --junit " + s.junit.string() + " --save-trace " +
                       s.trace.string());
  EXPECT_TRUE(s.verify.exit_code == 0 || s.verify.exit_code == 1) << s.verify.err;
  EXPECT_TRUE(fs::is_regular_file(s.trace));
  return s;
}

// recheck's reports beside verify's: the same bytes.
void ExpectSameReports(const Saved& s) {
  const fs::path json = s.trace.parent_path() / "recheck.json";
  const fs::path junit = s.trace.parent_path() / "recheck.xml";
  const CliResult r = Stitchsim("recheck " + s.trace.string() + " --scene " + s.scene +
                                " --report " + json.string() + " --junit " + junit.string());
  EXPECT_EQ(r.exit_code, s.verify.exit_code) << r.err;
  EXPECT_EQ(r.out, s.verify.out);
  EXPECT_EQ(ReadText(json), ReadText(s.json));
  EXPECT_EQ(ReadText(junit), ReadText(s.junit));
  EXPECT_EQ(r.err, "");
}

fs::path LimitsFile(const std::string& name, const std::string& yaml) {
  const fs::path p = testing::ScratchDir() / name;
  std::ofstream(p) << yaml;
  return p;
}

TEST(Recheck, CoupledCircleGivesVerifysReportsByteForByte) {
  const Saved s = PlanAndSave("circle_8in", "coupled");
  EXPECT_EQ(s.verify.exit_code, 1);  // the coupled circle rotates the needles in the preform
  ExpectSameReports(s);
}

TEST(Recheck, RailHitWithItsCollisionFindingsGivesVerifysReportsByteForByte) {
  const Saved s = PlanAndSave("rail_hit", "decoupled");
  EXPECT_NE(s.verify.out.find("collision.robot_cell: "), std::string::npos) << s.verify.out;
  ExpectSameReports(s);
}

// A rule's entry in a JSON report.
nlohmann::json RuleOf(const nlohmann::json& report, const std::string& id) {
  for (const auto& r : report.at("rules")) {
    if (r.at("id") == id) return r;
  }
  ADD_FAILURE() << "no rule " << id;
  return nlohmann::json::object();
}

// The finding of `rule` on `line`, if there is one.
std::optional<nlohmann::json> FindingOn(const nlohmann::json& rule, int line) {
  for (const auto& f : rule.value("findings", nlohmann::json::array())) {
    if (f.at("line") == line) return f;
  }
  return std::nullopt;
}

// Tightened limits on the coupled circle: an error limit on stitch.length under its worst
// deviation, a clearance margin over its smallest clearance. The second route is a fresh
// `verify` of the same programme on a copy of the scene that carries the same limits in its
// own `limits:` block: recheck (replaying the saved trace) must give the same rules, finding
// for finding. Where the findings must be is read from the untightened report's worst
// values, not copied from a run.
TEST(Recheck, TightenedLimitsGiveTheTighterVerdictOnTheExpectedLines) {
  const Saved s = PlanAndSave("circle_8in", "coupled");
  const nlohmann::json before = nlohmann::json::parse(ReadText(s.json));
  const nlohmann::json length_before = RuleOf(before, "stitch.length");
  const nlohmann::json clearance_before = RuleOf(before, "collision.clearance");
  ASSERT_EQ(length_before.at("errors"), 0);
  ASSERT_EQ(clearance_before.at("warnings"), 0);
  const double worst_length = length_before.at("worst").at("value").get<double>();
  const double nearest = clearance_before.at("worst").at("value").get<double>();
  ASSERT_GT(worst_length, 0.0);
  // The limits as the YAML carries them (to_string's six decimals).
  const double length_limit = std::stod(std::to_string(0.8 * worst_length));
  const double margin = std::stod(std::to_string(nearest + 2.0));
  const std::string block =
      "limits:\n  stitch.length: {error_pct: " + std::to_string(length_limit) +
      "}\n  collision.clearance: {warning_mm: " + std::to_string(margin) + "}\n";
  const fs::path limits = LimitsFile("tight.yaml", block);
  const fs::path json = s.trace.parent_path() / "tight.json";
  const CliResult r = Stitchsim("recheck " + s.trace.string() + " --scene " + s.scene +
                                " --limits " + limits.string() + " --report " + json.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json after = nlohmann::json::parse(ReadText(json));

  const fs::path dir = testing::ScratchDir() / "tight_scene";
  fs::create_directories(dir);
  const fs::path scene = dir / "circle_8in.yaml";
  std::ofstream(scene) << ReadText(s.scene) << block;
  const fs::path fresh_json = dir / "fresh.json";
  const CliResult fresh =
      Stitchsim("verify " + (s.trace.parent_path() / "p.nc").string() + " --scene " +
                scene.string() + " --report " + fresh_json.string());
  EXPECT_EQ(fresh.exit_code, 1) << fresh.err;
  const nlohmann::json again = nlohmann::json::parse(ReadText(fresh_json));

  for (const char* id : {"stitch.length", "collision.clearance", "needle.side_force"}) {
    EXPECT_EQ(RuleOf(after, id), RuleOf(again, id)) << id;
  }
  EXPECT_EQ(RuleOf(after, "needle.side_force"), RuleOf(before, "needle.side_force"));
  const nlohmann::json length = RuleOf(after, "stitch.length");
  EXPECT_GT(length.at("errors").get<long>(), 0);
  const int worst_line = length_before.at("worst").at("line").get<int>();
  const auto at_worst = FindingOn(length, worst_line);
  ASSERT_TRUE(at_worst.has_value()) << "no finding on the worst line " << worst_line;
  EXPECT_EQ(at_worst->at("stitch"), length_before.at("worst").at("stitch"));
  EXPECT_EQ(at_worst->at("severity"), "error");
  EXPECT_NEAR(at_worst->at("value").get<double>(), worst_length, 1e-9);
  for (const auto& f : length.at("findings")) {
    EXPECT_GT(f.at("value").get<double>(), length_limit) << f.dump();
  }
  const nlohmann::json clearance = RuleOf(after, "collision.clearance");
  EXPECT_GT(clearance.at("warnings").get<long>(), 0);
  const auto closest = FindingOn(clearance, clearance_before.at("worst").at("line").get<int>());
  ASSERT_TRUE(closest.has_value());
  EXPECT_NEAR(closest->at("value").get<double>(), nearest, 1e-9);
  for (const auto& f : clearance.at("findings")) {
    EXPECT_LT(f.at("value").get<double>(), margin) << f.dump();
  }
}

TEST(Recheck, ATightenedLimitFailsAProgrammeVerifyPassed) {
  const Saved s = PlanAndSave("circle_8in", "decoupled");
  ASSERT_EQ(s.verify.exit_code, 0) << s.verify.out;
  const fs::path limits =
      LimitsFile("tight_length.yaml", "limits:\n  stitch.length: {error_pct: 0.005}\n");
  const CliResult r = Stitchsim("recheck " + s.trace.string() + " --scene " + s.scene +
                                " --limits " + limits.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.out.rfind("FAIL", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("stitch.length: "), std::string::npos) << r.out;
}

TEST(Recheck, ATraceOfAnotherSceneIsRefused) {
  const Saved s = PlanAndSave("rail_hit", "decoupled");
  const CliResult r = Stitchsim("recheck " + s.trace.string() + " --scene " + Scene("circle_8in"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("trace-scene-mismatch"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(s.trace.string()), std::string::npos) << r.err;
}

TEST(Recheck, ATraceWhoseSceneFileChangedIsRefused) {
  const fs::path dir = testing::ScratchDir() / "edited";
  fs::create_directories(dir);
  const fs::path scene = dir / "rail_hit.yaml";
  fs::copy_file(Scene("rail_hit"), scene, fs::copy_options::overwrite_existing);
  const fs::path program = dir / "p.nc", trace = dir / "run.trace";
  ASSERT_EQ(Stitchsim("plan stitch --scene " + scene.string() + " --mode decoupled -o " +
                      program.string())
                .exit_code,
            0);
  ASSERT_EQ(Stitchsim("verify " + program.string() + " --scene " + scene.string() +
                      " --save-trace " + trace.string())
                .exit_code,
            1);
  std::ofstream(scene, std::ios::app) << "# edited\n";
  const CliResult r = Stitchsim("recheck " + trace.string() + " --scene " + scene.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("trace-stale"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("scene"), std::string::npos) << r.err;
}

// Bad trace files: exit 2 with the file named (and, for a damaged one, the byte offset).
TEST(Recheck, BadTraceFilesAreExitTwoNamingTheFile) {
  const Saved s = PlanAndSave("rail_hit", "decoupled");
  const std::string good = ReadText(s.trace);
  ASSERT_GT(good.size(), 1000u);
  std::vector<std::pair<std::string, std::string>> bad;  // name, contents
  for (std::size_t cut : {std::size_t{0}, std::size_t{5}, std::size_t{11}, std::size_t{40},
                          std::size_t{400}, good.size() / 2, good.size() - 1}) {
    bad.emplace_back("cut" + std::to_string(cut) + ".trace", good.substr(0, cut));
  }
  std::string magic = good;
  magic[0] ^= 0x20;
  bad.emplace_back("magic.trace", magic);
  std::string version = good;
  version[8] = 99;
  bad.emplace_back("version.trace", version);
  bad.emplace_back("text.trace", "%\nG0 X0\n%\n");
  for (const auto& [name, contents] : bad) {
    const fs::path p = testing::ScratchDir() / name;
    std::ofstream(p, std::ios::binary) << contents;
    const CliResult r = Stitchsim("recheck " + p.string() + " --scene " + s.scene);
    EXPECT_EQ(r.exit_code, 2) << name << ": " << r.err;
    EXPECT_NE(r.err.find(p.string()), std::string::npos) << name << ": " << r.err;
    EXPECT_EQ(r.out, "") << name;
    if (!contents.empty()) {
      EXPECT_NE(r.err.find("byte "), std::string::npos) << name << ": " << r.err;
    }
  }
  for (const fs::path& p : {testing::ScratchDir(), testing::ScratchDir() / "missing.trace"}) {
    const CliResult r = Stitchsim("recheck " + p.string() + " --scene " + s.scene);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(p.string()), std::string::npos) << r.err;
  }
  const CliResult wrong_version = Stitchsim(
      "recheck " + (testing::ScratchDir() / "version.trace").string() + " --scene " + s.scene);
  EXPECT_NE(wrong_version.err.find("version 99"), std::string::npos) << wrong_version.err;
}

// A verify that stops on bad input leaves no trace file behind.
TEST(Recheck, NoTraceIsSavedWhenVerifyStopsOnBadInput) {
  const fs::path program = testing::ScratchDir() / "cut.nc",
                 trace = testing::ScratchDir() / "cut.trace";
  std::ofstream(program) << "%\n(STITCHSIM scene=rail_hit head=rs535)\nG21 G90\nT1 M6\n"
                            "G0 X0 Y0 Z50 A0 B0 C0\n";
  const CliResult r = Stitchsim("verify " + program.string() + " --scene " + Scene("rail_hit") +
                                " --save-trace " + trace.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(trace));
}

}  // namespace
}  // namespace stitchsim::app
