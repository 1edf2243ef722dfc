// `stitchsim plan afp` programmes judged by the afp.* rules (issue 26 item 6): the course is
// written with its ply, course and tow marks, so `verify` lays its tows and the rules measure
// them; a fault planted in the planned programme fires on its line; the inclination search
// judges each candidate with the afp.* rules too.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::CliRun;

const fs::path kSource = STITCHSIM_SOURCE_DIR;
const fs::path kCylinder = kSource / "scenes" / "afp_concave_cylinder.yaml";

CliRun Cli(const std::string& args) { return testing::RunCli(args, "afp_course"); }

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// 1-based number of the first programme line starting with `prefix`, 0 if none.
int FirstLine(const std::vector<std::string>& lines, const std::string& prefix) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind(prefix, 0) == 0) return static_cast<int>(i) + 1;
  }
  return 0;
}

const json* Rule(const json& report, const std::string& id) {
  for (const json& r : report["rules"]) {
    if (r["id"] == id) return &r;
  }
  return nullptr;
}

const json* Subject(const json& rule, const std::string& name) {
  for (const json& s : rule["subjects"]) {
    if (s["subject"] == name) return &s;
  }
  return nullptr;
}

json VerifyReport(const fs::path& programme, const std::string& tag) {
  const fs::path report = testing::ScratchDir() / (tag + ".json");
  const CliRun v = Cli("verify " + programme.string() + " --scene " + kCylinder.string() +
                       " --no-collision --report " + report.string());
  EXPECT_TRUE(v.exit_code == 0 || v.exit_code == 1) << v.out << v.err;
  return json::parse(testing::ReadText(report));
}

fs::path PlanCylinderCourse(const std::string& incline, const std::string& tag) {
  const fs::path nc = testing::ScratchDir() / (tag + ".nc");
  const CliRun plan = Cli("plan afp --scene " + kCylinder.string() + " --lay-angle 45 --incline " +
                          incline + " -o " + nc.string());
  EXPECT_TRUE(plan.exit_code == 0 || plan.exit_code == 1) << plan.out << plan.err;
  EXPECT_TRUE(fs::exists(nc)) << plan.out << plan.err;
  return nc;
}

// Hand computation on the concave cylinder (r 250 mm, 800 x 450 mm of (u, v), which unrolls to
// the plane): the 45 deg course through the centre may run until a corner of its band, 8 tows
// of 6.35 mm to each side, reaches the edge v = 225: its centre ends at |v| = 225 - 50.8 / sqrt 2,
// so it is L = 2 (225 sqrt 2 - 50.8) mm long and lays L x 101.6 mm^2. Between two course points
// h = L / ceil(L / 5) apart the tool point runs on the chord, r (1 - cos(h sin 45 / 2r)) above
// the surface at its middle (the afp.* rules sample each line at most w / 2 apart: the middle
// is a sample).
TEST(PlanAfpCourse, EveryAfpRuleJudgesThePlannedCourse) {
  const fs::path nc = PlanCylinderCourse("0", "normal");
  const std::vector<std::string> lines = Lines(testing::ReadText(nc));
  EXPECT_GT(FirstLine(lines, "M70 P1"), 0);
  EXPECT_GT(FirstLine(lines, "M71 P1"), 0);
  EXPECT_GT(FirstLine(lines, "M62 P0"), 0);
  EXPECT_GT(FirstLine(lines, "M63 P0"), FirstLine(lines, "G1"));
  EXPECT_GT(FirstLine(lines, "M72"), FirstLine(lines, "M63 P0"));
  const json report = VerifyReport(nc, "normal");
  for (const char* id : {"afp.steering_radius", "afp.compaction", "afp.coverage"}) {
    const json* rule = Rule(report, id);
    ASSERT_NE(rule, nullptr) << id;
    EXPECT_TRUE((*rule)["applies"].get<bool>()) << id;
    EXPECT_EQ((*rule)["errors"].get<int>(), 0) << id << "\n" << rule->dump(1);
  }
  // afp.gap and afp.overlap measure facing edges of neighbouring courses: one course has none.
  EXPECT_NE(Rule(report, "afp.gap"), nullptr);
  EXPECT_NE(Rule(report, "afp.overlap"), nullptr);

  const double length = 2.0 * (225.0 * std::sqrt(2.0) - 50.8);  // 534.796 mm
  const json* coverage = Rule(report, "afp.coverage");
  ASSERT_NE(coverage, nullptr);
  const json* laid = Subject(*coverage, "ply 1 laid (of nominal)");
  const json* doubled = Subject(*coverage, "ply 1 doubled");
  ASSERT_TRUE(laid && doubled) << coverage->dump(1);
  // The band's area L x 16 w, as percent of the moves' chords x 16 w (the chords are shorter
  // than the arcs by h^2 / (24 rho^2), 1e-6 here); cells of w / 4 painted by their centres:
  // within 1 %.
  EXPECT_NEAR((*laid)["worst"]["value"].get<double>(), 100.0, 1.0);
  EXPECT_EQ((*doubled)["worst"]["value"].get<double>(), 0.0);

  const json* compaction = Rule(report, "afp.compaction");
  ASSERT_NE(compaction, nullptr);
  const double h = length / std::ceil(length / 5.0);
  const double lift_mm = 250.0 * (1.0 - std::cos(h * std::sqrt(0.5) / 2.0 / 250.0));  // 0.00625
  const json* lift = Subject(*compaction, "lift");
  ASSERT_NE(lift, nullptr);
  EXPECT_NEAR((*lift)["worst"]["value"].get<double>(), lift_mm / 0.25 * 100.0, 1e-3);
  for (const char* s : {"press", "roll", "lean"}) {
    ASSERT_NE(Subject(*compaction, s), nullptr) << s;
    EXPECT_NEAR((*Subject(*compaction, s))["worst"]["value"].get<double>(), 0.0, 1e-3) << s;
  }
}

