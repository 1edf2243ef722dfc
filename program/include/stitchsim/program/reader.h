#pragma once
// Streaming parser: one line at a time from an istream, with a fixed-size read buffer, so
// memory does not grow with file length. Bad input becomes "gcode-*" diagnostics.

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/dialect.h"

namespace stitchsim::program {

/// Key/values of "(STITCHSIM key=value ...)" comment lines before the first word block,
/// e.g. scene, head, stitch_length_mm, mode. Values are text; callers convert them.
struct ProgramHeader {
  std::vector<std::pair<std::string, std::string>> entries;  // in written order
  /// 1-based source line of each entry, parallel to `entries` (filled by the reader; empty
  /// for a header built in code). Not part of equality.
  std::vector<int> lines;

  /// The value for `key`, or nullopt.
  std::optional<std::string_view> Find(std::string_view key) const;
  /// The source line of `key`'s entry, or 0 when unknown.
  int LineOf(std::string_view key) const;
  bool empty() const { return entries.empty(); }
  friend bool operator==(const ProgramHeader& a, const ProgramHeader& b) {
    return a.entries == b.entries;
  }
};

/// Where a reader stands between two lines: what it needs to go on reading the same file from
/// there in another reader (chunked verification resumes a programme in the middle).
struct ReaderResume {
  std::uint64_t bytes = 0;  ///< offset of the next line in the file
  int line_number = 0;      ///< lines read before it
  int phase = 0;            ///< the '%' bookkeeping (reader-private values)
  bool had_opening = false;
  int opening_line = 0;
  int last_content_line = 0;
  bool any_words = false;
  ProgramHeader header;
};

/// Reads blocks from a stream. Lines with an error are reported and skipped; blank lines and
/// '%' marks are not returned. `dialect` and `sink` must outlive the reader.
class ProgramReader {
 public:
  /// More than `max_lines` lines is gcode-too-many-lines (reported once, reading stops).
  ProgramReader(std::istream& in, const Dialect& dialect, std::string file_name,
                DiagnosticSink& sink, int max_lines = limits::kMaxProgramLines);
  /// Resumes at `at` (from Resume() of a reader of the same file): `in` must stand at
  /// `at.bytes`. The header counts as read.
  ProgramReader(std::istream& in, const Dialect& dialect, std::string file_name,
                DiagnosticSink& sink, const ReaderResume& at,
                int max_lines = limits::kMaxProgramLines);
  ~ProgramReader();
  ProgramReader(const ProgramReader&) = delete;
  ProgramReader& operator=(const ProgramReader&) = delete;

  /// Fills `block` (reusing its buffers) with the next block; false at end of input, after
  /// the end-of-file checks (missing closing '%', empty programme) have been reported.
  bool Next(Block& block);

  /// Header entries seen so far (complete once the first word block has been returned).
  const ProgramHeader& Header() const;
  /// Reads up to the first block with words and returns the complete header; that block is
  /// kept and is the next one Next() returns (the comment-only lines before it are consumed),
  /// so a programme is read once even when its header decides how to run it.
  const ProgramHeader& ReadHeader();
  /// Lines read so far (1-based number of the last line read).
  int LineCount() const;
  /// Where the reader stands now, to resume there (after Next(), with no block held back by
  /// ReadHeader).
  ReaderResume Resume() const;
  /// Bytes consumed from the stream so far.
  std::uint64_t BytesRead() const;
  const std::string& FileName() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Parses a whole text (tests, small inputs). Optionally returns the header.
std::vector<Block> ParseString(std::string_view text, const Dialect& dialect, std::string file_name,
                               DiagnosticSink& sink, ProgramHeader* header = nullptr);

}  // namespace stitchsim::program
