// Fingerprints of a run's files and the machine-readable reports written as a set.
#include "stitchsim/run/reports.h"

#include <gtest/gtest.h>

#include <fstream>

#include "run_test_support.h"
#include "stitchsim/run/parts.h"

namespace stitchsim::run {
namespace {

using testing::ScratchDir;

void Write(const std::string& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

TEST(SceneFingerprints, FollowTheFilesBytes) {
  ScratchDir dir("fingerprints");
  scene::Scene scene;
  scene.file = dir.File("scene.yaml");
  scene.head.file = dir.File("head.yaml");
  Write(scene.file.string(), "name: a\n");
  Write(scene.head.file.string(), "head: b\n");
  const auto before = SceneFingerprints(scene);
  ASSERT_EQ(before.size(), 2u);  // the models not named: not fingerprinted
  EXPECT_EQ(before[0].role, "scene");
  EXPECT_EQ(before[1].role, "head spec");
  EXPECT_EQ(before[0].fnv1a, trace::Fnv1a64("name: a\n"));
  Write(scene.file.string(), "name: c\n");
  const auto after = SceneFingerprints(scene);
  EXPECT_NE(after[0].fnv1a, before[0].fnv1a);
  EXPECT_EQ(after[1].fnv1a, before[1].fnv1a);
  std::filesystem::remove(scene.head.file);
  EXPECT_EQ(SceneFingerprints(scene)[1].fnv1a, 0u);  // unreadable
  EXPECT_EQ(FileFnv(scene.head.file.string()), 0u);
}

TEST(FileFnv, IsThePartFilesHashOfTheBytes) {
  // Its offset basis is one digit short of FNV-1a's (part files have always used it):
  // 1469598103934665603 ^ 'a', times the FNV prime, mod 2^64, by hand.
  ScratchDir dir("file-fnv");
  Write(dir.File("a"), "a");
  EXPECT_EQ(FileFnv(dir.File("a")), 0x44bd8ad473cd9906ull);
  Write(dir.File("empty"), "");
  EXPECT_EQ(FileFnv(dir.File("empty")), 1469598103934665603ull);
}

TEST(SceneFingerprints, OfABundledSceneNameItsFiveFiles) {
  const LoadedScene loaded = testing::Bundled("flat_straight");
  const auto fp = SceneFingerprints(*loaded.scene);
  ASSERT_EQ(fp.size(), 5u);
  EXPECT_EQ(fp[4].role, "head MJCF");
  for (const auto& f : fp) EXPECT_NE(f.fnv1a, 0u) << f.path;
}

TEST(RunReport, CarriesTheRunsHeader) {
  scene::Scene scene;
  scene.name = "s";
  scene.head.name = "h";
  const verify::Report r = RunReport("p.nc", "s.yaml", scene, 4.5, {10, 8, 2.0, 2.5});
  EXPECT_EQ(r.program_file, "p.nc");
  EXPECT_EQ(r.scene_file, "s.yaml");
  EXPECT_EQ(r.scene_name, "s");
  EXPECT_EQ(r.head, "h");
  EXPECT_EQ(r.lines, 10);
  EXPECT_EQ(r.moves, 8);
  EXPECT_EQ(r.stitch_length_mm, 4.5);
  EXPECT_EQ(r.cycle_time_s, 2.0);
  EXPECT_EQ(r.cycle_time_timed_s, 2.5);
}

TEST(WriteReportFiles, WritesBothOrNeither) {
  ScratchDir dir("reports");
  scene::Scene scene;
  const verify::Report r = RunReport("p.nc", "s.yaml", scene, 5.0, {});
  const std::string json = dir.File("r.json"), junit = dir.File("r.xml");
  EXPECT_EQ(WriteReportFiles(r, json, junit), "");
  std::ifstream in(json, std::ios::binary);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), verify::ReportToJson(r));
  EXPECT_TRUE(std::filesystem::exists(junit));
  // The second path cannot be written: the first is not left behind either.
  const std::string json2 = dir.File("r2.json");
  EXPECT_NE(WriteReportFiles(r, json2, json + "/r2.xml"), "");  // a file as the folder
  EXPECT_FALSE(std::filesystem::exists(json2));
  EXPECT_EQ(WriteReportFiles(r, "", ""), "");  // nothing asked for
}

}  // namespace
}  // namespace stitchsim::run
