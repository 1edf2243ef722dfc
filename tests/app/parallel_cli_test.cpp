// verify --jobs N, --shard I/N and report merge (S11), as separate processes: the reports of
// a programme cut into chunks (small chunks here, so every programme is cut many times) are
// byte for byte those of one serial run; a missing, cut-short or foreign part is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

std::string Scene(const std::string& name) { return (kSource / "scenes" / name).string(); }

struct Outputs {
  int exit_code = -1;
  std::string text, json, junit, err;
};

// verify (or report merge) with its three reports.
Outputs Reports(const std::string& command, const std::string& tag) {
  const fs::path json = ScratchDir() / (tag + ".json"), xml = ScratchDir() / (tag + ".xml");
  const auto run = RunCli(command + " --report " + json.string() + " --junit " + xml.string(), tag);
  return {run.exit_code, run.out, ReadText(json), ReadText(xml), run.err};
}

void ExpectSame(const Outputs& a, const Outputs& b, const std::string& what) {
  EXPECT_EQ(a.exit_code, b.exit_code) << what << "\n" << b.err;
  EXPECT_TRUE(a.text == b.text) << what << ": text differs";
  EXPECT_TRUE(a.json == b.json) << what << ": JSON differs";
  EXPECT_TRUE(a.junit == b.junit) << what << ": JUnit differs";
}

// The programme's first `lines` lines, its seam and programme closed after them.
fs::path Window(const fs::path& nc, int lines, const std::string& tag) {
  std::ifstream in(nc);
  const fs::path out = ScratchDir() / (tag + ".nc");
  std::ofstream o(out);
  std::string line;
  for (int i = 0; i < lines && std::getline(in, line); ++i) o << line << "\n";
  o << "M11\nM30\n%\n";
  return out;
}

fs::path Plan(const std::string& args, const std::string& tag) {
  const fs::path nc = ScratchDir() / (tag + ".nc");
  const auto run = RunCli("plan " + args + " --quiet -o " + nc.string(), tag + "_plan");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return nc;
}

// Serial, --jobs 2 and 7 on small chunks, 8 shards merged: one set of reports.
void CheckAllWays(const fs::path& nc, const std::string& scene, const std::string& tag,
                  int chunk_lines) {
  const std::string verify = "verify " + nc.string() + " --scene " + scene + " -q";
  const std::string cut = " --chunk-lines " + std::to_string(chunk_lines);
  const Outputs serial = Reports(verify + " --jobs 1", tag + "_j1");
  ASSERT_LE(serial.exit_code, 1) << serial.err;
  ExpectSame(serial, Reports(verify + " --jobs 2" + cut, tag + "_j2"), tag + " --jobs 2");
  ExpectSame(serial, Reports(verify + " --jobs 7" + cut, tag + "_j7"), tag + " --jobs 7");
  // No warm-up: chunks start from the first pass's guess and run again where it was wrong.
  ExpectSame(serial, Reports(verify + " --jobs 2 --warm-lines 0" + cut, tag + "_w0"),
             tag + " --warm-lines 0");
  std::string parts;
  for (int i = 1; i <= 8; ++i) {
    const fs::path part = ScratchDir() / (tag + "_part" + std::to_string(i) + ".json");
    const auto run = RunCli(
        verify + cut + " --jobs 1 --shard " + std::to_string(i) + "/8 --part " + part.string(),
        tag + "_shard" + std::to_string(i));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    parts = part.string() + " " + parts;  // any order
  }
  ExpectSame(serial, Reports("report merge " + parts, tag + "_merged"), tag + " 8 shards");
}

TEST(ParallelVerify, StitchScenesGiveTheSerialReports) {
  const std::pair<std::string, std::string> runs[] = {
      {"circle_8in.yaml", "circle --mode coupled"},      // a6 winds through a turn
      {"circle_8in.yaml", "circle --mode decoupled"},    // a seam per stitch
      {"rs566_stringer_seam.yaml", "seam --mode auto"},  // the stringer hits
      {"cutout_slot.yaml", "cutout --mode decoupled"},
      {"rail_hit.yaml", "row --mode coupled"},  // head into the rail
      {"arcs_planar.yaml", "arc_r8 --mode auto"}};
  int k = 0;
  for (const auto& [scene, path] : runs) {
    const std::string tag = "stitch" + std::to_string(k++);
    const fs::path nc = Plan("stitch --scene " + Scene(scene) + " --path " + path, tag);
    CheckAllWays(nc, Scene(scene), tag, 20);
  }
}

// The wing's jump raster, its first `lines` lines (a seam every 754 lines).
fs::path JumpWindow(int lines) {
  static const fs::path jump =
      Plan("raster --scene " + Scene("wing_cover.yaml") + " --strategy jump", "wing_jump");
  return Window(jump, lines, "jump_window" + std::to_string(lines));
}

TEST(ParallelVerify, WingWindowsOfBothStrategiesGiveTheSerialReports) {
  CheckAllWays(JumpWindow(4000), Scene("wing_cover.yaml"), "jump", 300);
  const fs::path serp = Plan("raster --scene " + Scene("wing_cover.yaml") +
                                 " --strategy serpentine --pitch 0.5 --row-spacing 2",
                             "wing_serp");
  CheckAllWays(Window(serp, 3000, "serp_window"), Scene("wing_cover.yaml"), "serp", 250);
}

TEST(ParallelVerify, FibrePlacementIsVerifiedWhole) {
  int k = 0;
  for (const char* scene : {"afp_panel.yaml", "concave_cylinder_small.yaml"}) {
    const std::string tag = "afp" + std::to_string(k++);
    const fs::path nc = Plan("afp --scene " + Scene(scene) + " --lay-angle 45 --incline 0", tag);
    CheckAllWays(nc, Scene(scene), tag, 20);
  }
}

