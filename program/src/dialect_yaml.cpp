// Adapter from yaml-cpp to Dialect: every yaml-cpp exception and every unexpected shape
// becomes a diagnostic at the offending key.

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "codes.h"
#include "dialect_validate.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/program/dialect.h"

namespace stitchsim::program {
namespace {

class DialectLoader {
 public:
  DialectLoader(const std::string& file_name, DiagnosticSink& sink)
      : file_name_(file_name), sink_(sink) {}

  bool Load(const YAML::Node& root, Dialect& d) {
    if (!root.IsMap()) {
      Fail(codes::kDialectBadValue, root, "a dialect file is a YAML mapping of keys");
      return false;
    }
    Map(root, "",
        {
            {"name", [&](const YAML::Node& v, const std::string& p) { String(v, p, d.name); }},
            {"letters", [&](const YAML::Node& v, const std::string& p) { Letters(v, p, d); }},
            {"euler_order",
             [&](const YAML::Node& v, const std::string& p) { String(v, p, d.euler_order); }},
            {"default_units",
             [&](const YAML::Node& v, const std::string& p) { Units(v, p, d.default_units); }},
            {"decimals",
             [&](const YAML::Node& v, const std::string& p) {
               Map(v, p,
                   {
                       {"length", IntSetter(d.length_decimals)},
                       {"angle", IntSetter(d.angle_decimals)},
                       {"feed", IntSetter(d.feed_decimals)},
                   });
             }},
            {"max_line_length", IntSetter(d.max_line_length)},
            {"g_codes",
             [&](const YAML::Node& v, const std::string& p) {
               Map(v, p,
                   {
                       {"rapid", IntSetter(d.g.rapid)},
                       {"feed", IntSetter(d.g.feed)},
                       {"inch", IntSetter(d.g.inch)},
                       {"millimetre", IntSetter(d.g.millimetre)},
                       {"absolute", IntSetter(d.g.absolute)},
                       {"unsupported_distance_modes",
                        IntListSetter(d.g.unsupported_distance_modes)},
                       {"unsupported_motions", IntListSetter(d.g.unsupported_motions)},
                   });
             }},
            {"m_codes",
             [&](const YAML::Node& v, const std::string& p) {
               Map(v, p,
                   {
                       {"tool_change", IntSetter(d.m.tool_change)},
                       {"stitch_on", IntSetter(d.m.stitch_on)},
                       {"stitch_off", IntSetter(d.m.stitch_off)},
                       {"head_retract", IntSetter(d.m.head_retract)},
                       {"head_lower", IntSetter(d.m.head_lower)},
                       {"program_end", IntSetter(d.m.program_end)},
                       {"head_section", IntSetter(d.m.head_section)},
                       {"tow_add", IntSetter(d.m.tow_add)},
                       {"tow_cut", IntSetter(d.m.tow_cut)},
                       {"ply_start", IntSetter(d.m.ply_start)},
                       {"course_start", IntSetter(d.m.course_start)},
                       {"course_end", IntSetter(d.m.course_end)},
                       {"user_macros",
                        [&](const YAML::Node& r, const std::string& rp) {
                          std::vector<int> range;
                          if (IntList(r, rp, range) && range.size() != 2) {
                            Fail(codes::kDialectBadValue, r, rp + ": expected [first, last]");
                          } else if (range.size() == 2) {
                            d.m.user_macro_first = range[0];
                            d.m.user_macro_last = range[1];
                          }
                        }},
                   });
             }},
            {"tools", [&](const YAML::Node& v, const std::string& p) { Tools(v, p, d); }},
            {"trajectory",
             [&](const YAML::Node& v, const std::string& p) {
               Map(v, p,
                   {
                       {"blending",
                        [&](const YAML::Node& b, const std::string& bp) {
                          std::string mode;
                          String(b, bp, mode);
                          if (mode == "continuous" || mode == "exact_stop") {
                            d.trajectory.continuous = mode == "continuous";
                          } else if (b.IsScalar()) {
                            Fail(codes::kDialectBadValue, b,
                                 bp + ": '" + mode + "' (known: continuous, exact_stop)");
                          }
                        }},
                       {"ramp_time_s", DoubleSetter(d.trajectory.ramp_time_s)},
                       {"look_ahead_lines", IntSetter(d.trajectory.look_ahead_lines)},
                   });
             }},
        });
    return ok_;
  }

