// The ordered merge of chunk results: a chunk whose start differs from where the chunk before
// it ended is sent back (kRerun) from that chunk's warm start, and one that matches is taken;
// boundary states survive their text form.
#include <gtest/gtest.h>

#include "run_test_support.h"
#include "stitchsim/run/chunked.h"

namespace stitchsim::run {
namespace {

BoundaryState State(const std::string& executor, const std::string& output) {
  BoundaryState b;
  b.input.executor = executor;
  b.input.timing = "t";
  b.output = output;
  return b;
}

ChunkResult Result(const RunModel& model, int index, BoundaryState start, BoundaryState end) {
  ChunkResult r;
  r.chunk.index = index;
  r.chunk.first_line = 10 * index + 1;
  r.chunk.end_line = 10 * index + 11;
  r.chunk.warm.reader.bytes = 100u * static_cast<unsigned>(index);
  r.start = std::move(start);
  r.end = std::move(end);
  r.verifier = std::make_unique<verify::Verifier>(model.Rules(), false);
  r.timed.Add(0.25 * (index + 1));
  r.lines = 10;
  r.ok = true;
  return r;
}

class ChunkMergerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    DiagnosticSink sink;
    RunOptions options;
    options.no_collision = true;
    model_ = MakeRunModel(testing::Bundled("flat_straight"), program::Dialect::Default(), 5.0,
                          std::nullopt, options, sink);
    ASSERT_TRUE(model_) << testing::AllDiagnostics(sink);
  }
  std::unique_ptr<RunModel> model_;
};

TEST_F(ChunkMergerTest, PlantedBoundaryDifferenceIsRunAgainFromTheChunkBeforesStart) {
  ChunkMerger merger;
  EXPECT_EQ(merger.Add(Result(*model_, 0, State("a", ""), State("b", "v1"))),
            ChunkMerger::Outcome::kTaken);
  // Chunk 1 rebuilt another controller state in its warm-up ("v2" where chunk 0 ended "v1").
  ChunkResult planted = Result(*model_, 1, State("b", "v2"), State("c", "v3"));
  const sim::Chunk as_planned = planted.chunk;
  EXPECT_EQ(merger.Add(std::move(planted)), ChunkMerger::Outcome::kRerun);
  EXPECT_EQ(merger.Taken(), 1);
  EXPECT_NE(merger.FirstMismatch().find("chunk 1 at line 11"), std::string::npos)
      << merger.FirstMismatch();
  EXPECT_NE(merger.FirstMismatch().find("the controller's speed or the verifier's state"),
            std::string::npos);
  // The re-run: chunk 1's lines, warmed up from chunk 0's start.
  const sim::Chunk rerun = merger.Rerun(as_planned);
  EXPECT_EQ(rerun.first_line, 11);
  EXPECT_EQ(rerun.warm.reader.bytes, 0u);
  // Run again it starts where chunk 0 ended: taken, its time added to chunk 0's.
  EXPECT_EQ(merger.Add(Result(*model_, 1, State("b", "v1"), State("c", "v3"))),
            ChunkMerger::Outcome::kTaken);
  EXPECT_EQ(merger.Taken(), 2);
  EXPECT_DOUBLE_EQ(merger.Timed().Value(), 0.25 + 0.5);
  EXPECT_EQ(merger.FirstStart(), State("a", ""));
  EXPECT_EQ(merger.Last()->end, State("c", "v3"));
}

TEST(BoundaryState, HexRoundTripsAndNamesWhatDiffers) {
  const BoundaryState b = State(std::string("\x00\xff joints", 9), "out");
  const std::optional<BoundaryState> back = BoundaryState::FromHex(b.Hex());
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, b);
  EXPECT_EQ(b.Hex(), "9:00ff206a6f696e7473;1:74;3:6f7574;");  // length:hex; by hand
  EXPECT_FALSE(BoundaryState::FromHex(b.Hex() + "x"));
  EXPECT_FALSE(BoundaryState::FromHex("2:0;"));
  EXPECT_EQ(b.Difference(b), "");
  EXPECT_NE(b.Difference(State("other", "out")).find("the executor's joints"), std::string::npos);
}

}  // namespace
}  // namespace stitchsim::run
