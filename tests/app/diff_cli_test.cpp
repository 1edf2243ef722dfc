// `stitchsim diff OLD NEW --scene S` as a separate process (issue 16, Done-when 3): a programme
// against itself reports nothing; against a copy with one stitch moved onto a stringer it
// reports that stitch's new findings and nothing else; against copies with ten lines inserted
// at the start (comments; blank lines and repeated modal words) it reports no change of
// findings. The new findings are checked against `verify` of the copy (a second route).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

const fs::path kSource = STITCHSIM_SOURCE_DIR;
const std::string kWing = (kSource / "scenes" / "wing_cover.yaml").string();

std::vector<std::string> Lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

fs::path WriteLines(const std::vector<std::string>& lines, const std::string& tag) {
  const fs::path out = ScratchDir() / (tag + ".nc");
  std::ofstream o(out);
  for (const auto& l : lines) o << l << "\n";
  return out;
}

// A 12 x 4 in window of the wing (x -46 to -34 in, y -10 to -6 in): 27 rows of two pieces,
// each row jumping intercostal 3c at x = -40 in; it verifies clean with every rule.
const fs::path& WingWindow() {
  static const fs::path nc = [] {
    const fs::path out = ScratchDir() / "window.nc";
    const auto run =
        RunCli("plan raster --scene " + kWing +
                   " --strategy jump --region -46,-10,-34,-6 --quiet -o " + out.string(),
               "window_plan");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return out;
  }();
  return nc;
}

struct DiffRun {
  int exit_code = -1;
  std::string text, err;
  Json json;
  std::string junit;
};

DiffRun Diff(const fs::path& old_nc, const fs::path& new_nc, const std::string& extra,
             const std::string& tag) {
  const fs::path json = ScratchDir() / (tag + ".json"), xml = ScratchDir() / (tag + ".xml");
  const auto run =
      RunCli("diff " + old_nc.string() + " " + new_nc.string() + " --scene " + kWing + " -q" +
                 extra + " --report " + json.string() + " --junit " + xml.string(),
             tag);
  DiffRun d{run.exit_code, run.out, run.err, Json(), ReadText(xml)};
  if (fs::exists(json)) d.json = Json::parse(ReadText(json));
  return d;
}

// The findings of `verify` of a programme: (rule, line) of each.
std::set<std::pair<std::string, int>> VerifiedFindings(const fs::path& nc, const std::string& extra,
                                                       const std::string& tag) {
  const fs::path json = ScratchDir() / (tag + ".json");
  const auto run = RunCli(
      "verify " + nc.string() + " --scene " + kWing + " -q" + extra + " --report " + json.string(),
      tag);
  EXPECT_LE(run.exit_code, 1) << run.err;
  std::set<std::pair<std::string, int>> out;
  const Json j = Json::parse(ReadText(json));
  for (const Json& rule : j.at("rules")) {
    for (const Json& f : rule.at("findings"))
      out.insert({f.at("rule").get<std::string>(), f.at("line").get<int>()});
  }
  return out;
}

void ExpectNoChange(const DiffRun& d, const std::string& what) {
  EXPECT_EQ(d.exit_code, 0) << what << "\n" << d.err << d.text;
  ASSERT_TRUE(d.json.is_object()) << what << "\n" << d.err;
  EXPECT_EQ(d.json.at("counts").at("appeared"), 0) << what << "\n" << d.text;
  EXPECT_EQ(d.json.at("counts").at("disappeared"), 0) << what << "\n" << d.text;
  EXPECT_EQ(d.json.at("counts").at("changed"), 0) << what << "\n" << d.text;
  EXPECT_TRUE(d.json.at("findings").empty()) << what;
  EXPECT_EQ(d.json.at("new_errors"), false) << what;
  for (const Json& r : d.json.at("rules")) {
    EXPECT_EQ(r.at("errors").at("old"), r.at("errors").at("new")) << what << " " << r.at("id");
    EXPECT_EQ(r.at("warnings").at("old"), r.at("warnings").at("new")) << what << " " << r.at("id");
  }
  EXPECT_EQ(d.text.rfind("SAME  ", 0), 0u) << what << "\n" << d.text;
  EXPECT_EQ(d.junit.find("<failure"), std::string::npos) << what;
}

// The index (0-based) of the last stitch of the first row piece: the G1 before the first M11.
std::size_t LastStitchBeforeFirstJump(const std::vector<std::string>& lines) {
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i] == "M11") return i - 1;
  }
  return 0;
}

// Replaces the value of axis word `axis` ("Y") on a programme line.
std::string SetWord(const std::string& line, const std::string& axis, double value) {
  std::istringstream in(line);
  std::string out, word;
  while (in >> word) {
    if (!out.empty()) out += ' ';
    if (word.rfind(axis, 0) == 0) {
      std::ostringstream v;
      v.precision(9);
      v << axis << value;
      word = v.str();
    }
    out += word;
  }
  return out;
}

