// Report writers: n/a rules, per-subject figures beside their own limits and skipped rules
// in the text, JSON and JUnit reports (issue 10, items 14 and 15).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "report_test_support.h"
#include "stitchsim/common/version.h"
#include "stitchsim/verify/report.h"

namespace stitchsim::verify {
namespace {

using namespace report_test_support;  // NOLINT(google-build-using-namespace)

// stitch.length with per-needle figures, a rule that checked nothing (a stale worst value
// must not show), and the collision rules skipped.
Report SubjectsReport() {
  Report report;
  report.program_file = "prog.nc";
  report.scene_file = "scenes/circle_8in.yaml";
  report.scene_name = "circle_8in";
  report.head = "rs535";
  report.verdict = "pass";
  report.moves = 511;
  report.stitches = 255;
  RuleSummary length;
  length.id = "stitch.length";
  length.unit = "%";
  length.checked = 254;
  length.error_limit = 15.0;
  length.warning_limit = 5.0;
  length.worst_value = 0.25;
  length.worst_line = 9;
  length.worst_stitch = 2;
  SubjectFigure catcher;
  catcher.subject = "catcher";
  catcher.checked = 254;
  catcher.error_limit = 15.0;
  catcher.warning_limit = 5.0;
  catcher.worst_value = 0.25;
  catcher.worst_line = 9;
  catcher.worst_stitch = 2;
  SubjectFigure insertion;
  insertion.subject = "insertion";
  insertion.checked = 254;
  insertion.worst_value = 8.359;
  insertion.worst_line = 11;
  insertion.worst_stitch = 3;
  length.subjects = {catcher, insertion};
  RuleSummary idle;
  idle.id = "program.sync";
  idle.unit = "mm";
  idle.checked = 0;
  idle.error_limit = 0.01;
  idle.worst_value = 4.96;  // must never be shown: the rule checked nothing
  report.rules = {length, idle};
  report.skipped = {{"collision.head_mold", "--no-collision"},
                    {"collision.robot_cell", "--no-collision"},
                    {"collision.clearance", "--no-collision"}};
  report.errors = 0;
  report.warnings = 0;
  return report;
}

TEST(report_subjects, TextShowsEachFigureBesideItsLimitNaAndSkipped) {
  const std::string text = ReportToText(SubjectsReport());
  const std::vector<std::string> lines = SplitLines(text);
  EXPECT_NE(lines[0].find(" in 2 rules, 3 skipped (--no-collision: collision.head_mold, "
                          "collision.robot_cell, collision.clearance); 255 stitches"),
            std::string::npos)
      << lines[0];
  const auto row = [&](const std::string& start) {
    for (const std::string& l : lines) {
      if (l.rfind(start, 0) == 0) return l;
    }
    return std::string();
  };
  const std::string length = row("  stitch.length ");
  const std::string catcher = row("    catcher ");
  const std::string insertion = row("    insertion ");
  const std::string idle = row("  program.sync ");
  ASSERT_FALSE(length.empty() || catcher.empty() || insertion.empty() || idle.empty()) << text;
  EXPECT_NE(length.find("0.25 %"), std::string::npos) << length;
  EXPECT_NE(length.find("line 9 stitch 2"), std::string::npos) << length;
  EXPECT_NE(length.find("15 % (warn 5)"), std::string::npos) << length;
  EXPECT_NE(insertion.find("8.359 %"), std::string::npos) << insertion;
  EXPECT_EQ(insertion.substr(insertion.size() - 1), "-") << "no limit of its own";
  EXPECT_NE(catcher.find("15 % (warn 5)"), std::string::npos) << catcher;
  EXPECT_NE(idle.find("n/a"), std::string::npos) << idle;
  EXPECT_EQ(idle.find("4.96"), std::string::npos) << idle;
}

TEST(report_subjects, JsonListsSubjectsNaAndSkipped) {
  const Json j = Json::parse(ReportToJson(SubjectsReport()));
  const Json& length = j["rules"][0];
  EXPECT_EQ(length["applies"], true);
  ASSERT_EQ(length["subjects"].size(), 2u);
  const Json& insertion = length["subjects"][1];
  EXPECT_EQ(insertion["subject"], "insertion");
  EXPECT_EQ(insertion["checked"], 254);
  EXPECT_TRUE(insertion["error_limit"].is_null());
  EXPECT_EQ(insertion["worst"]["value"].get<double>(), 8.359);
  EXPECT_EQ(insertion["worst"]["line"], 11);
  EXPECT_EQ(length["subjects"][0]["warning_limit"].get<double>(), 5.0);
  const Json& idle = j["rules"][1];
  EXPECT_EQ(idle["applies"], false);
  EXPECT_TRUE(idle["worst"].is_null());
  ASSERT_EQ(j["skipped_rules"].size(), 3u);
  EXPECT_EQ(j["skipped_rules"][1]["id"], "collision.robot_cell");
  EXPECT_EQ(j["skipped_rules"][1]["reason"], "--no-collision");
  EXPECT_EQ(j["stitchsim_version"], std::string(stitchsim::ToolVersion()));
}

TEST(report_subjects, JunitMarksSkippedAndNaAndNamesSubjects) {
  Report report = SubjectsReport();
  report.rules[0].errors = 1;
  report.rules[0].worst_value = 30.0;
  report.rules[0].worst_line = 8;
  const Json root = ParseJunitWithPython(ReportToJunit(report));
  ASSERT_TRUE(root.is_object());
  EXPECT_EQ(root["attrib"]["tests"], "5");
  EXPECT_EQ(root["attrib"]["skipped"], "3");
  const Json& suite = root["children"][0];
  EXPECT_EQ(suite["attrib"]["skipped"], "3");
  EXPECT_EQ(suite["attrib"]["tests"], "5");
  const Json& properties = suite["children"][0];
  ASSERT_EQ(properties["tag"], "properties");
  std::vector<std::string> names;
  for (const Json& p : properties["children"]) names.push_back(p["attrib"]["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"program", "scene", "scene_file", "head",
                                             "stitchsim_version"}));
  EXPECT_EQ(properties["children"][0]["attrib"]["value"], "prog.nc");
  EXPECT_EQ(properties["children"][3]["attrib"]["value"], "rs535");
  const Json* length = FindCase(suite, "stitch.length");
  ASSERT_NE(length, nullptr);
  EXPECT_EQ((*length)["children"][0]["attrib"]["message"],
            "1 error; worst 30 % at line 8 (limit 15 %); catcher worst 0.25 % (limit 15 %); "
            "insertion worst 8.359 % (no limit)");
  const Json* idle = FindCase(suite, "program.sync");
  ASSERT_NE(idle, nullptr);
  EXPECT_EQ((*idle)["children"][0]["tag"], "system-out");
  EXPECT_EQ((*idle)["children"][0]["text"], "n/a: the rule found nothing to check");
  for (const char* id : {"collision.head_mold", "collision.robot_cell", "collision.clearance"}) {
    const Json* c = FindCase(suite, id);
    ASSERT_NE(c, nullptr) << id;
    EXPECT_EQ((*c)["children"][0]["tag"], "skipped");
    EXPECT_EQ((*c)["children"][0]["attrib"]["message"], "skipped: --no-collision");
  }
}

}  // namespace
}  // namespace stitchsim::verify
