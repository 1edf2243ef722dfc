// Streaming parser. Hot path: memchr for line ends in a 1 MiB chunk, one pass over each line,
// std::from_chars for numbers; no regex, no per-character stream calls, no per-line
// allocation once the caller's Block has grown its buffers.

#include "stitchsim/program/reader.h"

#include <array>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <istream>
#include <sstream>
#include <string>
#include <utility>

#include "codes.h"

namespace stitchsim::program {

std::optional<std::string_view> ProgramHeader::Find(std::string_view key) const {
  for (const auto& [k, v] : entries) {
    if (k == key) return std::string_view(v);
  }
  return std::nullopt;
}

int ProgramHeader::LineOf(std::string_view key) const {
  for (std::size_t i = 0; i < entries.size() && i < lines.size(); ++i) {
    if (entries[i].first == key) return lines[i];
  }
  return 0;
}

namespace {

// 64 KiB: large enough for throughput, small enough that ParseString on a short text does
// not allocate (and a sanitizer build map and unmap) a megabyte per call.
constexpr std::size_t kChunkSize = std::size_t{64} << 10;
constexpr double kMaxMagnitude = 1e9;
constexpr int kMaxCodeDigits = 9;  // integer words (G M N T P) are < 1e9

enum class WordKind : std::uint8_t { kUnknown, kAxis, kFeed, kBlock, kTool, kParam, kG, kM };

struct LetterInfo {
  WordKind kind = WordKind::kUnknown;
  std::uint8_t axis = 0;
};

enum class LineKind { kBlank, kPercent, kBlock, kError };

constexpr bool IsDigit(char c) { return c >= '0' && c <= '9'; }
constexpr bool IsBlank(char c) { return c == ' ' || c == '\t'; }
constexpr bool IsInvalid(char c) {
  const auto u = static_cast<unsigned char>(c);
  return (u < 0x20 && c != '\t') || u >= 0x7f;
}

std::string Describe(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out = "byte 0x";
  out += kHex[u >> 4];
  out += kHex[u & 0xF];
  return out;
}

bool StartsWithNoCase(std::string_view text, std::string_view word) {
  if (text.size() < word.size()) return false;
  for (std::size_t k = 0; k < word.size(); ++k) {
    if ((text[k] | 0x20) != word[k]) return false;
  }
  return true;
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

}  // namespace

struct ProgramReader::Impl {
  enum class Phase { kBeforeStart, kOpened, kInProgram, kEnded };

  Impl(std::istream& in_stream, const Dialect& d, std::string file, DiagnosticSink& s, int max)
      : in(in_stream),
        dialect(d),
        file_name(std::move(file)),
        sink(s),
        max_lines(max),
        chunk(new char[kChunkSize]) {
    assert(d.max_line_length > 0 && "validate the dialect before reading with it");
    for (std::size_t a = 0; a < kAxisCount; ++a) {
      Set(d.axis_letters[a], {WordKind::kAxis, static_cast<std::uint8_t>(a)});
    }
    Set(d.feed_letter, {WordKind::kFeed, 0});
    Set(d.block_letter, {WordKind::kBlock, 0});
    Set(d.tool_letter, {WordKind::kTool, 0});
    Set(d.param_letter, {WordKind::kParam, 0});
    Set('G', {WordKind::kG, 0});
    Set('M', {WordKind::kM, 0});
    exponent_is_error = letters['E' - 'A'].kind == WordKind::kUnknown;
    carry.reserve(static_cast<std::size_t>(d.max_line_length) + 2);
  }

  void Set(char letter, LetterInfo info) {
    if (letter >= 'A' && letter <= 'Z') letters[static_cast<std::size_t>(letter - 'A')] = info;
  }

  void Error(const char* code, std::size_t index, std::string message) {
    sink.Error(code, {file_name, line_number, static_cast<int>(index) + 1}, std::move(message));
  }

  bool Refill() {
    pos = 0;
    end = 0;
    if (!in) return false;
    in.read(chunk.get(), static_cast<std::streamsize>(kChunkSize));
    end = static_cast<std::size_t>(in.gcount());
    return end > 0;
  }

