// The planners' progress callbacks (S11): called with a rising count that ends at the total the
// plan itself holds (stitches, row pieces, courses), and the programme written with a callback
// is byte for byte the one written without.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/planner/raster_planner.h"
#include "stitchsim/planner/stitch_planner.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;
constexpr double kInch = 25.4;

std::unique_ptr<scene::Scene> Load(const fs::path& file) {
  DiagnosticSink sink;
  auto s = scene::LoadScene(file, sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return s;
}

struct Call {
  double done, total;
};

// Records every call; checks that done never falls and total never changes.
struct Recorder {
  std::vector<Call> calls;
  PlanProgress Callback() {
    return [this](double done, double total) {
      if (!calls.empty()) {
        EXPECT_GE(done, calls.back().done);
        EXPECT_EQ(total, calls.back().total);
      }
      calls.push_back({done, total});
    };
  }
};

std::string StitchText(const scene::Scene& s, StitchPlanOptions o) {
  DiagnosticSink sink;
  auto planner = StitchPathPlanner::Create(s, s.paths.front(), o, sink);
  EXPECT_TRUE(planner.has_value());
  std::ostringstream out;
  WriteStitchProgram(*planner, s, s.paths.front().name, program::Dialect::Default(), out);
  return out.str();
}

TEST(PlanProgress, StitchPlannerCountsEveryStitch) {
  const auto s = Load(kSource / "scenes" / "circle_8in.yaml");
  ASSERT_NE(s, nullptr);
  DiagnosticSink sink;
  const int count = StitchPathPlanner::Create(*s, s->paths.front(), {}, sink)->StitchCount();
  ASSERT_GT(count, 10);
  Recorder recorder;
  StitchPlanOptions with;
  with.progress = recorder.Callback();
  EXPECT_EQ(StitchText(*s, with), StitchText(*s, {}));
  ASSERT_EQ(recorder.calls.size(), static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    EXPECT_EQ(recorder.calls[static_cast<std::size_t>(i)].done, i + 1);
    EXPECT_EQ(recorder.calls[static_cast<std::size_t>(i)].total, count);
  }
}

TEST(PlanProgress, RasterRisesToItsRowPieces) {
  const auto s = Load(kSource / "scenes" / "wing_cover.yaml");
  ASSERT_NE(s, nullptr);
  for (RasterStrategy strategy : {RasterStrategy::kJump, RasterStrategy::kSerpentine}) {
    SCOPED_TRACE(std::string(ToString(strategy)));
    RasterOptions o = RasterOptionsFor(*s);
    o.strategy = strategy;
    o.heads = 2;
    o.region =
        Eigen::AlignedBox2d(Eigen::Vector2d(-46, -21) * kInch, Eigen::Vector2d(-34, -9) * kInch);
    DiagnosticSink sink;
    std::ostringstream quiet_text;
    ASSERT_TRUE(WriteRasterProgram(*s, o, program::Dialect::Default(), quiet_text, sink));
    // The rows: every piece of every region, counted from the plan itself.
    const std::optional<RasterPlan> plan = PlanRaster(*s, o, sink);
    ASSERT_TRUE(plan.has_value());
    long pieces = 0;
    for (const RasterRegion& r : plan->regions) pieces += static_cast<long>(r.pieces.size());
    ASSERT_GT(pieces, 10);
    EXPECT_EQ(plan->row_pieces, pieces);

    Recorder recorder;
    o.progress = recorder.Callback();
    std::ostringstream text;
    ASSERT_TRUE(WriteRasterProgram(*s, o, program::Dialect::Default(), text, sink));
    EXPECT_EQ(text.str(), quiet_text.str());
    ASSERT_GT(recorder.calls.size(), 2u);
    EXPECT_EQ(recorder.calls.front().total, pieces);
    EXPECT_EQ(recorder.calls.back().done, pieces);  // 100 % at the end
    // A fifth of the way (0.1 counting, 0.1 passes) when the plan is made.
    Recorder planning;
    o.progress = planning.Callback();
    ASSERT_TRUE(PlanRaster(*s, o, sink).has_value());
    ASSERT_FALSE(planning.calls.empty());
    EXPECT_NEAR(planning.calls.back().done, 0.2 * static_cast<double>(pieces), 1e-9);
    EXPECT_EQ(sink.ErrorCount(), 0u);
  }
}

// A band offset ply counts its courses as it finds them (total unknown: 0); a laminate family
// ply knows its course lines first.
TEST(PlanProgress, PlyCountsCourses) {
  const auto s = Load(kSource / "scenes" / "afp_panel.yaml");
  ASSERT_NE(s, nullptr);
  const scene::PlySpec* ply = s->FindPly("skin_45");
  ASSERT_NE(ply, nullptr);
  Recorder recorder;
  PlyPlanOptions o;
  o.progress = recorder.Callback();
  DiagnosticSink sink;
  const auto plan = PlanPly(*s, *ply, o, sink);
  ASSERT_TRUE(plan.has_value());
  std::ostringstream with, without;
  WritePlyProgram(*plan, *s, program::Dialect::Default(), with);
  const auto plain = PlanPly(*s, *ply, {}, sink);
  ASSERT_TRUE(plain.has_value());
  WritePlyProgram(*plain, *s, program::Dialect::Default(), without);
  EXPECT_EQ(with.str(), without.str());
  ASSERT_GE(recorder.calls.size(), plan->courses.size());  // the reference course always
  EXPECT_EQ(recorder.calls.back().done, static_cast<double>(plan->courses.size()));
  EXPECT_EQ(recorder.calls.back().total, 0.0);

  std::ifstream in(kSource / "scenes" / "afp_panel.yaml");
  std::stringstream yaml_text;
  yaml_text << in.rdbuf();
  std::string yaml = yaml_text.str();
  for (std::size_t at; (at = yaml.find("rule: offset")) != std::string::npos;)
    yaml.replace(at, 12, "rule: laminate_family");
  const fs::path dir = fs::temp_directory_path() / ("plan_progress_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "s.yaml") << yaml;
  const auto laminate = Load(dir / "s.yaml");
  fs::remove_all(dir);
  ASSERT_NE(laminate, nullptr);
  Recorder lines;
  o.progress = lines.Callback();
  ASSERT_TRUE(PlanPly(*laminate, *laminate->FindPly("skin_45"), o, sink).has_value());
  ASSERT_FALSE(lines.calls.empty());
  EXPECT_GT(lines.calls.back().total, 0.0);
  EXPECT_EQ(lines.calls.back().done, lines.calls.back().total);
  EXPECT_EQ(sink.ErrorCount(), 0u);
}

}  // namespace
}  // namespace stitchsim::planner
