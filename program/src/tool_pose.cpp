#include "stitchsim/program/tool_pose.h"

#include "stitchsim/common/units.h"

namespace stitchsim::program {
namespace {

// Degrees to radians as a multiplication by pi/180 (not deg * pi / 180): the executor's
// traces and reports were made with this rounding.

}  // namespace

geom::EulerOrder EulerOrderOf(const Dialect& dialect) {
  return geom::ParseEulerOrder(dialect.euler_order).value_or(geom::EulerOrder{});
}

std::optional<Eigen::Isometry3d> ToolPoseOf(const MachineState& state, geom::EulerOrder order) {
  for (Axis a : {Axis::kX, Axis::kY, Axis::kZ, Axis::kA, Axis::kB, Axis::kC}) {
    if (!state[a]) return std::nullopt;
  }
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.translation() = Eigen::Vector3d(*state[Axis::kX], *state[Axis::kY], *state[Axis::kZ]);
  tool.linear() = geom::RotationFromEuler(
      order, Eigen::Vector3d(*state[Axis::kA], *state[Axis::kB], *state[Axis::kC]) * kDeg);
  return tool;
}

}  // namespace stitchsim::program