TEST(DiffCli, AProgrammeAgainstItselfReportsNothing) {
  const DiffRun d = Diff(WingWindow(), WingWindow(), "", "self");
  ExpectNoChange(d, "wing window against itself");
  EXPECT_EQ(d.json.at("verdict").at("old"), "pass");
  EXPECT_EQ(d.json.at("stitches").at("old"), 1782);
  EXPECT_EQ(d.json.at("stitches").at("change"), 0);
  EXPECT_EQ(d.json.at("cycle_time_s").at("change"), 0.0);
}

// The last stitch of the first row piece (y = -10 in) moved sideways onto stringer_2 (centre
// y = -15.0449 in), Z set to the skin there (z = -0.002 y^2 in) so the needles still reach the
// skin. The raster planner keeps every stitch the head's keep-out radius (44 mm) plus its
// margin (0.5 in) from every constraint, so no stitch can reach a stringer without its own
// feed growing from one pitch (2.54 mm) to 128 mm: besides constraint.crossing (the needles
// pierce inside stringer_2's footprint, and the needles-down move into it crosses it), the
// rules that judge that feed report this same stitch on this same line: stitch.length (its
// length), needle.side_force (the needles are in the preform while a coupled raster feeds) and
// program.sync (V advances one pitch, the tool travels 128 mm; advancing U and V with the feed
// instead would have the executor stitch the whole feed, a stitch every pitch, and
// program.stitch_count fire). Being the last stitch before M11, no later stitch is measured
// from it: every new finding is on the moved line, and no other line changes. The
// collision rules are left out (--no-collision): they would add the head standing on the
// stringer here and on the retract that follows.
TEST(DiffCli, OneStitchMovedOntoAStringerIsThatStitchsNewFindings) {
  std::vector<std::string> lines = Lines(WingWindow());
  const std::size_t k = LastStitchBeforeFirstJump(lines);
  ASSERT_GT(k, 0u);
  ASSERT_EQ(lines[k].rfind("G1 ", 0), 0u) << lines[k];
  ASSERT_NE(lines[k].find(" Y-254 "), std::string::npos) << lines[k];  // y = -10 in
  constexpr double kIn = 25.4;
  const double y_in = -15.0449, z_in = -0.002 * y_in * y_in;
  lines[k] = SetWord(SetWord(lines[k], "Y", y_in * kIn), "Z", z_in * kIn);
  const fs::path moved = WriteLines(lines, "moved");
  const int moved_line = static_cast<int>(k) + 1;

  const DiffRun d = Diff(WingWindow(), moved, " --no-collision", "moved");
  EXPECT_EQ(d.exit_code, 1) << d.err << d.text;
  ASSERT_TRUE(d.json.is_object()) << d.err;
  EXPECT_EQ(d.json.at("new_errors"), true);
  EXPECT_EQ(d.json.at("counts").at("disappeared"), 0) << d.text;
  EXPECT_EQ(d.json.at("counts").at("changed"), 0) << d.text;
  int crossings = 0;
  std::set<std::pair<std::string, int>> appeared;
  for (const Json& f : d.json.at("findings")) {
    EXPECT_EQ(f.at("change"), "appeared");
    EXPECT_EQ(f.at("new").at("line"), moved_line) << f.dump();
    appeared.insert({f.at("rule").get<std::string>(), f.at("new").at("line").get<int>()});
    if (f.at("rule") == "constraint.crossing") {
      ++crossings;
      EXPECT_EQ(f.at("subject"), "stringer_2");
      EXPECT_EQ(f.at("new").at("severity"), "error");
    }
    // Line-judged findings sit at the moved line's end: the Y and Z written above, by hand.
    if (f.at("rule") == "constraint.crossing" || f.at("rule") == "program.sync") {
      const Json& p = f.at("new").at("position_mm");
      ASSERT_TRUE(p.is_array()) << f.dump();
      EXPECT_NEAR(p.at(1).get<double>(), y_in * kIn, 1e-6) << f.dump();
      EXPECT_NEAR(p.at(2).get<double>(), z_in * kIn, 1e-6) << f.dump();
    }
  }
  EXPECT_EQ(crossings, 1) << d.text;
  // The rules the comment above names, each once.
  const std::set<std::pair<std::string, int>> expected = {{"constraint.crossing", moved_line},
                                                          {"needle.side_force", moved_line},
                                                          {"program.sync", moved_line},
                                                          {"stitch.length", moved_line}};
  EXPECT_EQ(appeared, expected) << d.text;
  EXPECT_EQ(d.json.at("counts").at("appeared"), 4) << d.text;
  // The second route: the original verifies clean, so the new findings are those `verify`
  // gives the copy.
  EXPECT_TRUE(VerifiedFindings(WingWindow(), " --no-collision", "orig_verify").empty());
  EXPECT_EQ(appeared, VerifiedFindings(moved, " --no-collision", "moved_verify")) << d.text;
  EXPECT_EQ(d.json.at("verdict").at("new"), "fail");
  // Text and JUnit name it.
  EXPECT_NE(d.text.find("+ constraint.crossing error line " + std::to_string(moved_line)),
            std::string::npos)
      << d.text;
  EXPECT_NE(d.junit.find("type=\"constraint.crossing\""), std::string::npos) << d.junit;

  // Moved back: the diff the other way round lists them as disappeared, exit 0.
  const DiffRun back = Diff(moved, WingWindow(), " --no-collision", "moved_back");
  EXPECT_EQ(back.exit_code, 0) << back.err << back.text;
  EXPECT_EQ(back.json.at("counts").at("disappeared"), d.json.at("counts").at("appeared"));
  EXPECT_EQ(back.json.at("counts").at("appeared"), 0);
}

