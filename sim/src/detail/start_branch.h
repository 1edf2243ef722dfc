#pragma once
// The executor's start-branch look-ahead: a4 and a6 start on the 2 pi branch that keeps their
// travel over the whole programme within limits.

#include <istream>
#include <optional>
#include <string>

#include "stitchsim/program/dialect.h"
#include "stitchsim/sim/cell.h"

namespace stitchsim::sim::detail {

/// The start joints from a look-ahead over the whole programme when `in` can seek (back to
/// `origin`, through to the end, then back to where it stood); nullopt when it cannot, or the
/// programme has no feasible start.
std::optional<JointVector> StartBranchLookAhead(const CellSetup& cell, std::istream& in,
                                                std::streampos origin,
                                                const program::Dialect& dialect,
                                                const std::string& file_name);

}  // namespace stitchsim::sim::detail
