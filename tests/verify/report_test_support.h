#pragma once
// Helpers shared by the report writer tests: temp files, Python readers of the JSON and
// JUnit outputs (a second parser beside nlohmann), and small text and tree helpers.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace stitchsim::verify::report_test_support {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// A file in the temp folder, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& suffix) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    static int counter = 0;
    path_ = fs::temp_directory_path() /
            ("stitchsim_report_test_" + std::string(info->name()) + "_" +
             std::to_string(::getpid()) + "_" + std::to_string(counter++) + suffix);
  }
  ~TempFile() {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const fs::path& path() const { return path_; }
  void Write(const std::string& contents) const {
    std::ofstream out(path_, std::ios::binary);
    out << contents;
    ASSERT_TRUE(out.good()) << path_;
  }
  std::string Read() const {
    std::ifstream in(path_, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

 private:
  fs::path path_;
};

// Runs `python3 script args...`; returns the exit code, or -1 if it did not exit normally.
inline int RunPython(const std::string& script, const std::vector<std::string>& args) {
  TempFile script_file(".py");
  script_file.Write(script);
  std::string command = "python3 '" + script_file.path().string() + "'";
  for (const std::string& arg : args) command += " '" + arg + "'";
  const int status = std::system(command.c_str());
  return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Strict JSON (NaN / Infinity rejected, UTF-8 required), written back with sorted keys.
inline constexpr const char* kPythonJsonCheck = R"py(
import json, sys
def reject(constant):
    raise ValueError("not JSON: " + constant)
with open(sys.argv[1], encoding="utf-8") as f:
    data = json.load(f, parse_constant=reject)
assert data["stitchsim_report"] == 1
with open(sys.argv[2], "w", encoding="utf-8") as f:
    json.dump(data, f, sort_keys=True, ensure_ascii=False)
)py";

// Parses the JUnit XML with ElementTree, checks the structure CI consumers rely on, and
// writes the parsed tree as JSON for the C++ side to compare with the report.
inline constexpr const char* kPythonJunitCheck = R"py(
import json, sys
import xml.etree.ElementTree as E
root = E.parse(sys.argv[1]).getroot()
assert root.tag == "testsuites", root.tag
assert root.get("name") == "stitchsim"
suites = list(root)
assert len(suites) == 1 and suites[0].tag == "testsuite", suites
suite = suites[0]
assert [c.tag for c in suite][:1] == ["properties"], [c.tag for c in suite]
cases = list(suite)[1:]
assert all(c.tag == "testcase" for c in cases)
assert int(root.get("tests")) == int(suite.get("tests")) == len(cases)
failed = [c for c in cases if c.find("failure") is not None]
assert int(root.get("failures")) == int(suite.get("failures")) == len(failed)
skipped = [c for c in cases if c.find("skipped") is not None]
assert int(root.get("skipped")) == int(suite.get("skipped")) == len(skipped)
assert suite.get("errors") == "0"
for c in cases:
    assert c.get("classname") == suite.get("name")
    assert c.get("name")
    assert len(c.findall("failure")) <= 1
    for f in c.findall("failure"):
        assert f.get("message") and f.get("type") == c.get("name")
def tree(e):
    return {"tag": e.tag, "attrib": dict(e.attrib), "text": e.text or "",
            "children": [tree(c) for c in e]}
with open(sys.argv[2], "w", encoding="utf-8") as f:
    json.dump(tree(root), f, ensure_ascii=False)
)py";

// The JUnit XML as parsed by Python, as a tree of {tag, attrib, text, children}.
inline Json ParseJunitWithPython(const std::string& xml) {
  TempFile in(".xml");
  TempFile out(".json");
  in.Write(xml);
  EXPECT_EQ(RunPython(kPythonJunitCheck, {in.path().string(), out.path().string()}), 0) << xml;
  return Json::parse(out.Read(), nullptr, /*allow_exceptions=*/false);
}

inline std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The child of `suite` whose name attribute is `name` (the <properties> child has none: const
// operator[] on a missing key is undefined, so look it up with value()).
inline const nlohmann::json* FindCase(const nlohmann::json& suite, const std::string& name) {
  for (const nlohmann::json& c : suite.at("children")) {
    if (c.at("attrib").value("name", std::string()) == name) return &c;
  }
  return nullptr;
}

}  // namespace stitchsim::verify::report_test_support
