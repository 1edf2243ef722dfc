#pragma once
// The executor's start-branch look-ahead: a4 and a6 start on the 2 pi branch that keeps their
// travel over the whole programme within limits.

#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/sim/cell.h"

namespace stitchsim::sim::detail {

/// The look-ahead fed one move at a time (the chunked first pass visits every move anyway).
class StartBranchScan {
 public:
  StartBranchScan(const CellSetup& cell, geom::EulerOrder order);
  ~StartBranchScan();
  /// After a move: the modal state, its whole tool pose set.
  void Visit(const program::MachineState& st);
  /// The start joints (once, after the last move); nullopt when the first pose has no
  /// solution or no start keeps the travel within limits.
  std::optional<JointVector> Finish();
  /// Where every track stands now (kept by the first pass at each chunk's warm point) ...
  std::vector<ArmJointVector> Positions() const;
  /// ... and, after Finish, where the chosen start's track stood then, its whole turns
  /// applied: the arm's branch there (chunks seed their warm-up with it). nullopt: no start.
  std::optional<JointVector> At(const std::vector<ArmJointVector>& positions) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The start joints from a look-ahead over the whole programme when `in` can seek (back to
/// `origin`, through to the end, then back to where it stood); nullopt when it cannot, or the
/// programme has no feasible start.
std::optional<JointVector> StartBranchLookAhead(const CellSetup& cell, std::istream& in,
                                                std::streampos origin,
                                                const program::Dialect& dialect,
                                                const std::string& file_name);

}  // namespace stitchsim::sim::detail
