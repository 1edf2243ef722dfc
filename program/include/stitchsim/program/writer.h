#pragma once
// Writes blocks in canonical text: one space between words, fixed decimals from the dialect
// with trailing zeros trimmed, "-0" written as "0". Buffered; safe for millions of lines.

#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>

#include "stitchsim/program/block.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::program {

/// Word order: N, G20/G21, G90, G0/G1, axes in Axis order, F, T, M codes, P, comment.
/// `out` and `dialect` must outlive the writer; the destructor flushes.
class ProgramWriter {
 public:
  ProgramWriter(std::ostream& out, const Dialect& dialect);
  ~ProgramWriter();
  ProgramWriter(const ProgramWriter&) = delete;
  ProgramWriter& operator=(const ProgramWriter&) = delete;

  /// "%" on its own line (start or end mark).
  void WriteMark();
  /// "(STITCHSIM key=value ...)"; keys and values must not hold spaces or parentheses.
  void WriteHeader(const ProgramHeader& header);
  /// One line; a block with no words and no comment writes nothing. Values must be finite
  /// with |v| <= 1e9 (the parser rejects anything else).
  void Write(const Block& block);
  /// Hands buffered text to the stream.
  void Flush();
  std::uint64_t LinesWritten() const { return lines_written_; }

 private:
  void AppendNumber(double value, int decimals);
  void AppendInt(char letter, long long value);
  void Reserve(std::size_t bytes);

  std::ostream& out_;
  const Dialect& dialect_;
  std::string buffer_;
  std::uint64_t lines_written_ = 0;
};

/// "%", the header (if any), every block, "%" as one string. Leave `header` empty when
/// `blocks` already hold the header comment lines (as parsed programmes do).
std::string WriteProgramString(std::span<const Block> blocks, const Dialect& dialect,
                               const ProgramHeader& header = {});

}  // namespace stitchsim::program
