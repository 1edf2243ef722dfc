#pragma once
// Modal state tracking: turns successive blocks into absolute commands in millimetres and
// degrees, carrying forward everything a block does not set. The simulator consumes this.

#include <array>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::program {

/// The machine's modal state after a block. Absolute, part frame; filled by ModalState.
struct MachineState {
  /// Indexed by Axis: X Y Z, drive U, path length V, rail E in mm; A B C, rotator W in
  /// degrees. nullopt until a block first sets the axis.
  std::array<std::optional<double>, kAxisCount> axes;
  std::optional<double> feed_mm_per_min;       // last F, converted to mm/min
  Motion motion = Motion::kNone;               // modal G0/G1; kNone until first given
  LengthUnit units = LengthUnit::kMillimetre;  // programme unit in force (G20/G21)
  bool stitching = false;                      // M10 on, M11 off
  bool head_retracted = false;                 // M20 retract, M21 lower
  std::optional<int> selected_tool;            // last T word (preselection)
  std::optional<int> active_tool;              // T number mounted by the last M6
  std::optional<int> head_section;             // P of the last M60
  /// AFP tows laying (bit i = tow i + 1): M62 P<n> sets bit n - 1 (P0: every bit), M63
  /// clears it. Tows lay material only on feed moves with the head lowered (docs/afp.md).
  std::uint64_t tows = 0;
  int ply = 0;                 // P of the last M70 (0: before any ply)
  int course = 0;              // P of the open M71 course, 0 outside a course (after M72)
  bool program_ended = false;  // M30 seen

  const std::optional<double>& operator[](Axis axis) const {
    return axes[static_cast<std::size_t>(axis)];
  }
};

/// What one block asked for, resolved against the state before it. Filled by ModalState.
struct Step {
  int source_line = 0;
  bool is_move = false;             // the block had axis words: move from Previous() to State()
  Motion motion = Motion::kNone;    // motion used for the move (modal); kNone if !is_move
  bool tool_changed = false;        // M6 on this block (applied before the move)
  bool program_end = false;         // M30 on this block (applied after the move)
  std::optional<int> head_section;  // M60 P<n> on this block (applied before the move)
  std::vector<int> user_macros;     // M100..M199 on this block, in written order
  bool tows_changed = false;        // M62/M63 on this block (applied before the move)
};

/// Applies blocks in order. Order within a block: G20/G21, F, G0/G1, T, M6, M10/M11,
/// M20/M21, M60, then the move, then M30. Reports semantic errors (motion mode or feed
/// missing, M6 without T, words after M30) at the block's line and word column.
class ModalState {
 public:
  /// `dialect` and `sink` must outlive the tracker.
  ModalState(const Dialect& dialect, std::string file_name, DiagnosticSink& sink);

  /// Applies one block; the returned Step is valid until the next Update.
  const Step& Update(const Block& block);

  const MachineState& State() const { return state_; }        // after the last block
  const MachineState& Previous() const { return previous_; }  // before the last block
  /// Takes up the states of another tracker (chunked verification resumes a programme in the
  /// middle: the state after the last block read, and before it).
  void Restore(const MachineState& state, const MachineState& previous) {
    state_ = state;
    previous_ = previous;
  }
  /// Head orientation angles (A, B, C) in radians, if all three are known.
  std::optional<std::array<double, 3>> AnglesRad() const;

 private:
  void Error(const char* code, const Block& block, int column, std::string message);
  void ApplyTow(const Block& block, std::size_t k);
  bool ApplyMCodes(const Block& block);

  const Dialect& dialect_;
  std::string file_name_;
  DiagnosticSink& sink_;
  MachineState state_;
  MachineState previous_;
  Step step_;
};

/// What CheckProgram saw.
struct CheckSummary {
  int lines = 0;             // lines read
  std::uint64_t blocks = 0;  // blocks returned by the reader (comment lines included)
  std::uint64_t moves = 0;   // blocks with axis words
  ProgramHeader header;
  bool ok = false;  // no errors were reported
};

/// Reads a whole programme through ProgramReader and ModalState (what `stitchsim check`
/// needs), streaming.
CheckSummary CheckProgram(std::istream& in, const Dialect& dialect, std::string file_name,
                          DiagnosticSink& sink);

}  // namespace stitchsim::program
