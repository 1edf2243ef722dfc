// verify --html (S12): the page is one file with three.js and the data in it; its findings are
// the JSON report's; the robot has a pose at every line a finding points at, and that pose's
// tool point is where the trace put the tool; the same page comes from a serial and a chunked
// run; a page that cannot be written leaves nothing behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

// The page's data element, "<\/" put back.
json PageData(const std::string& page) {
  const std::string open = "<script id=\"stitchsim-data\" type=\"application/json\">";
  const std::size_t a = page.find(open);
  if (a == std::string::npos) return nullptr;
  const std::size_t b = page.find("</script>", a);
  std::string text = page.substr(a + open.size(), b - a - open.size());
  for (std::size_t at = text.find("<\\/"); at != std::string::npos; at = text.find("<\\/", at)) {
    text.replace(at, 3, "</");
  }
  return json::parse(text);
}

std::vector<unsigned char> Unbase64(const std::string& s) {
  const std::string a = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  int bits = 0, have = 0;
  for (char c : s) {
    if (c == '=') break;
    bits = (bits << 6) | static_cast<int>(a.find(c));
    have += 6;
    if (have >= 8) {
      have -= 8;
      out.push_back(static_cast<unsigned char>((bits >> have) & 255));
    }
  }
  return out;
}

template <typename T>
std::vector<T> Typed(const json& b64) {
  const std::vector<unsigned char> bytes = Unbase64(b64.get<std::string>());
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

struct PageRun {
  int exit_code = -1;
  std::string page;
  json report;
  std::string err;
};

PageRun Verify(const fs::path& nc, const std::string& extra, const std::string& tag) {
  const fs::path html = ScratchDir() / (tag + ".html"), rep = ScratchDir() / (tag + ".json");
  const auto r =
      RunCli("verify " + nc.string() + " --scene " + (kSource / "scenes/circle_8in.yaml").string() +
                 " -q --html " + html.string() + " --report " + rep.string() + extra,
             tag);
  PageRun out{r.exit_code, ReadText(html), nullptr, r.err};
  const std::string text = ReadText(rep);
  if (!text.empty()) out.report = json::parse(text);
  return out;
}

fs::path CoupledCircle() {
  const fs::path nc = ScratchDir() / "html_circle_coupled.nc";
  const auto r = RunCli("plan stitch --scene " + (kSource / "scenes/circle_8in.yaml").string() +
                            " --mode coupled --quiet -o " + nc.string(),
                        "html_plan");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nc;
}

TEST(HtmlReportCliTest, PageCarriesTheReportPosesAtEveryFindingAndTheSeries) {
  const fs::path nc = CoupledCircle();
  const PageRun run = Verify(nc, " --jobs 2 --chunk-lines 64", "html_chunked");
  ASSERT_EQ(run.exit_code, 1) << run.err;  // the coupled circle fails needle rules
  ASSERT_FALSE(run.page.empty());
  EXPECT_NE(run.page.find("REVISION"), std::string::npos);  // three.js is in the page
  const json data = PageData(run.page);
  ASSERT_FALSE(data.is_null());
  EXPECT_EQ(data["format"], "stitchsim-html-1");
  EXPECT_EQ(data["summary"]["verdict"], run.report["verdict"]);
  EXPECT_EQ(data["summary"]["stitches"], run.report["counts"]["stitches"]);
  // Every finding of the JSON report is on the page, with its position.
  std::size_t report_findings = 0;
  for (const json& rule : run.report["rules"]) report_findings += rule["findings"].size();
  ASSERT_GT(report_findings, 0u);
  ASSERT_EQ(data["findings"].size(), report_findings);
  // A pose at every finding's line, and the stitches all drawn (a small programme).
  const std::vector<std::int32_t> lines = Typed<std::int32_t>(data["poses"]["lines"]);
  const std::vector<float> q = Typed<float>(data["poses"]["q"]);
  ASSERT_EQ(q.size(), 8 * lines.size());
  for (std::size_t i = 1; i < lines.size(); ++i) ASSERT_LT(lines[i - 1], lines[i]);
  for (const json& f : data["findings"]) {
    EXPECT_TRUE(std::binary_search(lines.begin(), lines.end(), f["line"].get<int>()))
        << "no pose at line " << f["line"];
  }
  EXPECT_EQ(data["stitches"]["total"], run.report["counts"]["stitches"]);
  const std::vector<std::uint8_t> verdict = Typed<std::uint8_t>(data["stitches"]["verdict"]);
  EXPECT_EQ(static_cast<long>(verdict.size()), run.report["counts"]["stitches"].get<long>());
  EXPECT_GT(std::count(verdict.begin(), verdict.end(), 2), 0);
  // The needle side force is plotted, its largest value the rule's worst.
  bool side_force = false;
  for (const json& s : data["series"]) {
    if (s["rule"] != "needle.side_force") continue;
    side_force = true;
    const std::vector<float> mx = Typed<float>(s["max"]);
    float top = -1e30f;
    for (float v : mx) {
      if (!std::isnan(v)) top = std::max(top, v);
    }
    for (const json& rule : run.report["rules"]) {
      if (rule["id"] == "needle.side_force") {
        EXPECT_NEAR(top, rule["worst"]["value"].get<double>(), 1e-4);
      }
    }
  }
  EXPECT_TRUE(side_force);
  // The cell: the robot's eight joints and the part.
  EXPECT_EQ(data["cell"]["joints"].size(), 8u);
  EXPECT_GE(data["cell"]["part_body"].get<int>(), 0);
}

TEST(HtmlReportCliTest, SerialAndChunkedRunsWriteTheSameData) {
  const fs::path nc = CoupledCircle();
  const PageRun serial = Verify(nc, " --jobs 1", "html_serial");
  const PageRun chunked = Verify(nc, " --jobs 2 --chunk-lines 64", "html_chunked2");
  ASSERT_EQ(serial.exit_code, 1) << serial.err;
  ASSERT_EQ(chunked.exit_code, 1) << chunked.err;
  json a = PageData(serial.page), b = PageData(chunked.page);
  ASSERT_FALSE(a.is_null());
  ASSERT_FALSE(b.is_null());
  for (const char* key : {"summary", "rules", "findings", "stitches", "series", "drawings"}) {
    EXPECT_TRUE(a[key] == b[key]) << key << " differs between --jobs 1 and --jobs 2";
  }
}

TEST(HtmlReportCliTest, UnwritablePageIsExitTwoAndLeavesNothing) {
  const fs::path nc = CoupledCircle();
  const fs::path dir = ScratchDir() / "html_is_a_dir";
  fs::create_directories(dir);
  const auto r =
      RunCli("verify " + nc.string() + " --scene " + (kSource / "scenes/circle_8in.yaml").string() +
                 " -q --html " + dir.string(),
             "html_dir");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--html"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_directory(dir));
}

}  // namespace
}  // namespace stitchsim::app
