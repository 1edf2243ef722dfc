// The HTML report's data of a small run (one planted joint-limit sample): as many rules,
// skipped rules and findings as the report has (counted from the report, and by hand), the
// summary's counts, and the page with every marker filled once.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "picture_test_support.h"
#include "stitchsim/run/html_report.h"

namespace stitchsim::run {
namespace {

TEST(HtmlData, HasTheReportsRulesAndFindings) {
  auto run = testing::PlantJointLimit("flat_straight");
  ASSERT_NE(run, nullptr);
  PoseTrack poses(100);
  HtmlInputs in;
  in.report = &run->report;
  in.verifier = run->verifier.get();
  in.scene = &run->ls;
  in.poses = &poses;
  in.snapshots.emplace_back("overview.png", std::string("\x89PNG", 4));
  std::string error;
  const nlohmann::json data = HtmlData(in, HtmlLimits{}, error);
  ASSERT_FALSE(data.is_null()) << error;
  EXPECT_EQ(data["format"], "stitchsim-html-1");
  EXPECT_EQ(data["rules"].size(), run->report.rules.size());
  EXPECT_EQ(data["skipped"].size(), run->report.skipped.size());
  std::size_t findings = 0;
  for (const verify::RuleSummary& r : run->report.rules) findings += r.findings.size();
  EXPECT_EQ(data["findings"].size(), findings);
  // By hand: the planted joint limit, and program.empty (the run made no stitch).
  ASSERT_EQ(findings, 2u);
  EXPECT_EQ(data["findings"][0]["rule"], "program.empty");  // line 0 first
  EXPECT_EQ(data["findings"][1]["rule"], "kin.joint_limit");
  EXPECT_EQ(data["findings"][1]["line"], testing::kPlantedLine);
  EXPECT_EQ(data["findings"][1]["subject"], "a5");
  EXPECT_EQ(data["summary"]["errors"], run->report.errors);
  EXPECT_EQ(data["summary"]["errors"], 2);
  EXPECT_EQ(data["summary"]["kind"], "stitch");
  ASSERT_EQ(data["snapshots"].size(), 1u);
  EXPECT_EQ(data["snapshots"][0]["name"], "overview.png");

  const std::string page = HtmlPage(data, error);
  ASSERT_FALSE(page.empty()) << error;
  EXPECT_EQ(page.find("<!--STITCHSIM:"), std::string::npos);
  const std::string tag = "<script id=\"stitchsim-data\" type=\"application/json\">";
  const std::size_t at = page.find(tag);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(page.find(tag, at + 1), std::string::npos);
}

}  // namespace
}  // namespace stitchsim::run
