#include "stitchsim/scene/yaml_reader.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <map>
#include <system_error>
#include <vector>

#include "stitchsim/common/files.h"
#include "stitchsim/common/limits.h"
#include "yaml_alias_budget.h"

namespace stitchsim::scene::detail {
namespace {

std::string Trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

// Strict decimal: optional sign, digits, optional fraction, optional exponent. No nan/inf.
std::optional<double> ParseStrictNumber(std::string_view s, bool& not_finite) {
  not_finite = false;
  std::string t = Trim(s);
  if (t.empty()) return std::nullopt;
  const std::string lower = [&] {
    std::string l = t;
    for (auto& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return l;
  }();
  if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos) {
    not_finite = true;
    return std::nullopt;
  }
  const char* begin = t.data();
  if (*begin == '+') ++begin;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(begin, t.data() + t.size(), v);
  if (ec == std::errc::result_out_of_range) {
    not_finite = true;
    return std::nullopt;
  }
  if (ec != std::errc() || ptr != t.data() + t.size()) return std::nullopt;
  if (!std::isfinite(v)) {
    not_finite = true;
    return std::nullopt;
  }
  return v;
}

}  // namespace

std::optional<YAML::Node> YamlReader::LoadFile() {
  FileText f = ReadRegularFile(file_, limits::kMaxYamlFileBytes);
  if (!f.ok()) {
    const char* code = f.problem == FileProblem::kMissing      ? "-missing-file"
                       : f.problem == FileProblem::kTooLarge   ? "-file-too-large"
                       : f.problem == FileProblem::kNotRegular ? "-not-a-file"
                                                               : "-unreadable-file";
    sink_.Error(prefix_ + code, {file_.string(), 0, 0},
                f.problem == FileProblem::kMissing ? "file not found: " + file_.string() : f.error);
    return std::nullopt;
  }
  return LoadText(f.text);
}

std::optional<YAML::Node> YamlReader::LoadText(const std::string& text) {
  try {
    if (auto problem = FindAliasProblem(text, limits::kMaxYamlNodes)) {
      sink_.Error(prefix_ + "-yaml-alias",
                  {file_.string(), problem->mark.line + 1, problem->mark.column + 1},
                  problem->message);
      return std::nullopt;
    }
    YAML::Node root = YAML::Load(text);
    if (!root.IsDefined() || root.IsNull()) {
      sink_.Error(prefix_ + "-empty", {file_.string(), 1, 1}, "file is empty");
      return std::nullopt;
    }
    if (!CheckDuplicateKeys(root)) return std::nullopt;
    return root;
  } catch (const YAML::Exception& e) {
    sink_.Error(prefix_ + "-yaml-syntax", {file_.string(), e.mark.line + 1, e.mark.column + 1},
                "YAML syntax error: " + e.msg);
    return std::nullopt;
  }
}

bool YamlReader::CheckDuplicateKeys(const YAML::Node& root) {
  bool ok = true;
  std::vector<YAML::Node> pending{root};  // no recursion: nesting depth is the file's to choose
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (node.IsSequence()) {
      for (const auto& item : node) pending.push_back(item);
    } else if (node.IsMap()) {
      std::map<std::string, YAML::Node> seen;
      for (const auto& kv : node) {
        pending.push_back(kv.second);
        if (!kv.first.IsScalar()) continue;
        const auto [at, fresh] = seen.emplace(kv.first.Scalar(), kv.first);
        if (fresh) continue;
        Error(kv.first, "duplicate-key",
              "key '" + kv.first.Scalar() + "' appears twice in this mapping (first at line " +
                  std::to_string(at->second.Mark().line + 1) + ")");
        ok = false;
      }
    }
  }
  return ok;
}

