// The verify run linked directly: one small programme run serially (a saved trace makes the
// run serial), chunked on two workers with many chunks, and in two shards merged; every route
// gives the serial report byte for byte, and the saved trace rechecked gives it too.
#include "stitchsim/run/verify_run.h"

#include <gtest/gtest.h>

#include "run_test_support.h"
#include "stitchsim/run/parts.h"
#include "stitchsim/run/recheck.h"

namespace stitchsim::run {
namespace {

using testing::Bundled;
using testing::ScratchDir;

constexpr const char* kScene = "cutout_slot";

std::string ScenePath() {
  return (testing::SourceDir() / "scenes" / (std::string(kScene) + ".yaml")).string();
}

VerifyRunOptions Options(const std::string& program) {
  VerifyRunOptions o;
  o.program = program;
  o.scene = ScenePath();
  o.chunks.chunk_lines = 10;  // the programme's ~900 lines: a couple of dozen chunks
  o.chunks.warm_lines = 8;
  return o;
}

VerifyRun Verified(const VerifyRunOptions& o) {
  DiagnosticSink sink;
  VerifyRun run = RunVerification(o, Bundled(kScene), program::Dialect::Default(), nullptr, sink);
  EXPECT_EQ(run.status, RunStatus::kOk) << testing::AllDiagnostics(sink);
  return run;
}

class VerifyRunTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::PlanSmallRaster(Bundled(kScene), program_);
    VerifyRunOptions o = Options(program_);
    o.save_trace = dir_.File("run.trace");  // a saved trace: the serial run
    serial_ = Verified(o);
    ASSERT_TRUE(serial_.verifier);
    serial_json_ = verify::ReportToJson(serial_.report);
  }
  ScratchDir dir_{"verify-run"};
  std::string program_ = dir_.File("corner.nc");
  VerifyRun serial_;
  std::string serial_json_;
};

TEST_F(VerifyRunTest, SerialRunCountsEveryStitchOfTheProgramme) {
  EXPECT_EQ(serial_.chunks, 0);  // not chunked
  EXPECT_EQ(serial_.report.errors, 0);
  // 21 rows of 40 stitches (4 in at 0.1 in); the header declares them (program.stitch_count).
  EXPECT_EQ(serial_.report.stitches, 840);
  EXPECT_EQ(serial_.model->declared_stitches, std::optional<long>(840));
}

TEST_F(VerifyRunTest, ChunkedRunsGiveTheSerialReport) {
  for (int jobs : {1, 2}) {
    VerifyRunOptions o = Options(program_);
    o.chunks.jobs = jobs;
    const VerifyRun chunked = Verified(o);
    // One job and no shards: not cut (the serial order in one chunk); two: cut.
    if (jobs == 1) {
      EXPECT_EQ(chunked.chunks, 1);
    } else {
      EXPECT_GT(chunked.chunks, 5);
    }
    EXPECT_EQ(verify::ReportToJson(chunked.report), serial_json_) << "jobs " << jobs;
  }
}

TEST_F(VerifyRunTest, TwoShardsMergedGiveTheSerialReport) {
  std::vector<std::string> parts;
  std::size_t chunks_in_parts = 0;
  int chunks = 0;
  for (int shard : {2, 1}) {  // either order
    VerifyRunOptions o = Options(program_);
    o.chunks.shard = shard;
    o.chunks.shards = 2;
    o.chunks.part = dir_.File("part" + std::to_string(shard) + ".json");
    const VerifyRun run = Verified(o);
    EXPECT_EQ(run.report.rules.size(), 0u);  // a shard writes its part only
    chunks_in_parts += run.part_chunks;
    chunks = run.chunks;
    parts.push_back(o.chunks.part);
  }
  EXPECT_GT(chunks, 5);
  EXPECT_EQ(chunks_in_parts, static_cast<std::size_t>(chunks));  // each chunk in one part
  DiagnosticSink sink;
  const MergedReport merged = MergeParts(parts, scene::LoadOptions{}, sink);
  ASSERT_EQ(merged.status, RunStatus::kOk) << testing::AllDiagnostics(sink);
  EXPECT_FALSE(merged.complete);
  EXPECT_EQ(verify::ReportToJson(merged.report), serial_json_);
  // One part alone misses the other's chunks.
  DiagnosticSink one_sink;
  EXPECT_EQ(MergeParts({parts[0]}, scene::LoadOptions{}, one_sink).status, RunStatus::kBadInput);
  ASSERT_FALSE(one_sink.Diagnostics().empty());
  EXPECT_EQ(one_sink.Diagnostics().front().code, "part-missing");
}

