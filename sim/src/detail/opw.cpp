#include "detail/opw.h"

#include <algorithm>
#include <cmath>

namespace stitchsim::sim::detail {
namespace {

// Below this |sin t5| (or wrist-centre radius, metres) the free angle is taken from the hint:
// only exact singularities, where atan2 of two rounding errors would be arbitrary.
constexpr double kExactSingularity = 1e-12;
// Slack on the elbow cosine before a pose counts as out of reach (rounding at full stretch).
constexpr double kElbowCosineSlack = 1e-12;

}  // namespace

Eigen::Isometry3d OpwForward(const OpwGeometry& g, const ArmJointVector& t) {
  const double t23 = t(1) + t(2);
  const double s2 = std::sin(t(1)), c2 = std::cos(t(1));
  const double s23 = std::sin(t23), c23 = std::cos(t23);
  const Eigen::Vector3d wrist_in_frame1(g.a1_m + g.c2_m * s2 + g.a2_m * c23 + g.c3_m * s23, g.b_m,
                                        g.c1_m + g.c2_m * c2 - g.a2_m * s23 + g.c3_m * c23);
  const Eigen::Matrix3d r1 = RotZ(t(0));
  const Eigen::Matrix3d r = r1 * RotY(t23) * RotZ(t(3)) * RotY(t(4)) * RotZ(t(5));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = r;
  pose.translation() = r1 * wrist_in_frame1 + g.c4_m * r.col(2);
  return pose;
}

ArmConfiguration OpwConfiguration(const OpwGeometry& g, const ArmJointVector& t) {
  const double psi = std::atan2(g.a2_m, g.c3_m);
  const double forearm_angle = t(1) + t(2) + psi;  // from base z towards base x, frame 1
  const double wrist_x_in_frame1 =
      g.a1_m + g.c2_m * std::sin(t(1)) + std::hypot(g.a2_m, g.c3_m) * std::sin(forearm_angle);
  ArmConfiguration config;
  config.shoulder = wrist_x_in_frame1 >= 0.0 ? Shoulder::kFront : Shoulder::kBack;
  config.elbow = WrapToPi(t(2) + psi) >= 0.0 ? Elbow::kUp : Elbow::kDown;
  config.wrist = WrapToPi(t(4)) >= 0.0 ? Wrist::kNoFlip : Wrist::kFlip;
  return config;
}

void OpwInverse(const OpwGeometry& g, const Eigen::Isometry3d& base_to_flange,
                const ArmJointVector* hint_t, ArmIkSolutions& out) {
  out.count = 0;
  const Eigen::Matrix3d& r = base_to_flange.linear();
  const Eigen::Vector3d wrist = base_to_flange.translation() - g.c4_m * r.col(2);

  const double k = std::hypot(g.a2_m, g.c3_m);  // a3 axis to wrist centre
  const double psi = std::atan2(g.a2_m, g.c3_m);
  out.min_reach_m = std::abs(g.c2_m - k);
  out.max_reach_m = g.c2_m + k;

  // Shoulder: rotate frame 1 so the wrist centre lies in its x-z plane at y = b.
  const double rho2 = wrist.x() * wrist.x() + wrist.y() * wrist.y();
  const double radial2 = rho2 - g.b_m * g.b_m;
  if (radial2 < 0.0) {  // inside the cylinder swept by the lateral offset
    out.wrist_centre_radius_m = 0.0;
    return;
  }
  const double radial = std::sqrt(radial2);
  out.wrist_centre_radius_m = radial;
  double phi = std::atan2(wrist.y(), wrist.x());
  if (std::sqrt(rho2) < kExactSingularity && hint_t != nullptr) {
    phi = (*hint_t)(0) + std::atan2(g.b_m, radial);
  }
  const double lateral = std::atan2(g.b_m, radial);
  const double dz = wrist.z() - g.c1_m;

  const std::array<double, 2> t1 = {phi - lateral, phi + lateral - kPi};
  const std::array<double, 2> dx = {radial - g.a1_m, -radial - g.a1_m};
  out.shoulder_to_wrist_front_m = std::hypot(dx[0], dz);
  out.shoulder_to_wrist_back_m = std::hypot(dx[1], dz);

  for (int shoulder = 0; shoulder < 2; ++shoulder) {
    const double s2 = dx[shoulder] * dx[shoulder] + dz * dz;
    double elbow_cos = (s2 - g.c2_m * g.c2_m - k * k) / (2.0 * g.c2_m * k);
    if (std::abs(elbow_cos) > 1.0 + kElbowCosineSlack) continue;
    elbow_cos = std::clamp(elbow_cos, -1.0, 1.0);
    const double elbow_angle = std::acos(elbow_cos);  // |t3 + psi|
    const Eigen::Matrix3d r1 = RotZ(t1[shoulder]);
    for (int elbow = 0; elbow < 2; ++elbow) {
      const double g3 = elbow == 0 ? elbow_angle : -elbow_angle;  // t3 + psi
      const double t3 = g3 - psi;
      const double t2 =
          std::atan2(dx[shoulder], dz) - std::atan2(k * std::sin(g3), g.c2_m + k * std::cos(g3));
      // Wrist: R = R1 * Ry(t23) * Rz(t4) Ry(t5) Rz(t6), a ZYZ decomposition of m.
      const Eigen::Matrix3d m = (r1 * RotY(t2 + t3)).transpose() * r;
      const double sin5 = std::hypot(m(0, 2), m(1, 2));
      const double t5 = std::atan2(sin5, m(2, 2));
      double t4 = std::atan2(m(1, 2), m(0, 2));
      if (sin5 < kExactSingularity) t4 = hint_t != nullptr ? (*hint_t)(3) : 0.0;
      for (int wrist_flip = 0; wrist_flip < 2; ++wrist_flip) {
        const double u4 = wrist_flip == 0 ? t4 : t4 + kPi;
        const double u5 = wrist_flip == 0 ? t5 : -t5;
        // t6 from what remains, so the orientation is met even where t4 is ill-conditioned.
        const Eigen::Matrix3d n = (RotZ(u4) * RotY(u5)).transpose() * m;
        const double u6 = std::atan2(n(1, 0), n(0, 0));
        ArmIkSolution& s = out.solution[static_cast<std::size_t>(out.count++)];
        s.joints_rad << t1[shoulder], t2, t3, u4, u5, u6;
        s.configuration.shoulder = shoulder == 0 ? Shoulder::kFront : Shoulder::kBack;
        s.configuration.elbow = elbow == 0 ? Elbow::kUp : Elbow::kDown;
        s.configuration.wrist = wrist_flip == 0 ? Wrist::kNoFlip : Wrist::kFlip;
        s.sin_wrist = wrist_flip == 0 ? sin5 : -sin5;
      }
    }
  }
}

}  // namespace stitchsim::sim::detail
