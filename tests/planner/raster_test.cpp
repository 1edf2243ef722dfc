// The constraint-aware raster planner (seed 001): a small window of the wing cover planned
// with both strategies verifies clean (no constraint.crossing, no other error); heads split
// the work evenly by stitch count; a head out of service gets nothing; user code blocks.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "raster_test_support.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
constexpr double kInch = 25.4;

std::unique_ptr<scene::Scene> Wing() {
  DiagnosticSink sink;
  auto s = scene::LoadScene(kSource / "scenes" / "wing_cover.yaml", sink);
  EXPECT_NE(s, nullptr);
  EXPECT_EQ(sink.ErrorCount(), 0u);
  return s;
}

// A window around the crossing of intercostal_3 (x = -40 in) and stringer_2 (y = -15 in),
// with the scene's raster defaults.
RasterOptions SmallWindow(const scene::Scene& s, RasterStrategy strategy) {
  RasterOptions o = RasterOptionsFor(s);
  o.strategy = strategy;
  o.region =
      Eigen::AlignedBox2d(Eigen::Vector2d(-46, -21) * kInch, Eigen::Vector2d(-34, -9) * kInch);
  return o;
}

using testing::Errors;
using testing::Plan;
using testing::VerifyText;

// The plan is data and the writer follows it: the summary the writer counts equals what the
// plan holds, the programme's first pass has no transit, every jump flies at least the flight
// clearance, every pass starts off the footprints, and plan + write equals the one-call form.
TEST(RasterPlanner, PlanIsDataTheWriterFollows) {
  const auto s = Wing();
  for (RasterStrategy strategy : {RasterStrategy::kJump, RasterStrategy::kSerpentine}) {
    SCOPED_TRACE(std::string(ToString(strategy)));
    RasterOptions o = SmallWindow(*s, strategy);
    o.heads = 2;
    DiagnosticSink sink;
    const std::optional<RasterPlan> plan = PlanRaster(*s, o, sink);
    ASSERT_TRUE(plan.has_value());
    EXPECT_EQ(sink.ErrorCount(), 0u);
    ASSERT_EQ(plan->sections.size(), 2u);
    ASSERT_FALSE(plan->sections.front().passes.empty());
    EXPECT_FALSE(plan->sections.front().passes.front().transit.has_value());
    long stitches = 0, jumps = 0, rows = 0, regions = 0;
    for (const RasterSection& section : plan->sections) {
      regions += static_cast<long>(section.regions);
      for (const RasterPass& pass : section.passes) {
        EXPECT_GT(pass.stitches, 0);
        stitches += pass.stitches;
        rows += pass.row_start ? 1 : 0;
        if (pass.transit && pass.transit->jump) {
          ++jumps;
          EXPECT_GE(pass.transit->lift_mm, plan->flight_clearance_mm);
        }
        const double u = pass.direction > 0 ? pass.piece.u_begin_mm : pass.piece.u_end_mm;
        for (const scene::Footprint& f : plan->footprints) {
          EXPECT_LE(f.Depth({u, pass.piece.v_mm}), 1e-9) << f.name;
        }
      }
    }
    std::ostringstream text;
    const RasterSummary sum = WriteRasterProgram(*plan, *s, program::Dialect::Default(), text);
    EXPECT_EQ(sum.stitches, stitches);
    EXPECT_EQ(sum.jumps, jumps);
    EXPECT_EQ(sum.rows, rows);
    EXPECT_EQ(sum.bays, regions);
    EXPECT_GT(jumps, 0);
    EXPECT_EQ(text.str(), Plan(*s, o));
  }
}

TEST(RasterPlanner, WingWindowVerifiesCleanWithBothStrategies) {
  const auto s = Wing();
  for (RasterStrategy strategy : {RasterStrategy::kJump, RasterStrategy::kSerpentine}) {
    const RasterOptions o = SmallWindow(*s, strategy);
    RasterSummary sum;
    const std::string text = Plan(*s, o, &sum);
    EXPECT_GT(sum.stitches, 1000) << ToString(strategy);
    EXPECT_GT(sum.jumps, 0) << ToString(strategy);
    const verify::Report r = VerifyText(*s, text, o.pitch_mm);
    EXPECT_EQ(r.stitches, sum.stitches) << ToString(strategy);
    const verify::RuleSummary* crossing = nullptr;
    for (const auto& rule : r.rules) {
      if (rule.id == "constraint.crossing") crossing = &rule;
    }
    ASSERT_NE(crossing, nullptr);
    EXPECT_GT(crossing->checked, 0);
    EXPECT_EQ(crossing->errors, 0) << ToString(strategy);
    EXPECT_EQ(r.verdict, "pass") << ToString(strategy) << "\n" << Errors(r);
    // No warnings either (clearance to the stringers included).
    for (const auto& rule : r.rules) {
      EXPECT_EQ(rule.warnings, 0) << ToString(strategy) << " " << rule.id << ": "
                                  << (rule.findings.empty() ? "" : rule.findings[0].message);
    }
    // Jumps fly over the constraints: every M20 is followed by a lift away from the surface.
    EXPECT_NE(text.find("M20\nG0"), std::string::npos) << ToString(strategy);
  }
}