// Ten lines inserted after the header (line 2): every line number after them moves by ten.
std::vector<std::string> InsertAfterHeader(std::vector<std::string> lines,
                                           const std::vector<std::string>& ten) {
  EXPECT_EQ(ten.size(), 10u);
  EXPECT_EQ(lines.at(1).rfind("(STITCHSIM ", 0), 0u) << lines.at(1);
  lines.insert(lines.begin() + 2, ten.begin(), ten.end());
  return lines;
}

const std::vector<std::string> kTenComments = {"(edited by hand)",
                                               "(ten comment lines)",
                                               "(3)",
                                               "(4)",
                                               "(5)",
                                               "(6)",
                                               "(7)",
                                               "(8)",
                                               "(9)",
                                               "(10)"};
// Blank lines, comments and modal words already in force: nothing moves.
const std::vector<std::string> kTenHarmless = {"",        "G21", "G90", "(note)",         "",
                                               "G21 G90", "G90", "",    "(another note)", "G21"};

TEST(DiffCli, TenLinesInsertedAtTheStartChangeNoFinding) {
  // A programme with findings of every kind to match: the moved copy above (findings with and
  // without a position), and the coupled 8 in circle (255 side-force errors: truncated at 200).
  std::vector<std::string> lines = Lines(WingWindow());
  const std::size_t k = LastStitchBeforeFirstJump(lines);
  lines[k] = SetWord(SetWord(lines[k], "Y", -382.14), "Z", -11.4985);
  const fs::path base = WriteLines(lines, "ten_base");
  const std::pair<std::string, std::vector<std::string>> edits[] = {{"comments", kTenComments},
                                                                    {"harmless", kTenHarmless}};
  for (const auto& [name, ten] : edits) {
    const fs::path edited = WriteLines(InsertAfterHeader(lines, ten), "ten_" + name);
    const DiffRun d = Diff(base, edited, " --no-collision", "ten_" + name);
    ExpectNoChange(d, name);
    EXPECT_EQ(d.json.at("old").at("errors"), d.json.at("new").at("errors"));
    EXPECT_GT(d.json.at("new").at("errors").get<long>(), 0) << name;  // something was matched
    EXPECT_EQ(d.json.at("new").at("lines").get<long>() - d.json.at("old").at("lines").get<long>(),
              10);
    EXPECT_DOUBLE_EQ(d.json.at("cycle_time_s").at("change").get<double>(), 0.0) << name;
  }
}

TEST(DiffCli, TenLinesInsertedIntoATruncatedReportChangeNoFinding) {
  const fs::path circle = ScratchDir() / "circle.nc";
  const std::string scene = (kSource / "scenes" / "circle_8in.yaml").string();
  ASSERT_EQ(RunCli("plan stitch --scene " + scene + " --path circle --mode coupled --quiet -o " +
                       circle.string(),
                   "circle_plan")
                .exit_code,
            0);
  const fs::path edited = WriteLines(InsertAfterHeader(Lines(circle), kTenComments), "circle_ten");
  const fs::path json = ScratchDir() / "circle_diff.json";
  const auto run = RunCli("diff " + circle.string() + " " + edited.string() + " --scene " + scene +
                              " -q --no-collision --report " + json.string(),
                          "circle_diff");
  EXPECT_EQ(run.exit_code, 0) << run.err << run.out;
  const Json j = Json::parse(ReadText(json));
  EXPECT_TRUE(j.at("findings").empty()) << run.out;
  bool truncated = false;
  for (const Json& r : j.at("rules")) {
    truncated = truncated || r.at("findings_truncated").at("old").get<bool>();
  }
  EXPECT_TRUE(truncated) << "the coupled circle should have a rule past the findings cap";
}

TEST(DiffCli, BadInputIsExitTwoWithTheProgrammesLine) {
  std::vector<std::string> lines = Lines(WingWindow());
  lines[6] = "G1 X-1165.86 Q7";  // an unknown word
  const fs::path bad = WriteLines(lines, "bad");
  const DiffRun d = Diff(WingWindow(), bad, "", "bad");
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find(bad.string() + ":7:"), std::string::npos) << d.err;
  EXPECT_TRUE(d.text.empty()) << d.text;
  const DiffRun old_bad = Diff(bad, WingWindow(), "", "old_bad");
  EXPECT_EQ(old_bad.exit_code, 2);
  EXPECT_NE(old_bad.err.find(bad.string() + ":7:"), std::string::npos) << old_bad.err;
  EXPECT_FALSE(fs::exists(ScratchDir() / "bad.json"));
}

}  // namespace
}  // namespace stitchsim::app
