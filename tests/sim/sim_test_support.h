#pragma once
// Shared helpers for the sim tests: the cell model (loaded with no diagnostics allowed), pose
// errors and joint sampling.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/sim/kinematics.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::sim::testing {

inline std::filesystem::path CellUrdfPath() {
  return std::filesystem::path(STITCHSIM_SOURCE_DIR) / "models" / "isaac_cell.urdf";
}

inline std::filesystem::path CellMjcfPath() {
  return std::filesystem::path(STITCHSIM_SOURCE_DIR) / "models" / "isaac_cell.xml";
}

inline std::string FormatAll(const DiagnosticSink& sink) {
  std::string out;
  for (const Diagnostic& d : sink.Diagnostics()) out += FormatDiagnostic(d) + "\n";
  return out;
}

/// Fixture holding the cell model; fails on any diagnostic while loading it.
class CellTest : public ::testing::Test {
 protected:
  void SetUp() override {
    DiagnosticSink sink;
    loaded_ = LoadRobotModel(CellUrdfPath(), sink);
    ASSERT_TRUE(loaded_.has_value()) << FormatAll(sink);
    ASSERT_TRUE(sink.Diagnostics().empty()) << FormatAll(sink);
  }
  const RobotModel& model() const { return *loaded_; }

 private:
  std::optional<RobotModel> loaded_;
};

/// "1.234e-15": for recorded error figures.
inline std::string Sci(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3e", value);
  return buffer;
}

/// Translation error in metres.
inline double PositionError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

/// Rotation angle between two orientations in radians, accurate near zero.
inline double RotationError(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d r = a.transpose() * b;
  const Eigen::Vector3d vee(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
  return std::atan2(0.5 * vee.norm(), 0.5 * (r.trace() - 1.0));
}

inline double RotationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return RotationError(a.linear(), b.linear());
}

/// Uniform joints within the model limits.
inline JointVector RandomJoints(const RobotModel& model, std::mt19937_64& rng) {
  JointVector q;
  for (int i = 0; i < kNumJoints; ++i) {
    std::uniform_real_distribution<double> dist(model.lower_limits()(i), model.upper_limits()(i));
    q(i) = dist(rng);
  }
  return q;
}

}  // namespace stitchsim::sim::testing