// Four shards of a wing window with seams (it is cut at every seam's end: each shard holds
// chunks).
std::vector<fs::path> Shards(const std::string& tag, const std::string& extra = "",
                             const fs::path& programme = JumpWindow(3000)) {
  std::vector<fs::path> parts;
  for (int i = 1; i <= 4; ++i) {
    const fs::path part = ScratchDir() / (tag + "_p" + std::to_string(i) + ".json");
    const auto run = RunCli(
        "verify " + programme.string() + " --scene " + Scene("wing_cover.yaml") + extra +
            " -q --chunk-lines 100 --shard " + std::to_string(i) + "/4 --part " + part.string(),
        tag + "_s" + std::to_string(i));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    parts.push_back(part);
  }
  return parts;
}

std::string Join(const std::vector<fs::path>& parts) {
  std::string s;
  for (const auto& p : parts) s += p.string() + " ";
  return s;
}

TEST(ReportMerge, AMissingOrCutShortPartIsNamed) {
  std::vector<fs::path> parts = Shards("missing");
  // Shard 3 of 4 never wrote its part.
  std::vector<fs::path> three = {parts[0], parts[1], parts[3]};
  const auto missing = RunCli("report merge " + Join(three), "missing_merge");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("part-missing"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("are in no part"), std::string::npos) << missing.err;
  EXPECT_TRUE(missing.out.empty()) << missing.out;
  // The last shard missing: the range up to the last chunk.
  const auto tail = RunCli("report merge " + Join({parts[0], parts[1], parts[2]}), "tail_merge");
  EXPECT_EQ(tail.exit_code, 2);
  EXPECT_NE(tail.err.find("are in no part"), std::string::npos) << tail.err;
  // A shard killed while writing: its part cut short.
  const std::string text = ReadText(parts[1]);
  std::ofstream(parts[1], std::ios::trunc) << text.substr(0, text.size() / 2);
  const auto cut = RunCli("report merge " + Join(parts), "cut_merge");
  EXPECT_EQ(cut.exit_code, 2);
  EXPECT_NE(cut.err.find(parts[1].filename().string()), std::string::npos) << cut.err;
  EXPECT_NE(cut.err.find("cut short"), std::string::npos) << cut.err;
  // A report file asked for is not written by a refused merge.
  const fs::path json = ScratchDir() / "refused.json";
  RunCli("report merge " + Join(parts) + " --report " + json.string(), "refused");
  EXPECT_FALSE(fs::exists(json));
}

// A part whose start state is not where the part before it ended (a shard that warmed up to
// another arm branch or controller speed) is refused, not merged into a wrong report.
TEST(ReportMerge, APartStartingFromAnotherStateIsRefused) {
  const std::vector<fs::path> parts = Shards("state");
  ASSERT_EQ(RunCli("report merge " + Join(parts), "state_ok").exit_code, 1);
  for (std::size_t k = 1; k < parts.size(); ++k) {
    nlohmann::json j = nlohmann::json::parse(ReadText(parts[k]));
    if (j["chunks"].is_null()) continue;
    std::string start = j["start"];
    // One hex digit of the executor's joints changed: a state that differs in one bit.
    const std::size_t digit = start.find(':') + 1;
    start[digit] = start[digit] == '0' ? '1' : '0';
    j["start"] = start;
    std::ofstream(parts[k], std::ios::trunc) << j.dump() << "\n";
    const auto run = RunCli("report merge " + Join(parts), "state_bad");
    EXPECT_EQ(run.exit_code, 2) << run.out;
    EXPECT_NE(run.err.find("part-boundary"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(parts[k].filename().string()), std::string::npos) << run.err;
    return;
  }
  FAIL() << "no part after the first holds chunks";
}

TEST(ReportMerge, PartsOfDifferentRunsAreRefused) {
  const std::vector<fs::path> a = Shards("runa");
  const std::vector<fs::path> b = Shards("runb", " --no-collision");
  const auto mixed = RunCli("report merge " + Join({a[0], a[1], b[2], a[3]}), "mixed_merge");
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_NE(mixed.err.find("part-mismatch"), std::string::npos) << mixed.err;
  // Another programme on the same scene (a longer window).
  const std::vector<fs::path> c = Shards("runc", "", JumpWindow(3100));
  const auto foreign = RunCli("report merge " + Join({a[0], a[1], c[2], a[3]}), "foreign_merge");
  EXPECT_EQ(foreign.exit_code, 2);
  EXPECT_NE(foreign.err.find("different programmes"), std::string::npos) << foreign.err;
  // The whole sets merge.
  EXPECT_EQ(RunCli("report merge " + Join(a), "whole_merge").exit_code, 1);
  EXPECT_EQ(RunCli("report merge " + Join(c), "whole_merge_c").exit_code, 1);
}

TEST(ReportMerge, ShardUsageIsChecked) {
  const fs::path nc = Plan(
      "stitch --scene " + Scene("circle_8in.yaml") + " --path circle --mode decoupled", "usage");
  const std::string verify = "verify " + nc.string() + " --scene " + Scene("circle_8in.yaml");
  for (const char* bad :
       {" --shard 0/4 --part x.json", " --shard 5/4 --part x.json", " --shard 1-4 --part x.json",
        " --shard 1/4", " --shard 1/4 --part x.json --report r.json"}) {
    const auto run = RunCli(verify + bad, "usage_bad");
    EXPECT_EQ(run.exit_code, 2) << bad;
    EXPECT_NE(run.err.find("--shard"), std::string::npos) << bad << ": " << run.err;
  }
}

}  // namespace
}  // namespace stitchsim::app
