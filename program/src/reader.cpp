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
#include "reader_impl.h"

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

using namespace detail;  // the reader's private helpers

// Next physical line (without '\n'). Lines longer than the dialect limit are kept only up
// to just past the limit (`truncated`), so memory stays bounded.
bool ProgramReader::Impl::ReadLine(std::string_view& line, bool& truncated) {
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

LineKind ProgramReader::Impl::ParsePercentLine(std::string_view s, std::size_t i) {
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

// "(STITCHSIM key=value ...)": `text` is the comment, starting at line index `base`.
bool ProgramReader::Impl::ParseHeader(std::string_view text, std::size_t base) {
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

LineKind ProgramReader::Impl::ParseLine(std::string_view s, Block& b) {
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

bool ProgramReader::Impl::Next(Block& b) {
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

ProgramReader::ProgramReader(std::istream& in, const Dialect& dialect, std::string file_name,
                             DiagnosticSink& sink, int max_lines)
    : impl_(std::make_unique<Impl>(in, dialect, std::move(file_name), sink, max_lines)) {}

ProgramReader::ProgramReader(std::istream& in, const Dialect& dialect, std::string file_name,
                             DiagnosticSink& sink, const ReaderResume& at, int max_lines)
    : ProgramReader(in, dialect, std::move(file_name), sink, max_lines) {
  Impl& d = *impl_;
  d.bytes_read = at.bytes;
  d.line_number = at.line_number;
  d.phase = static_cast<Impl::Phase>(at.phase);
  d.had_opening = at.had_opening;
  d.opening_line = at.opening_line;
  d.last_content_line = at.last_content_line;
  d.any_words = at.any_words;
  d.header = at.header;
  d.header_read = true;
}

ReaderResume ProgramReader::Resume() const {
  const Impl& d = *impl_;
  assert(!d.pending && "ReadHeader holds a block back: read it first");
  ReaderResume r;
  r.bytes = d.bytes_read;
  r.line_number = d.line_number;
  r.phase = static_cast<int>(d.phase);
  r.had_opening = d.had_opening;
  r.opening_line = d.opening_line;
  r.last_content_line = d.last_content_line;
  r.any_words = d.any_words;
  r.header = d.header;
  return r;
}

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
