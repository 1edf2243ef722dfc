#pragma once
// The programme IR: one Block per source line that carries words or a comment, holding the
// values exactly as written (programme units, not yet resolved against modal state).

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/units.h"
#include "stitchsim/program/dialect.h"

namespace stitchsim::program {

enum class Motion { kNone, kRapid, kFeed };  // kRapid = G0, kFeed = G1

/// At most this many M codes on one line (more is gcode-too-many-m-codes).
inline constexpr std::size_t kMaxMCodesPerBlock = 4;

/// 1-based columns of the words of a block, for diagnostics; 0 = absent or built in code.
struct WordColumns {
  int first_word = 0;
  int block_number = 0;
  int motion = 0;
  int units = 0;
  int feed = 0;
  int tool = 0;
  int param = 0;
  std::array<int, kAxisCount> axes{};
  std::array<int, kMaxMCodesPerBlock> m_codes{};  // parallel to Block::m_codes
};

/// One line of a programme. Filled by ProgramReader, or by the planner for ProgramWriter.
struct Block {
  int source_line = 0;              // 1-based line in the source; 0 if built in code
  std::optional<int> block_number;  // N word, unitless
  Motion motion = Motion::kNone;    // G0/G1 on this line (kNone: not given here)
  std::optional<LengthUnit> units;  // G20 (kInch) / G21 (kMillimetre) on this line
  bool absolute = false;            // G90 on this line
  /// Axis words as written: lengths in the programme unit in force (mm or inch), angles in
  /// degrees; indexed by Axis. nullopt = not on this line.
  std::array<std::optional<double>, kAxisCount> axes;
  std::optional<double> feed;  // F, programme length unit per minute
  std::optional<int> tool;     // T number (head selection, see Dialect::tools)
  std::optional<int> param;    // P integer parameter (head index for M60)
  std::vector<int> m_codes;    // M codes in written order (<= kMaxMCodesPerBlock)
  std::string comment;         // comment text, trimmed; several joined by ' '
  WordColumns columns;         // where words were; reader-filled, not compared

  std::optional<double>& operator[](Axis axis) { return axes[static_cast<std::size_t>(axis)]; }
  const std::optional<double>& operator[](Axis axis) const {
    return axes[static_cast<std::size_t>(axis)];
  }
  /// True if any word (not just a comment) is present.
  bool HasWords() const;
  /// True if any axis word is present.
  bool HasAxisWords() const;
  /// Resets every field, keeping the capacity of m_codes and comment (streaming reuse).
  void Clear();
};

/// Equal content: every field except source_line and columns, which writing changes (the
/// writer drops blank lines and adds '%' marks). Doubles compare exactly.
bool operator==(const Block& a, const Block& b);

}  // namespace stitchsim::program