std::optional<std::filesystem::path> YamlReader::ReferencedFile(const YAML::Node& node,
                                                                const std::string& name,
                                                                const FileRefPolicy& policy,
                                                                std::string_view what) {
  namespace fs = std::filesystem;
  const fs::path p = fs::path(name).is_absolute() ? fs::path(name) : file_.parent_path() / name;
  bool inside = policy.allow_outside;
  for (const auto& root : policy.roots) inside = inside || IsInsideFolder(p, root);
  if (!inside) {
    std::string folders;
    for (const auto& root : policy.roots)
      folders += (folders.empty() ? "" : " or ") + root.string();
    Error(node, "path-outside",
          std::string(what) + " '" + name + "' lies outside " + folders +
              " (symlinks resolved); move it there, or pass --allow-outside-paths");
    return std::nullopt;
  }
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (!fs::exists(st)) {
    Error(node, "missing-file", std::string(what) + " not found: " + p.string());
    return std::nullopt;
  }
  if (!fs::is_regular_file(st)) {
    Error(node, "not-a-file", std::string(what) + " " + p.string() + " is not a regular file");
    return std::nullopt;
  }
  return p;
}

SourceLocation YamlReader::At(const YAML::Node& node) const {
  const YAML::Mark m = node.Mark();
  if (m.is_null()) return {file_.string(), 0, 0};
  return {file_.string(), m.line + 1, m.column + 1};
}

void YamlReader::Error(const YAML::Node& node, std::string_view code, std::string message) {
  sink_.Error(prefix_ + "-" + std::string(code), At(node), std::move(message));
}

bool YamlReader::ExpectMap(const YAML::Node& node, std::string_view what) {
  if (node.IsMap()) return true;
  Error(node, "type", std::string(what) + " must be a mapping (key: value)");
  return false;
}

bool YamlReader::CheckKeys(const YAML::Node& map, std::initializer_list<std::string_view> allowed,
                           std::string_view context) {
  if (!map.IsMap()) return false;
  bool ok = true;
  for (const auto& kv : map) {
    const std::string key = kv.first.Scalar();
    bool known = false;
    for (auto a : allowed) known = known || a == key;
    if (!known) {
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      Error(kv.first, "unknown-key",
            "unknown key '" + key + "' in " + std::string(context) + " (expected one of: " + list +
                ")");
      ok = false;
    }
  }
  return ok;
}

std::optional<YAML::Node> YamlReader::Child(const YAML::Node& map, std::string_view key,
                                            bool required) {
  if (map.IsMap()) {
    for (const auto& kv : map) {
      if (kv.first.Scalar() == key) return kv.second;
    }
  }
  if (required) {
    Error(map, "missing-key", "missing required key '" + std::string(key) + "'");
  }
  return std::nullopt;
}

std::optional<double> YamlReader::Number(const YAML::Node& node, std::string_view what) {
  if (!node.IsScalar()) {
    Error(node, "type", std::string(what) + " must be a number");
    return std::nullopt;
  }
  return NumberText(node, node.Scalar(), what);
}

std::optional<double> YamlReader::NumberText(const YAML::Node& node, std::string_view text,
                                             std::string_view what) {
  bool not_finite = false;
  auto v = ParseStrictNumber(text, not_finite);
  if (!v) {
    Error(node, not_finite ? "not-finite" : "bad-number",
          std::string(what) +
              (not_finite ? " must be a finite number, got '" : " must be a number, got '") +
              node.Scalar() + "'");
  }
  return v;
}

std::optional<long> YamlReader::Integer(const YAML::Node& node, std::string_view what, long min,
                                        long max) {
  const std::optional<double> v = Number(node, what);
  if (!v) return std::nullopt;
  if (*v != std::floor(*v)) {
    Error(node, "bad-number",
          std::string(what) + " must be a whole number, got '" + node.Scalar() + "'");
    return std::nullopt;
  }
  if (*v < static_cast<double>(min) || *v > static_cast<double>(max)) {
    Error(node, "out-of-range",
          std::string(what) + " must lie in " + std::to_string(min) + ".." + std::to_string(max) +
              ", got " + node.Scalar());
    return std::nullopt;
  }
  return static_cast<long>(*v);
}