// Faults planted in the planned programme fire on their lines: tow 5 cut after the 20th move
// leaves a gap of one tow width (6.35 mm) in the next laying line; a lean of 20 deg (the
// compaction limit is 15 deg) is reported on the first laying line at 20 / 15 of the limit.
TEST(PlanAfpCourse, PlantedTowGapAndOverTightInclineFireOnTheirLines) {
  const fs::path nc = PlanCylinderCourse("0", "gap");
  std::vector<std::string> lines = Lines(testing::ReadText(nc));
  const int first_g1 = FirstLine(lines, "G1");
  ASSERT_GT(first_g1, 0);
  const int cut_at = first_g1 + 19;  // 1-based: the 20th G1 goes down one line
  lines.insert(lines.begin() + (cut_at - 1), "M63 P5");
  const fs::path planted = testing::ScratchDir() / "gap_planted.nc";
  {
    std::ofstream out(planted, std::ios::binary);
    for (const std::string& l : lines) out << l << '\n';
  }
  const json gap_report = VerifyReport(planted, "gap_planted");
  const json* gap = Rule(gap_report, "afp.gap");
  ASSERT_NE(gap, nullptr);
  ASSERT_FALSE((*gap)["findings"].empty()) << gap->dump(1);
  EXPECT_EQ((*gap)["findings"][0]["line"].get<int>(), cut_at + 1);
  EXPECT_NEAR((*gap)["findings"][0]["value"].get<double>(), 6.35, 1e-9);

  const fs::path leaning = PlanCylinderCourse("20", "lean20");
  const int first_laying = FirstLine(Lines(testing::ReadText(leaning)), "G1");
  const json lean_report = VerifyReport(leaning, "lean20");
  const json* compaction = Rule(lean_report, "afp.compaction");
  ASSERT_NE(compaction, nullptr);
  ASSERT_FALSE((*compaction)["findings"].empty()) << compaction->dump(1);
  EXPECT_EQ((*compaction)["findings"][0]["line"].get<int>(), first_laying);
  // The programme's angles are written to 1e-6 deg (the dialect's digits): 1e-4 % of the limit.
  EXPECT_NEAR((*compaction)["findings"][0]["value"].get<double>(), 20.0 / 15.0 * 100.0, 1e-4);
  EXPECT_NE((*compaction)["findings"][0]["message"].get<std::string>().find("leaning"),
            std::string::npos);
}

// The inclination search judges each candidate with the afp.* rules: with the lean limited to
// 6.5 deg the leans that clear the mold (-7 deg and beyond, docs/afp.md) break afp.compaction,
// so no candidate within 8 deg passes. Before, afp.* said n/a on every candidate and the
// search handed over -7 deg.
TEST(PlanAfpCourse, InclineSearchJudgesWithTheAfpRules) {
  std::string text = testing::ReadText(kSource / "scenes" / "concave_cylinder_small.yaml");
  text += "limits:\n  afp.compaction: {max_lean_deg: 6.5}\n";
  const fs::path scene = testing::ScratchDir() / "small_lean_limited.yaml";
  std::ofstream(scene) << text;
  const fs::path nc = testing::ScratchDir() / "small_auto.nc";
  const CliRun r = Cli("plan afp --scene " + scene.string() +
                       " --lay-angle 45 --incline auto --incline-max 8 -o " + nc.string());
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("incline -7.000 deg: rejected: afp.compaction at line "), std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(nc));
}

}  // namespace
}  // namespace stitchsim::app