  // Next physical line (without '\n'). Lines longer than the dialect limit are kept only up
  // to just past the limit (`truncated`), so memory stays bounded.
  bool ReadLine(std::string_view& line, bool& truncated) {
    truncated = false;
    bool in_carry = false;
    const std::size_t limit = static_cast<std::size_t>(dialect.max_line_length) + 2;
    for (;;) {
      if (pos == end && !Refill()) {
        if (!in_carry) return false;
        line = carry;
        return true;
      }
      const char* start = chunk.get() + pos;
      const std::size_t available = end - pos;
      const void* found = std::memchr(start, '\n', available);
      const std::size_t n = found != nullptr
                                ? static_cast<std::size_t>(static_cast<const char*>(found) - start)
                                : available;
      if (!in_carry && found != nullptr) {
        line = std::string_view(start, n);
        pos += n + 1;
        bytes_read += n + 1;
        return true;
      }
      if (!in_carry) carry.clear();
      in_carry = true;
      const std::size_t room = limit - std::min(limit, carry.size());
      if (n > room) truncated = true;
      carry.append(start, std::min(n, room));
      pos += n;
      bytes_read += n;
      if (found != nullptr) {
        ++pos;
        ++bytes_read;
        line = carry;
        return true;
      }
    }
  }

  // A real number after an axis or feed letter; `i` is just past the letter.
  bool ParseReal(std::string_view s, std::size_t& i, std::size_t letter_pos, double& out) {
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
  bool CheckNumberEnd(std::string_view s, std::size_t j) {
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
  bool ParseCode(std::string_view s, std::size_t& i, std::size_t letter_pos, int& out) {
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

  void AppendComment(Block& b, std::string_view text) {
    text = Trim(text);
    if (text.empty()) return;
    if (!b.comment.empty()) b.comment += ' ';
    b.comment.append(text.data(), text.size());
  }

  LineKind ParsePercentLine(std::string_view s, std::size_t i) {
    switch (phase) {
      case Phase::kBeforeStart:
        phase = Phase::kOpened;
        had_opening = true;
        opening_line = line_number;
        break;
      case Phase::kOpened:
        Error(codes::kDuplicateStart, i,
              "second '%' before any block (a closing '%' needs blocks before it)");
        return LineKind::kError;
      case Phase::kInProgram:
        phase = Phase::kEnded;
        break;
      case Phase::kEnded:
        break;  // handled in Next()
    }
    for (std::size_t k = i + 1; k < s.size(); ++k) {
      if (!IsBlank(s[k])) {
        Error(codes::kTextAfterPercent, k, "'%' must stand alone on its line");
        return LineKind::kError;
      }
    }
    return LineKind::kPercent;
  }

  // Handles one word whose letter is at `letter_pos`; `i` is just past the letter.
  bool ParseWord(std::string_view s, std::size_t& i, std::size_t letter_pos, Block& b,
                 std::uint32_t& seen) {
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

  bool ApplyG(int code, std::size_t letter_pos, Block& b) {
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
        const LengthUnit unit = dialect.MeaningOfG(code) == GMeaning::kInch
                                    ? LengthUnit::kInch
                                    : LengthUnit::kMillimetre;
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

  bool ApplyM(int code, std::size_t letter_pos, Block& b) {
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
  bool CheckBlock(Block& b) {
    constexpr int kMeanings = static_cast<int>(MMeaning::kUserMacro) + 1;
    int column_of[kMeanings] = {};  // column of the M code with each meaning, 0 = absent
    for (std::size_t k = 0; k < b.m_codes.size(); ++k) {
      column_of[static_cast<int>(dialect.MeaningOfM(b.m_codes[k]))] = b.columns.m_codes[k];
    }
    const auto col = [&](MMeaning m) { return column_of[static_cast<int>(m)]; };
    const std::pair<MMeaning, MMeaning> exclusive[] = {
        {MMeaning::kStitchOn, MMeaning::kStitchOff},
        {MMeaning::kHeadRetract, MMeaning::kHeadLower}};
    for (auto [first, second] : exclusive) {
      if (col(first) == 0 || col(second) == 0) continue;
      if (col(first) > col(second)) std::swap(first, second);
      Error(codes::kConflictingModes, static_cast<std::size_t>(col(second) - 1),
            "M" + std::to_string(CodeFor(second)) + " contradicts M" +
                std::to_string(CodeFor(first)) + " on the same line");
      return false;
    }
    if (col(MMeaning::kHeadSection) != 0 && !b.param) {
      Error(codes::kMissingParameter, static_cast<std::size_t>(col(MMeaning::kHeadSection) - 1),
            "M" + std::to_string(dialect.m.head_section) + " needs " + dialect.param_letter +
                "<head index>");
      return false;
    }
    if (b.param && col(MMeaning::kHeadSection) == 0) {
      Error(codes::kUnexpectedParameter, static_cast<std::size_t>(b.columns.param - 1),
            std::string(1, dialect.param_letter) + " is only used with M" +
                std::to_string(dialect.m.head_section));
      return false;
    }
    return true;
  }

  int CodeFor(MMeaning m) const {
    switch (m) {
      case MMeaning::kStitchOn:
        return dialect.m.stitch_on;
      case MMeaning::kStitchOff:
        return dialect.m.stitch_off;
      case MMeaning::kHeadRetract:
        return dialect.m.head_retract;
      case MMeaning::kHeadLower:
        return dialect.m.head_lower;
      default:
        return -1;
    }
  }

  // "(STITCHSIM key=value ...)": `text` is the comment, starting at line index `base`.
  bool ParseHeader(std::string_view text, std::size_t base) {
    constexpr std::string_view kTag = "STITCHSIM";
    if (text.substr(0, kTag.size()) != kTag) return true;
    if (text.size() > kTag.size() && !IsBlank(text[kTag.size()])) return true;
    std::size_t k = kTag.size();
    while (k < text.size()) {
      if (IsBlank(text[k])) {
        ++k;
        continue;
      }
      std::size_t e = k;
      while (e < text.size() && !IsBlank(text[e])) ++e;
      const std::string_view entry = text.substr(k, e - k);
      const std::size_t eq = entry.find('=');
      if (eq == std::string_view::npos || eq == 0 || eq + 1 == entry.size()) {
        Error(codes::kBadHeader, base + k,
              "header entry '" + std::string(entry) + "' is not key=value");
        return false;
      }
      const std::string_view key = entry.substr(0, eq);
      if (header.Find(key)) {
        Error(codes::kBadHeader, base + k, "header key '" + std::string(key) + "' given twice");
        return false;
      }
      header.entries.emplace_back(std::string(key), std::string(entry.substr(eq + 1)));
      header.lines.push_back(line_number);
      k = e;
    }
    return true;
  }

  LineKind ParseLine(std::string_view s, Block& b) {
    const char* p = s.data();
    const std::size_t n = s.size();
    std::size_t i = 0;
    while (i < n && IsBlank(p[i])) ++i;
    if (i == n) return LineKind::kBlank;
    if (p[i] == '%') return ParsePercentLine(s, i);

    std::uint32_t seen = 0;
    std::size_t first_comment_text = std::string_view::npos;
    while (i < n) {
      const char c = p[i];
      if (IsBlank(c)) {
        ++i;
        continue;
      }
      const char lower = static_cast<char>(c | 0x20);
      if (lower >= 'a' && lower <= 'z') {
        const std::size_t letter_pos = i++;
        if (!ParseWord(s, i, letter_pos, b, seen)) return LineKind::kError;
        continue;
      }
      if (c == '(') {
        std::size_t j = i + 1;
        for (; j < n && p[j] != ')'; ++j) {
          if (p[j] == '(') {
            Error(codes::kNestedComment, j, "'(' inside a comment; comments do not nest");
            return LineKind::kError;
          }
          if (IsInvalid(p[j])) {
            Error(codes::kInvalidCharacter, j,
                  Describe(p[j]) + " is not allowed (printable ASCII only)");
            return LineKind::kError;
          }
        }
        if (j == n) {
          Error(codes::kUnclosedComment, i, "comment opened here is not closed on this line");
          return LineKind::kError;
        }
        if (first_comment_text == std::string_view::npos) {
          first_comment_text = i + 1;
          while (first_comment_text < j && IsBlank(p[first_comment_text])) ++first_comment_text;
        }
        AppendComment(b, s.substr(i + 1, j - i - 1));
        i = j + 1;
        continue;
      }
      if (c == ';') {
        for (std::size_t j = i + 1; j < n; ++j) {
          if (IsInvalid(p[j])) {
            Error(codes::kInvalidCharacter, j,
                  Describe(p[j]) + " is not allowed (printable ASCII only)");
            return LineKind::kError;
          }
        }
        if (first_comment_text == std::string_view::npos) {
          first_comment_text = i + 1;
          while (first_comment_text < n && IsBlank(p[first_comment_text])) ++first_comment_text;
        }
        AppendComment(b, s.substr(i + 1));
        break;
      }
      if (c == ')') {
        Error(codes::kUnmatchedParen, i, "')' without an opening '('");
        return LineKind::kError;
      }
      if (IsDigit(c) || c == '.' || c == '+' || c == '-') {
        Error(codes::kMissingLetter, i, "number without a word letter");
        return LineKind::kError;
      }
      if (c == '%') {
        Error(codes::kInvalidCharacter, i, "'%' must stand alone on its line");
        return LineKind::kError;
      }
      Error(codes::kInvalidCharacter, i, Describe(c) + " is not allowed here");
      return LineKind::kError;
    }

    if (!b.HasWords()) {
      if (b.comment.empty()) return LineKind::kBlank;
      if (phase != Phase::kInProgram && first_comment_text != std::string_view::npos &&
          !ParseHeader(b.comment, first_comment_text)) {
        return LineKind::kError;
      }
      return LineKind::kBlock;
    }
    if (!CheckBlock(b)) return LineKind::kError;
    phase = Phase::kInProgram;
    any_words = true;
    return LineKind::kBlock;
  }

  bool Next(Block& b) {
    if (done) return false;
    std::string_view line;
    bool truncated = false;
    while (ReadLine(line, truncated)) {
      if (line_number >= max_lines) {  // the counter (an int, like every line number) is full
        sink.Error(codes::kTooManyLines, {file_name, line_number, 1},
                   "the programme goes on past line " + std::to_string(max_lines) +
                       ", the most one programme may have (docs/limits.md)");
        break;
      }
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (phase == Phase::kEnded) {
        std::size_t k = 0;
        while (k < line.size() && IsBlank(line[k])) ++k;
        if (k < line.size()) {
          Error(codes::kTextAfterEnd, k, "text after the closing '%'");
          done = true;
          return false;
        }
        continue;
      }
      const auto limit = static_cast<std::size_t>(dialect.max_line_length);
      if (truncated || line.size() > limit) {
        Error(codes::kLineTooLong, limit,
              "line longer than " + std::to_string(limit) + " characters");
        continue;
      }
      b.Clear();
      b.source_line = line_number;
      const LineKind kind = ParseLine(line, b);
      if (kind != LineKind::kBlank) last_content_line = line_number;
      if (kind == LineKind::kBlock) return true;
    }
    done = true;
    if (line_number >= max_lines) {
      b.Clear();
      return false;
    }
    if (!any_words) {
      sink.Error(codes::kEmptyProgram, {file_name, had_opening ? opening_line : 1, 1},
                 "the programme has no blocks");
    } else if (had_opening && phase != Phase::kEnded) {
      // Where the text stops is where a cut-short programme went wrong.
      sink.Error(codes::kMissingEnd, {file_name, last_content_line, 1},
                 "the programme stops here without the closing '%' of the '%' on line " +
                     std::to_string(opening_line) + " (cut short?)");
    }
    b.Clear();
    return false;
  }

  std::istream& in;
  const Dialect& dialect;
  std::string file_name;
  DiagnosticSink& sink;
  int max_lines;
  std::array<LetterInfo, 26> letters{};
  bool exponent_is_error = false;

  std::unique_ptr<char[]> chunk;
  std::size_t pos = 0;
  std::size_t end = 0;
  std::string carry;
  std::uint64_t bytes_read = 0;
  int line_number = 0;

  Phase phase = Phase::kBeforeStart;
  bool had_opening = false;
  int opening_line = 0;
  int last_content_line = 0;  // last line that was not blank
  bool any_words = false;
  bool header_read = false;
  std::optional<Block> pending;  // the first word block, held back by ReadHeader
  bool done = false;
  ProgramHeader header;
};

ProgramReader::ProgramReader(std::istream& in, const Dialect& dialect, std::string file_name,
                             DiagnosticSink& sink, int max_lines)
    : impl_(std::make_unique<Impl>(in, dialect, std::move(file_name), sink, max_lines)) {}

ProgramReader::~ProgramReader() = default;

bool ProgramReader::Next(Block& block) {
  if (impl_->pending) {
    block = std::move(*impl_->pending);
    impl_->pending.reset();
    return true;
  }
  return impl_->Next(block);
}

const ProgramHeader& ProgramReader::ReadHeader() {
  Impl& d = *impl_;
  if (!d.header_read) {
    d.header_read = true;
    Block b;
    while (d.Next(b)) {
      if (b.HasWords()) {
        d.pending = std::move(b);
        break;
      }
    }
  }
  return d.header;
}
const ProgramHeader& ProgramReader::Header() const { return impl_->header; }
int ProgramReader::LineCount() const { return impl_->line_number; }
std::uint64_t ProgramReader::BytesRead() const { return impl_->bytes_read; }
const std::string& ProgramReader::FileName() const { return impl_->file_name; }

std::vector<Block> ParseString(std::string_view text, const Dialect& dialect, std::string file_name,
                               DiagnosticSink& sink, ProgramHeader* header) {
  std::istringstream in{std::string(text)};
  ProgramReader reader(in, dialect, std::move(file_name), sink);
  std::vector<Block> blocks;
  Block block;
  while (reader.Next(block)) blocks.push_back(block);
  if (header != nullptr) *header = reader.Header();
  return blocks;
}

}  // namespace stitchsim::program
