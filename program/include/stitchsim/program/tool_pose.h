#pragma once
// The one conversion from a machine state to the tool pose it commands: the programme's
// X Y Z (mm) and A B C (degrees, in the dialect's Euler convention) as a rigid transform of
// the part frame. The executor, the start-branch look-ahead and the CLI all use it.

#include <Eigen/Geometry>
#include <optional>

#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/modal_state.h"

namespace stitchsim::program {

/// The Euler convention of the dialect's A B C. ValidateDialect rejects a malformed order;
/// an unvalidated one falls back to XYZ (the default).
geom::EulerOrder EulerOrderOf(const Dialect& dialect);

/// The tool pose `state` commands, part frame: translation in mm from X Y Z, rotation from
/// A B C (degrees) in `order`. nullopt until all six axes are set.
std::optional<Eigen::Isometry3d> ToolPoseOf(const MachineState& state, geom::EulerOrder order);

}  // namespace stitchsim::program
