#pragma once
// Private to the programme reader: ProgramReader::Impl, the streaming parser's state and
// steps. reader.cpp reads lines, the header and blocks; reader_words.cpp parses the words of
// a line (numbers, codes) and checks a block.

#include <array>
#include <cassert>
#include <cstdint>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "codes.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::program::detail {

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

inline std::string Describe(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out = "byte 0x";
  out += kHex[u >> 4];
  out += kHex[u & 0xF];
  return out;
}

inline bool StartsWithNoCase(std::string_view text, std::string_view word) {
  if (text.size() < word.size()) return false;
  for (std::size_t k = 0; k < word.size(); ++k) {
    if ((text[k] | 0x20) != word[k]) return false;
  }
  return true;
}

inline std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

}  // namespace stitchsim::program::detail

namespace stitchsim::program {

struct ProgramReader::Impl {
  using LetterInfo = detail::LetterInfo;
  using LineKind = detail::LineKind;
  using WordKind = detail::WordKind;

  enum class Phase { kBeforeStart, kOpened, kInProgram, kEnded };

  Impl(std::istream& in_stream, const Dialect& d, std::string file, DiagnosticSink& s, int max)
      : in(in_stream),
        dialect(d),
        file_name(std::move(file)),
        sink(s),
        max_lines(max),
        chunk(new char[detail::kChunkSize]) {
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
    in.read(chunk.get(), static_cast<std::streamsize>(detail::kChunkSize));
    end = static_cast<std::size_t>(in.gcount());
    return end > 0;
  }

  // Next physical line (without '\n'). Lines longer than the dialect limit are kept only up
  // to just past the limit (`truncated`), so memory stays bounded.
  bool ReadLine(std::string_view& line, bool& truncated);

  // A real number after an axis or feed letter; `i` is just past the letter.
  bool ParseReal(std::string_view s, std::size_t& i, std::size_t letter_pos, double& out);

  // What may follow a number: a second '.', a sign or an exponent mean a malformed number.
  bool CheckNumberEnd(std::string_view s, std::size_t j);

  // An unsigned integer after G, M, N, T or P; `i` is just past the letter.
  bool ParseCode(std::string_view s, std::size_t& i, std::size_t letter_pos, int& out);

  void AppendComment(Block& b, std::string_view text) {
    text = detail::Trim(text);
    if (text.empty()) return;
    if (!b.comment.empty()) b.comment += ' ';
    b.comment.append(text.data(), text.size());
  }

  LineKind ParsePercentLine(std::string_view s, std::size_t i);

  // Handles one word whose letter is at `letter_pos`; `i` is just past the letter.
  bool ParseWord(std::string_view s, std::size_t& i, std::size_t letter_pos, Block& b,
                 std::uint32_t& seen);

  bool ApplyG(int code, std::size_t letter_pos, Block& b);

  bool ApplyM(int code, std::size_t letter_pos, Block& b);

  // Checks between words of one block once the whole line is read.
  bool CheckBlock(Block& b);
  bool CheckParam(const Block& b, const int* column_of);

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
      case MMeaning::kHeadSection:
        return dialect.m.head_section;
      case MMeaning::kTowAdd:
        return dialect.m.tow_add;
      case MMeaning::kTowCut:
        return dialect.m.tow_cut;
      case MMeaning::kPlyStart:
        return dialect.m.ply_start;
      case MMeaning::kCourseStart:
        return dialect.m.course_start;
      case MMeaning::kCourseEnd:
        return dialect.m.course_end;
      default:
        return -1;
    }
  }

  // "(STITCHSIM key=value ...)": `text` is the comment, starting at line index `base`.
  bool ParseHeader(std::string_view text, std::size_t base);

  LineKind ParseLine(std::string_view s, Block& b);

  bool Next(Block& b);

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

}  // namespace stitchsim::program
