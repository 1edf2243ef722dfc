// The stitch-cycle process model against hand computations: where the needle shafts are,
// how far they drift in the preform when the head turns about tool x or y, and the coupled
// (closed-form) route agreeing with the sampled window the verifier uses.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "stitchsim/common/units.h"
#include "stitchsim/process/stitch_cycle.h"

namespace stitchsim::process {
namespace {

// The RS535 as the bundled head spec describes it: 17 mm stitches, needles in from 15 % to
// 85 % of the cycle, 12 mm preform.
ProcessModel Rs535() {
  DiagnosticSink sink;
  const auto head = scene::LoadHeadSpec(
      std::filesystem::path(STITCHSIM_SOURCE_DIR) / "models/heads/rs535.yaml", sink);
  EXPECT_TRUE(head.has_value());
  ProcessModel m;
  m.needles = head->needles;
  m.phase_in = head->stitch.phase_in;
  m.phase_out = head->stitch.phase_out;
  m.preform_thickness_mm = head->stitch.preform_thickness_mm;
  m.stitch_length_mm = 5.0;
  m.nominal_width_mm = head->stitch.width_mm;
  const double t = m.preform_thickness_mm;
  m.shaft_heights_mm = {0.0, 0.25 * t, 0.5 * t, 0.75 * t, t};
  return m;
}

// Hand computation, plain trigonometry in the entry tool frame, no Eigen: the head moves
// `dx` along tool x and turns `phi` about tool y (through the tool point) over the window.
// A shaft point p at height z goes to Ry(phi) p + (dx, 0, 0); its drift across the turned
// needle axis is the proxy. The largest drift over the preform's heights z in [0, t] is at
// z = t for these motions (drift is affine in z and both terms grow with z).
double HandDrift(double x0, double ax, double az, double z, double dx, double phi) {
  // Point on the needle axis at height z: through (x0, 0, 0) along (ax, 0, az).
  const double px = x0 + ax * (z / az), pz = z;
  const double c = std::cos(phi), s = std::sin(phi);
  const double qx = c * px + s * pz + dx, qz = -s * px + c * pz;
  double ex = qx - px, ez = qz - pz;
  const double bx = c * ax + s * az, bz = -s * ax + c * az;  // turned axis
  const double along = ex * bx + ez * bz;
  ex -= along * bx;
  ez -= along * bz;
  return std::hypot(ex, ez);
}

Eigen::Isometry3d Pose(double x, double rot_y_rad) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, 0, 0);
  t.linear() = Eigen::AngleAxisd(rot_y_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return t;
}

// The audit's case: on a flat plate, one stitch line moves 0.6 mm along tool x and turns
// 1 deg about tool y. Inside the preform the catcher drifts 0.51 mm and the insertion needle
// 0.57 mm (before the fix the shafts were followed below the surface: 0.30 and 0.42).
TEST(SideForce, TurnAboutToolYDriftsTheShaftsInsideThePreform) {
  const ProcessModel m = Rs535();
  const double window = m.phase_out - m.phase_in;
  const double dx = 0.6 * window, phi = 1.0 * kDeg * window, t = m.preform_thickness_mm;
  const double inv_sqrt2 = 1.0 / std::sqrt(2.0);
  const double catcher = HandDrift(0.0, inv_sqrt2, -inv_sqrt2, t, dx, phi);
  const double insertion = HandDrift(17.0, 0.0, -1.0, t, dx, phi);
  EXPECT_NEAR(catcher, 0.508, 0.001);
  EXPECT_NEAR(insertion, 0.568, 0.001);

  // The line is placed so that the needles enter with the tool frame on the part frame (the
  // hand computation's frame): it starts 15 % of the motion before that.
  const Eigen::Isometry3d from = Pose(-0.6 * m.phase_in, -1.0 * kDeg * m.phase_in);
  const Eigen::Isometry3d to = Pose(0.6 * (1.0 - m.phase_in), 1.0 * kDeg * (1.0 - m.phase_in));
  // Route 1: the sampled window the verifier feeds.
  NeedleWindow w(m);
  w.Enter(InterpolatePose(from, to, m.phase_in));
  for (int i = 1; i <= 100; ++i) {
    w.Update(InterpolatePose(from, to, m.phase_in + window * i / 100.0));
  }
  ASSERT_EQ(w.Metrics().side_force_mm.size(), 2u);
  EXPECT_NEAR(w.Metrics().side_force_mm[0], catcher, 1e-6);
  EXPECT_NEAR(w.Metrics().side_force_mm[1], insertion, 1e-6);

  // Route 2: the planner's closed form.
  const WindowMetrics c = EvaluateCoupledStitch(m, from, to, 100);
  EXPECT_NEAR(c.side_force_mm[0], catcher, 1e-6);
  EXPECT_NEAR(c.side_force_mm[1], insertion, 1e-6);
}

// A turn about tool x: the shafts above the surface swing along -y, against the walk's axis;
// the walk cancels only the tool point's travel, so the drift is the turn times the height.
TEST(SideForce, TurnAboutToolXDriftsByHeightTimesAngle) {
  const ProcessModel m = Rs535();
  Eigen::Isometry3d to = Eigen::Isometry3d::Identity();
  to.linear() = Eigen::AngleAxisd(0.5 * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const WindowMetrics c = EvaluateCoupledStitch(m, Eigen::Isometry3d::Identity(), to, 64);
  const double turn = 0.5 * kDeg * (m.phase_out - m.phase_in);
  // Insertion needle (vertical): the top of the shaft at z = t moves t sin(turn) across it.
  EXPECT_NEAR(c.side_force_mm[1], m.preform_thickness_mm * std::sin(turn), 1e-9);
}

}  // namespace
}  // namespace stitchsim::process
