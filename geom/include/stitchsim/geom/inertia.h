#pragma once
// Checks on rigid-body mass properties, shared by the URDF and head-spec readers.

#include <Eigen/Core>
#include <string>

namespace stitchsim::geom {

/// Why `inertia_kg_m2` cannot be a rigid body's inertia about its centre of mass (not finite,
/// not symmetric, not positive definite, principal moments breaking a + b >= c); empty when it
/// can. Tolerances are relative to the trace.
std::string InertiaProblem(const Eigen::Matrix3d& inertia_kg_m2);

}  // namespace stitchsim::geom
