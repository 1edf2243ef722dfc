#pragma once
// Private pieces of programme text shared by the planners.

#include "stitchsim/program/block.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::planner::detail {

/// The set-up every planned programme starts with: millimetres, absolute, then the head
/// (`T<tool> M6`). `b` is scratch space, left cleared.
inline void WriteSetup(program::ProgramWriter& w, program::Block& b,
                       const program::Dialect& dialect, int tool_number) {
  b.Clear();
  b.units = LengthUnit::kMillimetre;
  b.absolute = true;
  w.Write(b);
  b.Clear();
  b.tool = tool_number;
  b.m_codes = {dialect.m.tool_change};
  w.Write(b);
  b.Clear();
}

}  // namespace stitchsim::planner::detail