std::optional<std::string> YamlReader::String(const YAML::Node& node, std::string_view what) {
  if (!node.IsScalar()) {
    Error(node, "type", std::string(what) + " must be a string");
    return std::nullopt;
  }
  return node.Scalar();
}

std::optional<bool> YamlReader::Bool(const YAML::Node& node, std::string_view what) {
  if (node.IsScalar()) {
    const std::string& s = node.Scalar();
    if (s == "true" || s == "yes") return true;
    if (s == "false" || s == "no") return false;
  }
  Error(node, "type", std::string(what) + " must be true or false");
  return std::nullopt;
}

std::optional<double> YamlReader::Length(const YAML::Node& node, LengthUnit unit,
                                         std::string_view what) {
  if (!node.IsScalar()) {
    Error(node, "type", std::string(what) + " must be a length (number or '<n> mm|in|m')");
    return std::nullopt;
  }
  std::string s = Trim(node.Scalar());
  LengthUnit u = unit;
  // Optional unit suffix.
  std::size_t end = s.size();
  while (end > 0 && std::isalpha(static_cast<unsigned char>(s[end - 1]))) --end;
  if (end < s.size()) {
    const std::string suffix = s.substr(end);
    const std::string lower = [&] {
      std::string l = suffix;
      for (auto& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return l;
    }();
    if (lower == "nan" || lower == "inf" || lower.ends_with("nan") || lower.ends_with("inf")) {
      Error(node, "not-finite", std::string(what) + " must be finite, got '" + s + "'");
      return std::nullopt;
    }
    auto parsed = ParseLengthUnit(suffix);
    if (!parsed) {
      Error(node, "bad-unit",
            std::string(what) + ": unknown unit '" + suffix + "' (use mm, in or m)");
      return std::nullopt;
    }
    u = *parsed;
    s = Trim(s.substr(0, end));
  }
  bool not_finite = false;
  auto v = ParseStrictNumber(s, not_finite);
  if (!v) {
    Error(node, not_finite ? "not-finite" : "bad-number",
          std::string(what) + " must be a finite length, got '" + node.Scalar() + "'");
    return std::nullopt;
  }
  const double mm = *v * MmPer(u);
  if (std::abs(mm) > limits::kMaxLengthMm) {
    Error(node, "out-of-range",
          std::string(what) + " is " + node.Scalar() + ", beyond the " +
              std::to_string(static_cast<long>(limits::kMaxLengthMm)) +
              " mm (1 km) a length may have (docs/limits.md)");
    return std::nullopt;
  }
  return mm;
}

std::optional<Eigen::VectorXd> YamlReader::Vector(const YAML::Node& node, int n,
                                                  std::string_view what,
                                                  std::optional<LengthUnit> unit) {
  if (!node.IsSequence() || static_cast<int>(node.size()) != n) {
    Error(node, "type",
          std::string(what) + " must be a list of " + std::to_string(n) +
              (unit ? " lengths" : " numbers"));
    return std::nullopt;
  }
  Eigen::VectorXd v(n);
  bool ok = true;
  for (int i = 0; i < n; ++i) {
    auto x = unit ? Length(node[static_cast<std::size_t>(i)], *unit, what)
                  : Number(node[static_cast<std::size_t>(i)], what);
    if (!x) {
      ok = false;
    } else {
      v[i] = *x;
    }
  }
  if (!ok) return std::nullopt;
  return v;
}

bool YamlReader::Positive(const YAML::Node& node, double value, std::string_view what,
                          bool allow_zero) {
  if (value > 0 || (allow_zero && value == 0)) return true;
  Error(node, "out-of-range",
        std::string(what) + (allow_zero ? " must not be negative" : " must be positive") +
            ", got " + std::to_string(value));
  return false;
}

}  // namespace stitchsim::scene::detail