  SourceLocation Where(std::string_view key_path) const {
    const auto it = where_.find(std::string(key_path));
    if (it != where_.end()) return it->second;
    return {file_name_, 0, 0};
  }

  bool ok() const { return ok_; }

 private:
  using Handler = std::function<void(const YAML::Node&, const std::string&)>;

  SourceLocation At(const YAML::Node& node) const {
    const YAML::Mark mark = node.Mark();
    if (mark.is_null()) return {file_name_, 0, 0};
    return {file_name_, mark.line + 1, mark.column + 1};
  }

  void Fail(const char* code, const YAML::Node& node, std::string message) {
    sink_.Error(code, At(node), std::move(message));
    ok_ = false;
  }

  // Dispatches each key of a mapping to its handler; unknown and repeated keys are errors.
  void Map(const YAML::Node& node, const std::string& prefix,
           const std::vector<std::pair<std::string, Handler>>& handlers) {
    if (!node.IsMap()) {
      Fail(codes::kDialectBadValue, node, prefix + ": expected a mapping");
      return;
    }
    std::set<std::string> seen;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node key = it->first;
      const YAML::Node value = it->second;
      const std::string name = key.IsScalar() ? key.Scalar() : std::string("?");
      const std::string path = prefix.empty() ? name : prefix + "." + name;
      if (!seen.insert(name).second) {
        Fail(codes::kDialectBadValue, key, path + ": key given twice");
        continue;
      }
      const Handler* handler = nullptr;
      for (const auto& [known, h] : handlers) {
        if (known == name) handler = &h;
      }
      if (handler == nullptr) {
        std::string known_keys;
        for (const auto& [known, h] : handlers)
          known_keys += (known_keys.empty() ? "" : ", ") + known;
        Fail(codes::kDialectUnknownKey, key,
             "unknown key '" + path + "' (known here: " + known_keys + ")");
        continue;
      }
      where_[path] = At(key);
      (*handler)(value, path);
    }
  }

  bool Int(const YAML::Node& node, const std::string& path, int& out) {
    if (!node.IsScalar()) {
      Fail(codes::kDialectBadValue, node, path + ": expected an integer");
      return false;
    }
    const std::string& text = node.Scalar();
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
      Fail(codes::kDialectBadValue, node, path + ": '" + text + "' is not an integer");
      return false;
    }
    out = value;
    return true;
  }

  void Double(const YAML::Node& node, const std::string& path, double& out) {
    const std::string text = node.IsScalar() ? node.Scalar() : std::string();
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (!node.IsScalar() || text.empty() || ec != std::errc() || end != text.data() + text.size()) {
      Fail(codes::kDialectBadValue, node, path + ": expected a number");
      return;
    }
    out = value;
  }

  Handler DoubleSetter(double& out) {
    return [this, &out](const YAML::Node& v, const std::string& p) { Double(v, p, out); };
  }

  Handler IntSetter(int& out) {
    return [this, &out](const YAML::Node& v, const std::string& p) { Int(v, p, out); };
  }

