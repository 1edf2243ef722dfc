// The judge of `plan afp --incline auto` built on a scene's cell, and the search with it: a
// programme the verify run passes, the judge passes; one it fails, the judge fails on the rule
// the run reports; the AFP panel's 45 deg course verifies at the first lean tried.
#include "stitchsim/run/incline_judge.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "run_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/run/verify_run.h"

namespace stitchsim::run {
namespace {

using testing::Bundled;

std::string Text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// The verify run's report of `file` on `scene` (the second route to the judge's verdict).
verify::Report Verified(const std::string& scene, const std::string& file) {
  VerifyRunOptions o;
  o.program = file;
  o.scene = scene;
  DiagnosticSink sink;
  VerifyRun run = RunVerification(o, Bundled(scene), program::Dialect::Default(), nullptr, sink);
  EXPECT_EQ(run.status, RunStatus::kOk) << testing::AllDiagnostics(sink);
  return std::move(run.report);
}

struct Judged {
  LoadedScene loaded;
  std::unique_ptr<sim::CollisionWorld> world;
};

Judged WithWorld(const std::string& scene) {
  Judged j{Bundled(scene), nullptr};
  DiagnosticSink sink;
  j.world = sim::CollisionWorld::Create(*j.loaded.scene, *j.loaded.robot, sink);
  EXPECT_TRUE(j.world) << testing::AllDiagnostics(sink);
  return j;
}

TEST(VerifyJudge, PassesWhatTheRunPassesAndFailsOnTheRulesItReports) {
  testing::ScratchDir dir("judge");
  for (const std::string scene : {"flat_straight", "rail_hit"}) {
    const std::string file = dir.File(scene + ".nc");
    testing::PlanFirstPath(Bundled(scene), file);
    const verify::Report report = Verified(scene, file);
    Judged j = WithWorld(scene);
    const planner::InclineVerdict v = VerifyJudge(j.loaded, *j.world)(Text(file));
    EXPECT_EQ(v.error, "");
    EXPECT_EQ(v.pass, report.errors == 0) << scene;
    EXPECT_EQ(v.pass, scene == "flat_straight");  // rail_hit: the arm meets the rail
    if (v.pass) continue;
    // The judge's first failure is a rule the run failed.
    const std::string rule = v.first_failure.substr(0, v.first_failure.find(' '));
    bool run_failed_it = false;
    for (const auto& r : report.rules) run_failed_it |= r.id == rule && r.errors > 0;
    EXPECT_TRUE(run_failed_it) << v.first_failure;
    EXPECT_EQ(rule.rfind("collision.", 0), 0u) << v.first_failure;
  }
}

TEST(VerifyJudge, AProgrammeThatDoesNotRunIsAnErrorNotAVerdict) {
  Judged j = WithWorld("flat_straight");
  const planner::InclineVerdict v = VerifyJudge(j.loaded, *j.world)("G1 X0 Y0 Z0 F\n");
  EXPECT_FALSE(v.pass);
  EXPECT_NE(v.error, "");
}

TEST(PlanAfpAutoIncline, TheAfpPanelsCourseVerifiesAtTheFirstLean) {
  planner::AfpPlanOptions options;
  options.lay_angle_rad = 45.0 * kDeg;
  DiagnosticSink sink;
  int seen = 0;
  const AutoInclineRun r = PlanAfpAutoIncline(
      (testing::SourceDir() / "scenes" / "afp_panel.yaml").string(), scene::LoadOptions{},
      std::nullopt, options, planner::InclineSearchOptions{},
      [&](const planner::InclineCandidate&) { ++seen; }, sink);
  ASSERT_EQ(r.status, RunStatus::kOk) << testing::AllDiagnostics(sink);
  ASSERT_TRUE(r.search.plan);
  ASSERT_TRUE(r.loaded);
  EXPECT_EQ(r.search.candidates.size(), 1u);
  EXPECT_EQ(seen, 1);
  EXPECT_EQ(r.search.plan->incline_rad, 0.0);
  EXPECT_TRUE(r.search.candidates.front().pass);
}

TEST(PlanAfpAutoIncline, UnknownSceneIsBadInput) {
  DiagnosticSink sink;
  const AutoInclineRun r =
      PlanAfpAutoIncline("no/such/scene.yaml", scene::LoadOptions{}, std::nullopt,
                         planner::AfpPlanOptions{}, planner::InclineSearchOptions{}, nullptr, sink);
  EXPECT_EQ(r.status, RunStatus::kBadInput);
  EXPECT_TRUE(sink.HasErrors());
}

TEST(FailuresByRule, CountsEachCandidatesFirstFailingRuleInNameOrder) {
  std::vector<planner::InclineCandidate> c(4);
  c[0].failure = "kin.reach at line 3: unreachable";
  c[1].failure = "collision.head_mold at line 7: the head meets the mold (2 more errors)";
  c[2].failure = "kin.reach: no solution";
  c[3].failure = "kin.reach at line 9: unreachable";
  EXPECT_EQ(FailuresByRule(c), "collision.head_mold on 1, kin.reach on 3");
}

}  // namespace
}  // namespace stitchsim::run
