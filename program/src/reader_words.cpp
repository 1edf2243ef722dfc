// The words of one programme line: real numbers after axis and feed letters, integer codes
// after G, M, N, T and P, what each G and M code sets, and the checks between the words of a
// block (see reader_impl.h).
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "codes.h"
#include "reader_impl.h"

namespace stitchsim::program {

using namespace detail;  // the reader's private helpers

// A real number after an axis or feed letter; `i` is just past the letter.
bool ProgramReader::Impl::ParseReal(std::string_view s, std::size_t& i, std::size_t letter_pos,
                                    double& out) {
  const char* p = s.data();
  const std::size_t n = s.size();
  const std::size_t start = i;
  std::size_t j = i;
  bool negative = false;
  if (j < n && (p[j] == '+' || p[j] == '-')) {
    negative = p[j] == '-';
    ++j;
  }
  if (j < n && (StartsWithNoCase(s.substr(j), "nan") || StartsWithNoCase(s.substr(j), "inf"))) {
    Error(codes::kNan, start, "not a finite number: values must be plain decimals");
    return false;
  }
  const std::size_t int_begin = j;
  while (j < n && IsDigit(p[j])) ++j;
  std::size_t digits = j - int_begin;
  if (j < n && p[j] == '.') {
    const std::size_t frac_begin = ++j;
    while (j < n && IsDigit(p[j])) ++j;
    digits += j - frac_begin;
  }
  if (digits == 0) {
    if (j == start) {
      Error(codes::kMissingValue, letter_pos,
            "word '" + std::string(1, s[letter_pos]) + "' has no value");
    } else {
      Error(codes::kBadNumber, start,
            "'" + std::string(s.substr(start, j - start)) + "' is not a number");
    }
    return false;
  }
  if (!CheckNumberEnd(s, j)) return false;
  double value = 0.0;
  const char* first = negative ? p + int_begin - 1 : p + int_begin;
  const auto [ptr, ec] = std::from_chars(first, p + j, value, std::chars_format::fixed);
  if (ec == std::errc::result_out_of_range || !std::isfinite(value) ||
      std::fabs(value) > kMaxMagnitude) {
    Error(codes::kNumberOverflow, start,
          "'" + std::string(s.substr(start, j - start)) + "' is out of range (|value| <= 1e9)");
    return false;
  }
  if (ec != std::errc() || ptr != p + j) {
    Error(codes::kBadNumber, start,
          "'" + std::string(s.substr(start, j - start)) + "' is not a number");
    return false;
  }
  out = value;
  i = j;
  return true;
}

// What may follow a number: a second '.', a sign or an exponent mean a malformed number.
bool ProgramReader::Impl::CheckNumberEnd(std::string_view s, std::size_t j) {
  if (j >= s.size()) return true;
  const char c = s[j];
  if (c == '.') {
    Error(codes::kBadNumber, j, "second decimal point in a number");
    return false;
  }
  if (c == '+' || c == '-') {
    Error(codes::kBadNumber, j, "sign inside a number");
    return false;
  }
  if ((c == 'e' || c == 'E') && exponent_is_error && j + 1 < s.size() &&
      (IsDigit(s[j + 1]) || s[j + 1] == '+' || s[j + 1] == '-')) {
    Error(codes::kExponentNotAllowed, j, "exponents are not allowed; write a plain decimal");
    return false;
  }
  return true;
}

// An unsigned integer after G, M, N, T or P; `i` is just past the letter.
bool ProgramReader::Impl::ParseCode(std::string_view s, std::size_t& i, std::size_t letter_pos,
                                    int& out) {
  const char* p = s.data();
  const std::size_t n = s.size();
  const char letter = static_cast<char>(s[letter_pos] & ~0x20);
  std::size_t j = i;
  if (j < n && (p[j] == '+' || p[j] == '-')) {
    Error(codes::kSignedCode, j,
          std::string("'") + letter + "' takes an unsigned integer; no sign allowed");
    return false;
  }
  while (j < n && p[j] == '0') ++j;
  const std::size_t significant = j;
  while (j < n && IsDigit(p[j])) ++j;
  if (j < n && p[j] == '.') {
    Error(codes::kFractionalCode, j, std::string("'") + letter + "' takes an integer");
    return false;
  }
  if (j == i) {
    if (j < n && (StartsWithNoCase(s.substr(j), "nan") || StartsWithNoCase(s.substr(j), "inf"))) {
      Error(codes::kNan, j, "not a finite number: values must be plain decimals");
    } else {
      Error(codes::kMissingValue, letter_pos, std::string("word '") + letter + "' has no value");
    }
    return false;
  }
  if (!CheckNumberEnd(s, j)) return false;
  if (j - significant > kMaxCodeDigits) {
    Error(codes::kNumberOverflow, i,
          "'" + std::string(s.substr(i, j - i)) + "' is out of range (< 1e9)");
    return false;
  }
  int value = 0;
  for (std::size_t k = significant; k < j; ++k) value = value * 10 + (p[k] - '0');
  out = value;
  i = j;
  return true;
}

// Handles one word whose letter is at `letter_pos`; `i` is just past the letter.
bool ProgramReader::Impl::ParseWord(std::string_view s, std::size_t& i, std::size_t letter_pos,
                                    Block& b, std::uint32_t& seen) {
  const int letter_index = (s[letter_pos] | 0x20) - 'a';
  const char letter = static_cast<char>('A' + letter_index);
  const LetterInfo info = letters[static_cast<std::size_t>(letter_index)];
  const int column = static_cast<int>(letter_pos) + 1;
  const std::uint32_t bit = std::uint32_t{1} << letter_index;
  if (info.kind == WordKind::kUnknown) {
    Error(codes::kUnknownWord, letter_pos,
          std::string("unknown word letter '") + letter + "' in dialect '" + dialect.name + "'");
    return false;
  }
  if (info.kind != WordKind::kG && info.kind != WordKind::kM && (seen & bit) != 0) {
    Error(codes::kDuplicateWord, letter_pos,
          std::string("word '") + letter + "' appears twice on this line");
    return false;
  }
  seen |= bit;
  if (b.columns.first_word == 0) b.columns.first_word = column;

  if (info.kind == WordKind::kAxis || info.kind == WordKind::kFeed) {
    double value = 0.0;
    if (!ParseReal(s, i, letter_pos, value)) return false;
    if (info.kind == WordKind::kAxis) {
      b.axes[info.axis] = value;
      b.columns.axes[info.axis] = column;
      return true;
    }
    if (value < 0.0) {
      Error(codes::kNegativeFeed, letter_pos, "feed must be positive");
      return false;
    }
    if (value == 0.0) {
      Error(codes::kZeroFeed, letter_pos, "feed must be positive, not zero");
      return false;
    }
    b.feed = value;
    b.columns.feed = column;
    return true;
  }

  int code = 0;
  if (!ParseCode(s, i, letter_pos, code)) return false;
  switch (info.kind) {
    case WordKind::kBlock:
      b.block_number = code;
      b.columns.block_number = column;
      return true;
    case WordKind::kTool:
      if (dialect.FindTool(code) == nullptr) {
        Error(codes::kUnknownTool, letter_pos,
              std::string("no head is mounted by ") + letter + std::to_string(code));
        return false;
      }
      b.tool = code;
      b.columns.tool = column;
      return true;
    case WordKind::kParam:
      b.param = code;
      b.columns.param = column;
      return true;
    case WordKind::kG:
      return ApplyG(code, letter_pos, b);
    case WordKind::kM:
      return ApplyM(code, letter_pos, b);
    default:
      return false;
  }
}

bool ProgramReader::Impl::ApplyG(int code, std::size_t letter_pos, Block& b) {
  const int column = static_cast<int>(letter_pos) + 1;
  const auto word = [code] { return "G" + std::to_string(code); };
  switch (dialect.MeaningOfG(code)) {
    case GMeaning::kUnknown:
      Error(codes::kUnknownGCode, letter_pos, word() + " is not a G code of this dialect");
      return false;
    case GMeaning::kUnsupportedDistanceMode:
      Error(codes::kUnsupportedDistanceMode, letter_pos,
            word() + ": only absolute coordinates (G" + std::to_string(dialect.g.absolute) +
                ") are supported");
      return false;
    case GMeaning::kUnsupportedMotion:
      Error(codes::kUnsupportedMotion, letter_pos,
            word() + ": arcs are not supported; use linear moves");
      return false;
    case GMeaning::kRapid:
    case GMeaning::kFeed: {
      const Motion motion =
          dialect.MeaningOfG(code) == GMeaning::kRapid ? Motion::kRapid : Motion::kFeed;
      if (b.motion != Motion::kNone) {
        Error(b.motion == motion ? codes::kDuplicateWord : codes::kConflictingMotion, letter_pos,
              b.motion == motion ? word() + " appears twice on this line"
                                 : word() + " conflicts with the other motion code on this line");
        return false;
      }
      b.motion = motion;
      b.columns.motion = column;
      return true;
    }
    case GMeaning::kInch:
    case GMeaning::kMillimetre: {
      const LengthUnit unit =
          dialect.MeaningOfG(code) == GMeaning::kInch ? LengthUnit::kInch : LengthUnit::kMillimetre;
      if (b.units) {
        Error(*b.units == unit ? codes::kDuplicateWord : codes::kConflictingUnits, letter_pos,
              *b.units == unit ? word() + " appears twice on this line"
                               : word() + " conflicts with the other unit code on this line");
        return false;
      }
      b.units = unit;
      b.columns.units = column;
      return true;
    }
    case GMeaning::kAbsolute:
      if (b.absolute) {
        Error(codes::kDuplicateWord, letter_pos, word() + " appears twice on this line");
        return false;
      }
      b.absolute = true;
      return true;
  }
  return false;
}

bool ProgramReader::Impl::ApplyM(int code, std::size_t letter_pos, Block& b) {
  const auto word = [code] { return "M" + std::to_string(code); };
  if (dialect.MeaningOfM(code) == MMeaning::kUnknown) {
    Error(codes::kUnknownMCode, letter_pos, word() + " is not an M code of this dialect");
    return false;
  }
  for (int existing : b.m_codes) {
    if (existing == code) {
      Error(codes::kDuplicateWord, letter_pos, word() + " appears twice on this line");
      return false;
    }
  }
  if (b.m_codes.size() >= kMaxMCodesPerBlock) {
    Error(codes::kTooManyMCodes, letter_pos,
          "more than " + std::to_string(kMaxMCodesPerBlock) + " M codes on one line");
    return false;
  }
  b.columns.m_codes[b.m_codes.size()] = static_cast<int>(letter_pos) + 1;
  b.m_codes.push_back(code);
  return true;
}

// Checks between words of one block once the whole line is read.
bool ProgramReader::Impl::CheckBlock(Block& b) {
  int column_of[kMMeaningCount] = {};  // column of the M code with each meaning, 0 = absent
  for (std::size_t k = 0; k < b.m_codes.size(); ++k) {
    column_of[static_cast<int>(dialect.MeaningOfM(b.m_codes[k]))] = b.columns.m_codes[k];
  }
  const auto col = [&](MMeaning m) { return column_of[static_cast<int>(m)]; };
  const std::pair<MMeaning, MMeaning> exclusive[] = {{MMeaning::kStitchOn, MMeaning::kStitchOff},
                                                     {MMeaning::kHeadRetract, MMeaning::kHeadLower},
                                                     {MMeaning::kCourseStart, MMeaning::kCourseEnd},
                                                     {MMeaning::kTowAdd, MMeaning::kTowCut}};
  for (auto [first, second] : exclusive) {
    if (col(first) == 0 || col(second) == 0) continue;
    if (col(first) > col(second)) std::swap(first, second);
    Error(codes::kConflictingModes, static_cast<std::size_t>(col(second) - 1),
          "M" + std::to_string(CodeFor(second)) + " contradicts M" +
              std::to_string(CodeFor(first)) + " on the same line");
    return false;
  }
  return CheckParam(b, column_of);
}

// One P word per block, read by at most one of the codes that take it (each needs it).
bool ProgramReader::Impl::CheckParam(const Block& b, const int* column_of) {
  const auto col = [&](MMeaning m) { return column_of[static_cast<int>(m)]; };
  struct ParamUse {
    MMeaning meaning;
    const char* what;
    int min;
    int max;
  };
  constexpr int kAny = std::numeric_limits<int>::max();
  static constexpr ParamUse kParamUses[] = {{MMeaning::kHeadSection, "<head index>", 0, kAny},
                                            {MMeaning::kTowAdd, "<tow number>", 0, kMaxTows},
                                            {MMeaning::kTowCut, "<tow number>", 0, kMaxTows},
                                            {MMeaning::kPlyStart, "<ply number>", 1, kAny},
                                            {MMeaning::kCourseStart, "<course number>", 1, kAny}};
  const ParamUse* used = nullptr;
  for (const ParamUse& use : kParamUses) {
    if (col(use.meaning) == 0) continue;
    const std::string code = "M" + std::to_string(CodeFor(use.meaning));
    if (used != nullptr) {
      const int first = std::min(col(used->meaning), col(use.meaning));
      const int second = std::max(col(used->meaning), col(use.meaning));
      Error(codes::kConflictingModes, static_cast<std::size_t>(second - 1),
            "M codes at columns " + std::to_string(first) + " and " + std::to_string(second) +
                " both need the one " + dialect.param_letter + " word of the line");
      return false;
    }
    used = &use;
    if (!b.param) {
      Error(codes::kMissingParameter, static_cast<std::size_t>(col(use.meaning) - 1),
            code + " needs " + dialect.param_letter + use.what);
      return false;
    }
    if (*b.param < use.min || *b.param > use.max) {
      Error(codes::kMissingParameter, static_cast<std::size_t>(b.columns.param - 1),
            code + " needs " + dialect.param_letter + use.what + " from " +
                std::to_string(use.min) +
                (use.max == kAny ? std::string(" on") : " to " + std::to_string(use.max)));
      return false;
    }
  }
  if (b.param && used == nullptr) {
    Error(codes::kUnexpectedParameter, static_cast<std::size_t>(b.columns.param - 1),
          std::string(1, dialect.param_letter) + " is only used with M" +
              std::to_string(dialect.m.head_section) + ", M" + std::to_string(dialect.m.tow_add) +
              ", M" + std::to_string(dialect.m.tow_cut) + ", M" +
              std::to_string(dialect.m.ply_start) + " and M" +
              std::to_string(dialect.m.course_start));
    return false;
  }
  return true;
}
}  // namespace stitchsim::program