  bool IntList(const YAML::Node& node, const std::string& path, std::vector<int>& out) {
    if (!node.IsSequence()) {
      Fail(codes::kDialectBadValue, node, path + ": expected a list of integers");
      return false;
    }
    std::vector<int> values;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node item = *it;
      int value = 0;
      if (!Int(item, path, value)) return false;
      values.push_back(value);
    }
    out = std::move(values);
    return true;
  }

  Handler IntListSetter(std::vector<int>& out) {
    return [this, &out](const YAML::Node& v, const std::string& p) { IntList(v, p, out); };
  }

  void String(const YAML::Node& node, const std::string& path, std::string& out) {
    if (!node.IsScalar()) {
      Fail(codes::kDialectBadValue, node, path + ": expected a string");
      return;
    }
    out = node.Scalar();
  }

  void Units(const YAML::Node& node, const std::string& path, LengthUnit& out) {
    std::string text;
    String(node, path, text);
    if (text == "mm") {
      out = LengthUnit::kMillimetre;
    } else if (text == "in") {
      out = LengthUnit::kInch;
    } else if (node.IsScalar()) {
      Fail(codes::kDialectBadValue, node, path + ": '" + text + "' is not mm or in");
    }
  }

  void Letter(const YAML::Node& node, const std::string& path, char& out) {
    if (!node.IsScalar() || node.Scalar().size() != 1 || node.Scalar()[0] < 'A' ||
        node.Scalar()[0] > 'Z') {
      Fail(codes::kDialectBadLetter, node, path + ": expected one upper-case letter A-Z");
      return;
    }
    out = node.Scalar()[0];
  }

  Handler LetterSetter(char& out) {
    return [this, &out](const YAML::Node& v, const std::string& p) { Letter(v, p, out); };
  }

  void Letters(const YAML::Node& node, const std::string& path, Dialect& d) {
    std::vector<std::pair<std::string, Handler>> handlers;
    for (std::size_t i = 0; i < kAxisCount; ++i) {
      handlers.emplace_back(std::string(RoleName(static_cast<Axis>(i))),
                            LetterSetter(d.axis_letters[i]));
    }
    handlers.emplace_back("feed", LetterSetter(d.feed_letter));
    handlers.emplace_back("block", LetterSetter(d.block_letter));
    handlers.emplace_back("tool", LetterSetter(d.tool_letter));
    handlers.emplace_back("param", LetterSetter(d.param_letter));
    Map(node, path, handlers);
  }

  void Tools(const YAML::Node& node, const std::string& path, Dialect& d) {
    if (!node.IsMap()) {
      Fail(codes::kDialectBadValue, node, path + ": expected a mapping T number -> head");
      return;
    }
    std::vector<ToolEntry> tools;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node key = it->first;
      const YAML::Node value = it->second;
      ToolEntry tool;
      const std::string key_path = path + "." + (key.IsScalar() ? key.Scalar() : "?");
      if (!Int(key, key_path, tool.number)) continue;
      String(value, key_path, tool.head);
      where_[path + "." + std::to_string(tool.number)] = At(key);
      tools.push_back(std::move(tool));
    }
    d.tools = std::move(tools);
  }

  const std::string& file_name_;
  DiagnosticSink& sink_;
  std::map<std::string, SourceLocation> where_;
  bool ok_ = true;
};

}  // namespace

std::optional<Dialect> LoadDialectFromString(std::string_view yaml, const std::string& file_name,
                                             DiagnosticSink& sink) {
  Dialect dialect = Dialect::Default();
  DialectLoader loader(file_name, sink);
  try {
    const YAML::Node root = YAML::Load(std::string(yaml));
    if (!loader.Load(root, dialect)) return std::nullopt;
  } catch (const YAML::Exception& e) {
    const SourceLocation where =
        e.mark.is_null() ? SourceLocation{file_name, 0, 0}
                         : SourceLocation{file_name, e.mark.line + 1, e.mark.column + 1};
    sink.Error(codes::kDialectYamlSyntax, where, e.msg);
    return std::nullopt;
  }
  const auto locate = [&loader](std::string_view key_path) { return loader.Where(key_path); };
  if (!detail::ValidateDialectAt(dialect, locate, sink)) return std::nullopt;
  return dialect;
}

std::optional<Dialect> LoadDialect(const std::filesystem::path& path, DiagnosticSink& sink) {
  const FileText text = ReadRegularFile(path, limits::kMaxYamlFileBytes);
  if (!text.ok()) {
    sink.Error(codes::kDialectFileNotFound, {path.string(), 0, 0},
               "cannot read dialect file: " + text.error);
    return std::nullopt;
  }
  return LoadDialectFromString(text.text, path.string(), sink);
}

}  // namespace stitchsim::program
