// `sequence --html` as a library (run/sequence_html.h): the off-part stretches of a
// hand-written programme by hand; on seed 004's planar 45 deg plies (seq_plate), the stretches
// add up to the flown lengths the run measures its own way (the reader's total less the
// lay-ups; the writer's blocks), the plies' figures add up to the totals, and the page embeds
// exactly the JSON the report file holds.
#include "stitchsim/run/sequence_html.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sequence_fixture.h"
#include "stitchsim/run/sequence_report.h"

namespace stitchsim::run {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Two courses on z = 0 (as tests/program/afp_program_test.cpp's): lay-ups x = 0 and x = 30,
// y 0 -> 100; approach down from z = 100, retract up to z = 100.
constexpr char kTwoCourses[] = R"(%
G21 G90
M70 P1 (PLY name=a)
M71 P1
G0 X0 Y0 Z100 A0 B0 C0 M20
M21
G1 X0 Y0 Z0 F6000
M62 P0
G1 X0 Y100 Z0
M63 P0
M20
G0 X0 Y100 Z100
M72
M71 P2
G0 X30 Y0 Z100
M21
G1 X30 Y0 Z0
M62 P0
G1 X30 Y100 Z0
M63 P0
M20
G0 X30 Y100 Z100
M72
M30
%
)";

TEST(SequenceHtml, StretchesOfAHandWrittenProgrammeAreTheMovesOutsideTheLayups) {
  std::istringstream text(kTwoCourses);
  DiagnosticSink sink;
  const auto p = program::ReadAfpProgram(text, program::Dialect::Default(), "t.nc", sink);
  ASSERT_TRUE(p.has_value());
  const auto s = OffPartStretches(*p, Eigen::Vector3d(0, 0, 100));  // from its first point
  ASSERT_EQ(s.size(), 3u);
  // Down onto course 1: 100 mm; up, across to (30, 0, 100) and down: 100 + hypot(30, 100) +
  // 100; up after course 2: 100.
  EXPECT_EQ(s[0].course, 0);
  EXPECT_NEAR(s[0].length_mm, 100.0, 1e-9);
  EXPECT_EQ(s[1].course, 1);
  EXPECT_NEAR(s[1].length_mm, 200.0 + std::hypot(30.0, 100.0), 1e-9);
  ASSERT_EQ(s[1].points.size(), 4u);
  EXPECT_NEAR((s[1].points.front() - Eigen::Vector3d(0, 100, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((s[1].points.back() - Eigen::Vector3d(30, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(s[2].course, -1);
  EXPECT_NEAR(s[2].length_mm, 100.0, 1e-9);
  EXPECT_NEAR(s[0].length_mm + s[1].length_mm + s[2].length_mm, p->offpart_length_mm, 1e-9);
  // Flown from elsewhere: the move from there to (0, 0, 100) leads the first stretch.
  const auto h = OffPartStretches(*p, Eigen::Vector3d(-40, 0, 130));
  ASSERT_EQ(h.size(), 3u);
  EXPECT_NEAR(h[0].length_mm, 100.0 + 50.0, 1e-9);  // hypot(40, 30) = 50
  EXPECT_NEAR((h[0].points.front() - Eigen::Vector3d(-40, 0, 130)).norm(), 0.0, 1e-12);
}

class SequenceHtmlTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::SequenceTestDir());
    test::PlanSeqPlate({"base_45", "pad_45_left", "pad_45_mid"}, *dir_ / "planar45.nc");
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path* dir_;
};
fs::path* SequenceHtmlTest::dir_ = nullptr;

// The JSON inside the page's data script ("<\/" put back to "</").
json EmbeddedData(const std::string& page) {
  const std::string open = R"(<script id="stitchsim-data" type="application/json">)";
  const std::size_t at = page.find(open);
  EXPECT_NE(at, std::string::npos);
  const std::size_t from = at + open.size(), to = page.find("</script>", from);
  std::string text = page.substr(from, to - from);
  std::size_t i = 0;
  while ((i = text.find("<\\/", i)) != std::string::npos) text.replace(i, 3, "</");
  return json::parse(text);
}

TEST_F(SequenceHtmlTest, PageEmbedsTheReportAndStretchesAddUpToTheFlownLengths) {
  SequenceOptions o = test::SeqPlateOptions(*dir_ / "planar45.nc");
  o.bidirectional = true;
  o.measure = Measure::kTool;
  const SequenceInputs in = test::LoadOrFail(o);
  const SequenceRun r = RunSequence(in, o, nullptr);
  ASSERT_EQ(r.status, SequenceStatus::kOk);
  ASSERT_TRUE(r.sequenced.has_value());
  const SequenceOutcome& out = r.outcome;
  // Second routes: the reader's moved length less the lay-ups (before), the writer's blocks
  // (SequenceOffPart, after).
  double before = 0.0, after = 0.0;
  for (const auto& s : OffPartStretches(in.program, r.start_mm)) before += s.length_mm;
  for (const auto& s : OffPartStretches(*r.sequenced, r.start_mm)) after += s.length_mm;
  EXPECT_NEAR(before, out.flown_offpart_before_mm, 1e-6);
  EXPECT_NEAR(after, out.flown_offpart_after_mm, 1e-6);
  EXPECT_LT(after, 0.8 * before);  // the zig-zag-free plan still gains from the joins
  // The plies' shares add up to the totals, in every measure and flown.
  ASSERT_EQ(out.plies.size(), 3u);
  Costs pb{}, pa{};
  double fb = 0.0, fa = 0.0, lay = 0.0;
  for (const PlyOutcome& p : out.plies) {
    for (std::size_t m = 0; m < pb.size(); ++m) {
      pb[m] += p.offpart_before[m];
      pa[m] += p.offpart_after[m];
    }
    fb += p.flown_before_mm;
    fa += p.flown_after_mm;
    lay += p.layup_mm;
  }
  for (std::size_t m = 0; m < pb.size(); ++m) {
    EXPECT_NEAR(pb[m], out.offpart_before[m], 1e-6 * (1.0 + out.offpart_before[m])) << m;
    EXPECT_NEAR(pa[m], out.offpart_after[m], 1e-6 * (1.0 + out.offpart_after[m])) << m;
  }
  EXPECT_NEAR(fb, out.flown_offpart_before_mm, 1e-6);
  EXPECT_NEAR(fa, out.flown_offpart_after_mm, 1e-6);
  EXPECT_NEAR(lay, out.layup[2], 1e-6);  // the tool measure's lay-up: the same tool path
  // The page's embedded report is the report file's JSON, field for field.
  std::string error;
  const std::string page = SequenceHtmlPage(r, in.program, error);
  ASSERT_FALSE(page.empty()) << error;
  std::ostringstream report;
  WriteSequenceJson(out, in.program, report);
  const json data = EmbeddedData(page);
  EXPECT_EQ(data.at("report"), json::parse(report.str()));
  EXPECT_EQ(data.at("courses").size(), in.program.courses.size());
  EXPECT_EQ(data.at("after").at("visits").size(), in.program.courses.size());
  // Each drawn course is laid from its visit's start: a backward one from its forward end.
  const auto& order = data.at("report").at("order");
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto& v = data.at("after").at("visits").at(i);
    const auto& c = in.program.courses[v.at("course").get<std::size_t>()];
    EXPECT_EQ(c.number, order.at(i).at("course").get<int>());
    const auto& st =
        order.at(i).at("reversed").get<bool>() ? c.stations.back() : c.stations.front();
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(v.at("start").at(k).get<double>(), st.pose.translation()[k], 0.006);
  }
}

}  // namespace
}  // namespace stitchsim::run