TEST_F(VerifyRunTest, PartFileRoundTrips) {
  VerifyRunOptions o = Options(program_);
  o.chunks.shard = 1;
  o.chunks.shards = 1;
  o.chunks.part = dir_.File("whole.json");
  Verified(o);
  DiagnosticSink sink;
  Part part;
  ASSERT_TRUE(ReadPart(o.chunks.part, part, sink)) << testing::AllDiagnostics(sink);
  EXPECT_EQ(part.j["program"], program_);
  EXPECT_EQ(part.j["stitch_length_mm"].get<double>(), serial_.model->stitch_length_mm);
  EXPECT_EQ(part.j["declared_stitches"].get<long>(), 840);
  EXPECT_EQ(part.lo, 0);
  EXPECT_EQ(part.hi, part.j["chunks_total"].get<int>() - 1);
  // Its boundary states read back as they were written.
  const auto start = BoundaryState::FromHex(part.j["start"].get<std::string>());
  ASSERT_TRUE(start);
  EXPECT_EQ(start->Hex(), part.j["start"].get<std::string>());
  // The programme's fingerprint: FileFnv of its bytes.
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(FileFnv(program_)));
  EXPECT_EQ(part.j["program_fnv1a"].get<std::string>(), std::string(hex));
  // A part cut short is refused.
  const std::string text = part.j.dump();
  std::ofstream(dir_.File("cut.json"), std::ios::binary) << text.substr(0, text.size() / 2);
  DiagnosticSink cut_sink;
  Part cut;
  EXPECT_FALSE(ReadPart(dir_.File("cut.json"), cut, cut_sink));
  ASSERT_FALSE(cut_sink.Diagnostics().empty());
  EXPECT_EQ(cut_sink.Diagnostics().front().code, "part-bad");
}

TEST_F(VerifyRunTest, SavedTraceRecheckedGivesTheSerialReport) {
  RecheckRequest request;
  request.trace = dir_.File("run.trace");
  request.scene = ScenePath();
  DiagnosticSink sink;
  const RecheckResult r = RecheckTrace(request, sink);
  ASSERT_EQ(r.status, RunStatus::kOk) << testing::AllDiagnostics(sink);
  EXPECT_EQ(verify::ReportToJson(r.report), serial_json_);
  // On another scene: refused, naming both scenes.
  request.scene = (testing::SourceDir() / "scenes" / "rail_hit.yaml").string();
  DiagnosticSink other;
  EXPECT_EQ(RecheckTrace(request, other).status, RunStatus::kBadInput);
  ASSERT_FALSE(other.Diagnostics().empty());
  EXPECT_EQ(other.Diagnostics().front().code, "trace-scene-mismatch");
  EXPECT_EQ(FormatDiagnostic(other.Diagnostics().front()).rfind("stitchsim: error[", 0), 0u);
}

TEST(VerifyRun, ProgrammeForAnotherSceneIsBadInputWithItsLine) {
  ScratchDir dir("mismatch");
  testing::PlanFirstPath(Bundled("flat_straight"), dir.File("flat.nc"));
  VerifyRunOptions o = Options(dir.File("flat.nc"));
  o.scene = (testing::SourceDir() / "scenes" / "rail_hit.yaml").string();
  DiagnosticSink sink;
  const VerifyRun run =
      RunVerification(o, Bundled("rail_hit"), program::Dialect::Default(), nullptr, sink);
  EXPECT_EQ(run.status, RunStatus::kBadInput);
  ASSERT_EQ(sink.Diagnostics().size(), 1u);
  EXPECT_EQ(sink.Diagnostics().front().code, "program-scene-mismatch");
  EXPECT_EQ(sink.Diagnostics().front().location.file, dir.File("flat.nc"));
  EXPECT_GT(sink.Diagnostics().front().location.line, 0);
}

}  // namespace
}  // namespace stitchsim::run
