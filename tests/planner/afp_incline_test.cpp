// The AFP inclination search (planner/afp_incline.h) with judges written here: candidates in
// order, the first passing one wins, feeds lowered where only the joint speed fails (and only
// on feed moves), a judge's error stops the search. The real judge (executor + verifier) is
// exercised by the CLI tests and scripts/scene_reports.sh (`plan afp --incline auto`).
#include "stitchsim/planner/afp_incline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "stitchsim/common/units.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;

std::unique_ptr<scene::Scene> AfpScene() {
  DiagnosticSink sink;
  auto s = scene::LoadScene(kSource / "scenes" / "afp_concave_cylinder.yaml", sink);
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  return s;
}

AfpPlanOptions Lay45() {
  AfpPlanOptions o;
  o.lay_angle_rad = 45 * kDeg;
  return o;
}

// The lean a candidate programme was planned at, from its header (degrees).
double InclineOf(const std::string& text) {
  const std::size_t at = text.find("incline_deg=");
  EXPECT_NE(at, std::string::npos);
  return std::stod(text.substr(at + 12));
}

// The 1-based line of the first block starting with `word` ("G0 ", "G1 ").
int LineOf(const std::string& text, const std::string& word) {
  int line = 1;
  for (std::size_t at = 0; at < text.size(); ++line) {
    if (text.compare(at, word.size(), word) == 0) return line;
    const std::size_t nl = text.find('\n', at);
    if (nl == std::string::npos) break;
    at = nl + 1;
  }
  ADD_FAILURE() << "no line starts with " << word;
  return 0;
}

// The search at lean 0 only, so a candidate's feed rounds are the whole search.
InclineSearchResult SearchNoLean(const scene::Scene& s, const InclineJudge& judge,
                                 int max_feed_rounds = 6) {
  InclineSearchOptions o;
  o.max_deg = 0;
  o.max_feed_rounds = max_feed_rounds;
  DiagnosticSink sink;
  return SearchAfpIncline(s, nullptr, Lay45(), o, judge, sink);
}

InclineVerdict Passing() {
  InclineVerdict v;
  v.pass = true;
  return v;
}

InclineVerdict Failing(const std::string& why) {
  InclineVerdict v;
  v.first_failure = why;
  return v;
}

// Only the joint speed fails, on `line`, at `pct` % of its maximum.
InclineVerdict JointSpeedFails(int line, double pct) {
  InclineVerdict v = Failing("kin.joint_speed at line " + std::to_string(line) + ": too fast");
  v.only_joint_speed_fails = true;
  v.joint_speed_rule = "kin.joint_speed";
  v.joint_speed_pct[line] = pct;
  return v;
}

TEST(AfpIncline, CandidatesSmallestLeanFirstForwardBeforeBack) {
  InclineSearchOptions o;
  o.max_deg = 2.5;
  o.step_deg = 1.0;
  const std::vector<double> c = InclineCandidates(o);
  const std::vector<double> expected = {0, 1, -1, 2, -2};
  ASSERT_EQ(c.size(), expected.size());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(c[i], expected[i] * kDeg, 1e-12);
}

TEST(AfpIncline, FirstCandidateTheJudgePassesWins) {
  const auto s = AfpScene();
  std::vector<double> judged;
  const InclineJudge judge = [&](const std::string& text) {
    judged.push_back(InclineOf(text));
    return std::abs(judged.back() - 2.0) < 1e-9 ? Passing()
                                                : Failing("collision.head_mold at line 5: hit");
  };
  InclineSearchOptions o;
  o.max_deg = 5;
  DiagnosticSink sink;
  int reported = 0;
  const InclineSearchResult r = SearchAfpIncline(*s, nullptr, Lay45(), o, judge, sink,
                                                 [&](const InclineCandidate&) { ++reported; });
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_TRUE(r.plan.has_value());
  EXPECT_NEAR(r.plan->incline_rad, 2 * kDeg, 1e-12);
  EXPECT_EQ(judged, (std::vector<double>{0, 1, -1, 2}));
  ASSERT_EQ(r.candidates.size(), 4u);
  EXPECT_EQ(reported, 4);
  EXPECT_EQ(r.candidates.front().failure, "collision.head_mold at line 5: hit");
  EXPECT_TRUE(r.candidates.back().pass);
  EXPECT_EQ(r.candidates.back().failure, "");
}

TEST(AfpIncline, FeedLoweredWhereOnlyTheJointSpeedFails) {
  const auto s = AfpScene();
  std::vector<std::string> texts;
  const InclineJudge judge = [&](const std::string& text) {
    texts.push_back(text);
    // The first judgement: the first feed move runs its worst joint at 150 % of the limit.
    return texts.size() == 1 ? JointSpeedFails(LineOf(text, "G1 "), 150.0) : Passing();
  };
  const InclineSearchResult r = SearchNoLean(*s, judge);
  ASSERT_TRUE(r.plan.has_value());
  ASSERT_EQ(r.candidates.size(), 1u);
  const InclineCandidate& c = r.candidates.front();
  EXPECT_TRUE(c.pass);
  EXPECT_EQ(c.slowed_moves, 1);
  EXPECT_NEAR(c.slowest_feed_fraction, 0.95 * 100.0 / 150.0, 1e-12);
  EXPECT_NEAR(r.plan->points[1].feed_fraction, 0.95 * 100.0 / 150.0, 1e-12);
  ASSERT_EQ(texts.size(), 2u);
  EXPECT_NE(texts[0], texts[1]);  // the second programme has the lower feed written
}

TEST(AfpIncline, JointSpeedOnARapidCannotBeLowered) {
  const auto s = AfpScene();
  const InclineJudge judge = [&](const std::string& text) {
    return JointSpeedFails(LineOf(text, "G0 "), 150.0);
  };
  const InclineSearchResult r = SearchNoLean(*s, judge);
  EXPECT_FALSE(r.plan.has_value());
  ASSERT_EQ(r.candidates.size(), 1u);
  EXPECT_EQ(r.candidates.front().failure,
            "kin.joint_speed at line 7, which is not a feed move: its speed cannot be lowered");
}

TEST(AfpIncline, GivesUpAfterTheFeedRounds) {
  const auto s = AfpScene();
  int calls = 0;
  const InclineJudge judge = [&](const std::string& text) {
    ++calls;
    return JointSpeedFails(LineOf(text, "G1 "), 150.0);
  };
  const InclineSearchResult r = SearchNoLean(*s, judge, 3);
  EXPECT_FALSE(r.plan.has_value());
  EXPECT_EQ(calls, 4);
  ASSERT_EQ(r.candidates.size(), 1u);
  EXPECT_EQ(r.candidates.front().failure,
            "kin.joint_speed at line 9: too fast (still, after lowering the feed 3 times)");
}

TEST(AfpIncline, AJudgesErrorStopsTheSearch) {
  const auto s = AfpScene();
  const InclineJudge judge = [](const std::string&) {
    InclineVerdict v;
    v.error = "boom";
    return v;
  };
  DiagnosticSink sink;
  const InclineSearchResult r =
      SearchAfpIncline(*s, nullptr, Lay45(), InclineSearchOptions{}, judge, sink);
  EXPECT_EQ(r.error, "incline 0.000 deg: boom");
  EXPECT_TRUE(r.candidates.empty());
  EXPECT_FALSE(r.plan.has_value());
}

}  // namespace
}  // namespace stitchsim::planner
