#include "stitchsim/program/dialect.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "codes.h"
#include "dialect_validate.h"

namespace stitchsim::program {

std::string_view RoleName(Axis axis) {
  switch (axis) {
    case Axis::kX:
      return "x";
    case Axis::kY:
      return "y";
    case Axis::kZ:
      return "z";
    case Axis::kA:
      return "a";
    case Axis::kB:
      return "b";
    case Axis::kC:
      return "c";
    case Axis::kDrive:
      return "drive";
    case Axis::kPathLength:
      return "path_length";
    case Axis::kRail:
      return "rail";
    case Axis::kRotator:
      return "rotator";
  }
  return "?";
}

const Dialect& Dialect::Default() {
  static const Dialect kDefault;
  return kDefault;
}

GMeaning Dialect::MeaningOfG(int code) const {
  if (code == g.rapid) return GMeaning::kRapid;
  if (code == g.feed) return GMeaning::kFeed;
  if (code == g.inch) return GMeaning::kInch;
  if (code == g.millimetre) return GMeaning::kMillimetre;
  if (code == g.absolute) return GMeaning::kAbsolute;
  for (int c : g.unsupported_distance_modes) {
    if (c == code) return GMeaning::kUnsupportedDistanceMode;
  }
  for (int c : g.unsupported_motions) {
    if (c == code) return GMeaning::kUnsupportedMotion;
  }
  return GMeaning::kUnknown;
}

MMeaning Dialect::MeaningOfM(int code) const {
  if (code == m.tool_change) return MMeaning::kToolChange;
  if (code == m.stitch_on) return MMeaning::kStitchOn;
  if (code == m.stitch_off) return MMeaning::kStitchOff;
  if (code == m.head_retract) return MMeaning::kHeadRetract;
  if (code == m.head_lower) return MMeaning::kHeadLower;
  if (code == m.program_end) return MMeaning::kProgramEnd;
  if (code == m.head_section) return MMeaning::kHeadSection;
  if (code == m.tow_add) return MMeaning::kTowAdd;
  if (code == m.tow_cut) return MMeaning::kTowCut;
  if (code == m.ply_start) return MMeaning::kPlyStart;
  if (code == m.course_start) return MMeaning::kCourseStart;
  if (code == m.course_end) return MMeaning::kCourseEnd;
  if (code >= m.user_macro_first && code <= m.user_macro_last) return MMeaning::kUserMacro;
  return MMeaning::kUnknown;
}

const ToolEntry* Dialect::FindTool(int number) const {
  for (const ToolEntry& tool : tools) {
    if (tool.number == number) return &tool;
  }
  return nullptr;
}

namespace detail {
namespace {

constexpr int kMaxCode = 9999;

struct NamedLetter {
  std::string key;
  char letter;
};

struct NamedCode {
  std::string key;
  int code;
};

bool CheckCodes(const std::vector<NamedCode>& named, const KeyLocator& locate, DiagnosticSink& sink,
                char letter) {
  bool ok = true;
  for (std::size_t i = 0; i < named.size(); ++i) {
    if (named[i].code < 0 || named[i].code > kMaxCode) {
      sink.Error(codes::kDialectBadValue, locate(named[i].key),
                 named[i].key + ": code must be in 0.." + std::to_string(kMaxCode));
      ok = false;
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (named[i].code == named[j].code) {
        sink.Error(codes::kDialectDuplicateCode, locate(named[i].key),
                   named[i].key + ": " + letter + std::to_string(named[i].code) + " is already " +
                       named[j].key);
        ok = false;
      }
    }
  }
  return ok;
}

// Axis, feed, block, tool and parameter letters: one upper-case A-Z other than G and M each,
// all distinct.
bool CheckLetters(const Dialect& d, const KeyLocator& locate, DiagnosticSink& sink) {
  bool ok = true;
  std::vector<NamedLetter> letters;
  for (std::size_t i = 0; i < kAxisCount; ++i) {
    letters.push_back(
        {"letters." + std::string(RoleName(static_cast<Axis>(i))), d.axis_letters[i]});
  }
  letters.push_back({"letters.feed", d.feed_letter});
  letters.push_back({"letters.block", d.block_letter});
  letters.push_back({"letters.tool", d.tool_letter});
  letters.push_back({"letters.param", d.param_letter});
  for (std::size_t i = 0; i < letters.size(); ++i) {
    const char c = letters[i].letter;
    if (c < 'A' || c > 'Z' || c == 'G' || c == 'M') {
      sink.Error(codes::kDialectBadLetter, locate(letters[i].key),
                 letters[i].key + ": a letter must be one upper-case A-Z other than G and M");
      ok = false;
      continue;
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (letters[j].letter == c) {
        sink.Error(
            codes::kDialectDuplicateLetter, locate(letters[i].key),
            letters[i].key + ": letter '" + std::string(1, c) + "' is already " + letters[j].key);
        ok = false;
      }
    }
  }
  return ok;
}

// Euler order, default units, decimals and the line length limit.
bool CheckFormat(const Dialect& d, const KeyLocator& locate, DiagnosticSink& sink) {
  bool ok = true;
  const std::string& e = d.euler_order;
  const auto is_axis = [](char c) { return c == 'X' || c == 'Y' || c == 'Z'; };
  if (e.size() != 3 || !is_axis(e[0]) || !is_axis(e[1]) || !is_axis(e[2]) || e[0] == e[1] ||
      e[1] == e[2]) {
    sink.Error(codes::kDialectBadEulerOrder, locate("euler_order"),
               "euler_order '" + e +
                   "': three of X, Y, Z (fixed axes) with no two equal neighbours, e.g. XYZ");
    ok = false;
  }

  if (d.default_units != LengthUnit::kMillimetre && d.default_units != LengthUnit::kInch) {
    sink.Error(codes::kDialectBadValue, locate("default_units"), "default_units must be mm or in");
    ok = false;
  }
  const std::pair<const char*, int> decimals[] = {{"decimals.length", d.length_decimals},
                                                  {"decimals.angle", d.angle_decimals},
                                                  {"decimals.feed", d.feed_decimals}};
  for (const auto& [key, value] : decimals) {
    if (value < 0 || value > 9) {
      sink.Error(codes::kDialectBadValue, locate(key), std::string(key) + " must be in 0..9");
      ok = false;
    }
  }
  if (d.max_line_length < 64 || d.max_line_length > 65536) {
    sink.Error(codes::kDialectBadValue, locate("max_line_length"),
               "max_line_length must be in 64..65536");
    ok = false;
  }
  if (!(d.trajectory.ramp_time_s > 0.0 && d.trajectory.ramp_time_s <= 60.0)) {
    sink.Error(codes::kDialectBadValue, locate("trajectory.ramp_time_s"),
               "trajectory.ramp_time_s must be a number in (0, 60] seconds");
    ok = false;
  }
  if (d.trajectory.look_ahead_lines < 1 || d.trajectory.look_ahead_lines > 10000) {
    sink.Error(codes::kDialectBadValue, locate("trajectory.look_ahead_lines"),
               "trajectory.look_ahead_lines must be in 1..10000");
    ok = false;
  }
  return ok;
}

// G and M codes: in range and distinct; the user macro range clear of the named M codes.
bool CheckGAndMCodes(const Dialect& d, const KeyLocator& locate, DiagnosticSink& sink) {
  bool ok = true;
  std::vector<NamedCode> g = {{"g_codes.rapid", d.g.rapid},
                              {"g_codes.feed", d.g.feed},
                              {"g_codes.inch", d.g.inch},
                              {"g_codes.millimetre", d.g.millimetre},
                              {"g_codes.absolute", d.g.absolute}};
  for (int c : d.g.unsupported_distance_modes) {
    g.push_back({"g_codes.unsupported_distance_modes", c});
  }
  for (int c : d.g.unsupported_motions) g.push_back({"g_codes.unsupported_motions", c});
  ok = CheckCodes(g, locate, sink, 'G') && ok;

  const std::vector<NamedCode> m = {
      {"m_codes.tool_change", d.m.tool_change},   {"m_codes.stitch_on", d.m.stitch_on},
      {"m_codes.stitch_off", d.m.stitch_off},     {"m_codes.head_retract", d.m.head_retract},
      {"m_codes.head_lower", d.m.head_lower},     {"m_codes.program_end", d.m.program_end},
      {"m_codes.head_section", d.m.head_section}, {"m_codes.tow_add", d.m.tow_add},
      {"m_codes.tow_cut", d.m.tow_cut},           {"m_codes.ply_start", d.m.ply_start},
      {"m_codes.course_start", d.m.course_start}, {"m_codes.course_end", d.m.course_end}};
  ok = CheckCodes(m, locate, sink, 'M') && ok;
  if (d.m.user_macro_first < 0 || d.m.user_macro_last > kMaxCode ||
      d.m.user_macro_first > d.m.user_macro_last) {
    sink.Error(
        codes::kDialectBadValue, locate("m_codes.user_macros"),
        "user_macros must be [first, last] with 0 <= first <= last <= " + std::to_string(kMaxCode));
    ok = false;
  } else {
    for (const NamedCode& named : m) {
      if (named.code >= d.m.user_macro_first && named.code <= d.m.user_macro_last) {
        sink.Error(
            codes::kDialectDuplicateCode, locate("m_codes.user_macros"),
            "user_macros range contains " + named.key + " (M" + std::to_string(named.code) + ")");
        ok = false;
      }
    }
  }
  return ok;
}

// Tool entries: numbers in range and distinct, head names [a-z0-9_-].
bool CheckTools(const Dialect& d, const KeyLocator& locate, DiagnosticSink& sink) {
  bool ok = true;
  for (std::size_t i = 0; i < d.tools.size(); ++i) {
    const ToolEntry& tool = d.tools[i];
    const std::string key = "tools." + std::to_string(tool.number);
    if (tool.number < 0 || tool.number > kMaxCode) {
      sink.Error(codes::kDialectBadValue, locate(key),
                 "tool number must be in 0.." + std::to_string(kMaxCode));
      ok = false;
    }
    const bool bad_name =
        tool.head.empty() || std::any_of(tool.head.begin(), tool.head.end(), [](char c) {
          return !((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-');
        });
    if (bad_name) {
      sink.Error(codes::kDialectBadValue, locate(key),
                 "tool head name '" + tool.head + "' must be non-empty [a-z0-9_-]");
      ok = false;
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (d.tools[j].number == tool.number) {
        sink.Error(codes::kDialectDuplicateCode, locate(key),
                   "T" + std::to_string(tool.number) + " is listed twice");
        ok = false;
      }
    }
  }
  return ok;
}

}  // namespace

bool ValidateDialectAt(const Dialect& d, const KeyLocator& locate, DiagnosticSink& sink) {
  bool ok = CheckLetters(d, locate, sink);
  ok = CheckFormat(d, locate, sink) && ok;
  ok = CheckGAndMCodes(d, locate, sink) && ok;
  ok = CheckTools(d, locate, sink) && ok;
  return ok;
}

}  // namespace detail

bool ValidateDialect(const Dialect& dialect, const std::string& file_name, DiagnosticSink& sink) {
  return detail::ValidateDialectAt(
      dialect,
      [&file_name](std::string_view) {
        return SourceLocation{file_name, 0, 0};
      },
      sink);
}

}  // namespace stitchsim::program