TEST(RasterPlanner, WholeWingHasOverOnePointFiveMillionStitches) {
  // Counted without writing text: the writer to a discarding stream.
  const auto s = Wing();
  RasterOptions o = SmallWindow(*s, RasterStrategy::kJump);
  o.region.reset();
  o.heads = 1;
  DiagnosticSink sink;
  std::ostream null(nullptr);
  const auto sum = WriteRasterProgram(*s, o, program::Dialect::Default(), null, sink);
  ASSERT_TRUE(sum.has_value());
  EXPECT_GT(sum->stitches, 1500000);
}

TEST(RasterPlanner, TwoHeadsSplitWithinTenPercent) {
  const auto s = Wing();
  for (RasterStrategy strategy : {RasterStrategy::kJump, RasterStrategy::kSerpentine}) {
    RasterOptions o;
    o.strategy = strategy;
    o.region =
        Eigen::AlignedBox2d(Eigen::Vector2d(-100, -40) * kInch, Eigen::Vector2d(100, 40) * kInch);
    o.pitch_mm = 10.0;  // coarse: the split, not the density, is under test
    o.heads = 2;
    RasterSummary sum;
    const std::string text = Plan(*s, o, &sum);
    ASSERT_EQ(sum.head_stitches.size(), 2u);
    const double a = static_cast<double>(sum.head_stitches[0]);
    const double b = static_cast<double>(sum.head_stitches[1]);
    EXPECT_EQ(sum.head_stitches[0] + sum.head_stitches[1], sum.stitches);
    EXPECT_LE(std::abs(a - b), 0.1 * std::max(a, b)) << ToString(strategy) << " " << a << " " << b;
    EXPECT_NE(text.find("M60 P1"), std::string::npos);
    EXPECT_NE(text.find("M60 P2"), std::string::npos);
  }
}

TEST(RasterPlanner, HeadOutOfServiceGetsNothing) {
  const auto s = Wing();
  RasterOptions o = SmallWindow(*s, RasterStrategy::kJump);
  RasterSummary one;
  Plan(*s, o, &one);
  o.heads = 2;
  o.out_of_service = {1};
  RasterSummary two;
  const std::string text = Plan(*s, o, &two);
  ASSERT_EQ(two.head_stitches.size(), 2u);
  EXPECT_EQ(two.head_stitches[0], 0);
  EXPECT_EQ(two.head_stitches[1], one.stitches);
  EXPECT_EQ(text.find("M60 P1"), std::string::npos);
  EXPECT_NE(text.find("M60 P2"), std::string::npos);
  o.out_of_service = {1, 2};
  DiagnosticSink sink;
  std::ostringstream out;
  EXPECT_FALSE(WriteRasterProgram(*s, o, program::Dialect::Default(), out, sink).has_value());
  EXPECT_GT(sink.ErrorCount(), 0u);
}

TEST(RasterPlanner, UserCodeLibraryBlocksAtTheirEvents) {
  const auto s = Wing();
  DiagnosticSink sink;
  const auto lib = ParseUserCodeLibrary(
      "blocks:\n"
      "  - {name: needle_cooling, at: every_stitches, every: 500, m: [110]}\n"
      "  - {name: row_mark, at: row_start, m: [111]}\n"
      "  - {name: before_jump, at: before_jump, m: [112]}\n",
      "lib.yaml", program::Dialect::Default(), sink);
  ASSERT_TRUE(lib.has_value());
  RasterOptions o = SmallWindow(*s, RasterStrategy::kJump);
  o.library = *lib;
  RasterSummary sum;
  const std::string text = Plan(*s, o, &sum);
  auto count = [&](const std::string& word) {
    long n = 0;
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
      ++n;
    return n;
  };
  EXPECT_EQ(count("M110"), sum.stitches / 500);
  EXPECT_EQ(count("M111"), sum.rows);
  EXPECT_EQ(count("M112"), sum.jumps);
  EXPECT_EQ(count("M20\n"), sum.jumps);
  // A code outside the user range is refused with its line.
  DiagnosticSink bad;
  EXPECT_FALSE(ParseUserCodeLibrary("blocks:\n  - {name: x, at: row_start, m: [10]}\n", "b.yaml",
                                    program::Dialect::Default(), bad)
                   .has_value());
  EXPECT_GT(bad.ErrorCount(), 0u);
}

}  // namespace
}  // namespace stitchsim::planner
