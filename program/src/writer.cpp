// Canonical writer. Text is assembled in a reusable 64 KiB buffer with std::to_chars and
// handed to the stream in large writes.

#include "stitchsim/program/writer.h"

#include <cassert>
#include <charconv>
#include <cmath>
#include <ostream>
#include <sstream>
#include <string_view>

namespace stitchsim::program {
namespace {

constexpr std::size_t kBufferSize = std::size_t{1} << 16;
// Upper bound on a block's text without its comment: 16 words of at most 32 characters.
constexpr std::size_t kMaxWordsText = 16 * 32;

constexpr bool IsCommentSafe(char c) {
  const auto u = static_cast<unsigned char>(c);
  return (u >= 0x20 && u < 0x7f) || c == '\t';
}

}  // namespace

ProgramWriter::ProgramWriter(std::ostream& out, const Dialect& dialect)
    : out_(out), dialect_(dialect) {
  buffer_.reserve(kBufferSize);
}

ProgramWriter::~ProgramWriter() { Flush(); }

void ProgramWriter::Flush() {
  if (buffer_.empty()) return;
  out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

void ProgramWriter::Reserve(std::size_t bytes) {
  if (buffer_.size() + bytes > kBufferSize) Flush();
}

void ProgramWriter::AppendNumber(double value, int decimals) {
  assert(std::isfinite(value) && std::fabs(value) <= 1e9);
  char text[64];
  const auto result =
      std::to_chars(text, text + sizeof(text), value, std::chars_format::fixed, decimals);
  char* end = result.ptr;
  if (decimals > 0) {
    while (end[-1] == '0') --end;
    if (end[-1] == '.') --end;
  }
  std::string_view digits(text, static_cast<std::size_t>(end - text));
  if (digits == "-0") digits = "0";
  buffer_.append(digits);
}

void ProgramWriter::AppendInt(char letter, long long value) {
  char text[24];
  text[0] = letter;
  const auto result = std::to_chars(text + 1, text + sizeof(text), value);
  buffer_.append(text, static_cast<std::size_t>(result.ptr - text));
}

void ProgramWriter::WriteMark() {
  Reserve(2);
  buffer_ += "%\n";
  ++lines_written_;
}

void ProgramWriter::WriteHeader(const ProgramHeader& header) {
  if (header.empty()) return;
  Block block;
  block.comment = "STITCHSIM";
  for (const auto& [key, value] : header.entries) {
    block.comment += ' ';
    block.comment += key;
    block.comment += '=';
    block.comment += value;
  }
  Write(block);
}

void ProgramWriter::Write(const Block& b) {
  assert(b.m_codes.size() <= kMaxMCodesPerBlock);
  const bool has_words = b.HasWords();
  if (!has_words && b.comment.empty()) return;
  Reserve(kMaxWordsText + b.comment.size() + 4);
  const std::size_t line_start = buffer_.size();
  const auto separate = [&] {
    if (buffer_.size() != line_start) buffer_ += ' ';
  };
  if (b.block_number) {
    separate();
    AppendInt(dialect_.block_letter, *b.block_number);
  }
  if (b.units) {
    separate();
    AppendInt('G', *b.units == LengthUnit::kInch ? dialect_.g.inch : dialect_.g.millimetre);
  }
  if (b.absolute) {
    separate();
    AppendInt('G', dialect_.g.absolute);
  }
  if (b.motion != Motion::kNone) {
    separate();
    AppendInt('G', b.motion == Motion::kRapid ? dialect_.g.rapid : dialect_.g.feed);
  }
  for (std::size_t a = 0; a < kAxisCount; ++a) {
    if (!b.axes[a]) continue;
    separate();
    buffer_ += dialect_.axis_letters[a];
    AppendNumber(*b.axes[a], dialect_.DecimalsFor(static_cast<Axis>(a)));
  }
  if (b.feed) {
    separate();
    buffer_ += dialect_.feed_letter;
    AppendNumber(*b.feed, dialect_.feed_decimals);
  }
  if (b.tool) {
    separate();
    AppendInt(dialect_.tool_letter, *b.tool);
  }
  for (int m : b.m_codes) {
    separate();
    AppendInt('M', m);
  }
  if (b.param) {
    separate();
    AppendInt(dialect_.param_letter, *b.param);
  }
  if (!b.comment.empty()) {
    separate();
    // A comment holding parentheses can only be written as a ';' comment.
    const bool parens = b.comment.find_first_of("()") != std::string::npos;
    buffer_ += parens ? "; " : "(";
    for (char c : b.comment) buffer_ += IsCommentSafe(c) ? c : ' ';
    if (!parens) buffer_ += ')';
  }
  buffer_ += '\n';
  ++lines_written_;
}

std::string WriteProgramString(std::span<const Block> blocks, const Dialect& dialect,
                               const ProgramHeader& header) {
  std::ostringstream out;
  {
    ProgramWriter writer(out, dialect);
    writer.WriteMark();
    writer.WriteHeader(header);
    for (const Block& block : blocks) writer.Write(block);
    writer.WriteMark();
  }
  return out.str();
}

}  // namespace stitchsim::program
