#include "stitchsim/process/stitch_cycle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "stitchsim/common/units.h"

namespace stitchsim::process {
namespace {

// Point of needle `n` on its axis at tool-frame height z_mm (the preform lies at tool z in
// [0, thickness], between the stitching surface and the head).
Eigen::Vector3d ShaftPoint(const scene::NeedleSpec& n, double z_mm) {
  return n.through_mm + n.direction * ((z_mm - n.through_mm.z()) / n.direction.z());
}

}  // namespace

ProcessModel MakeProcessModel(const scene::Scene& scene, double stitch_length_mm) {
  ProcessModel m;
  m.needles = scene.head.needles;
  m.phase_in = scene.head.stitch.phase_in;
  m.phase_out = scene.head.stitch.phase_out;
  m.walk_capacity_mm = scene.head.stitch.walk_capacity_mm;
  m.preform_thickness_mm = scene.preform_thickness_mm;
  m.stitch_length_mm = stitch_length_mm;
  m.nominal_width_mm = scene.head.stitch.width_mm;
  const double t = m.preform_thickness_mm;
  m.shaft_heights_mm = {0.0, 0.25 * t, 0.5 * t, 0.75 * t, t};
  return m;
}

double CyclePhase(double drive_mm, double stitch_length_mm) {
  double phase = std::fmod(drive_mm / stitch_length_mm, 1.0);
  if (phase < 0) phase += 1.0;
  // Drive values that are whole stitches up to rounding are at phase 0.
  if (phase > 1.0 - 1e-9) phase = 0.0;
  return phase;
}

bool NeedlesIn(const ProcessModel& model, double phase) {
  return phase >= model.phase_in && phase <= model.phase_out;
}

double WindowMetrics::MaxSideForceMm() const {
  double m = 0.0;
  for (double v : side_force_mm) m = std::max(m, v);
  return m;
}

NeedleWindow::NeedleWindow(const ProcessModel& model) : model_(&model) {}

void NeedleWindow::Enter(const Eigen::Isometry3d& tool, const Eigen::Isometry3d* walk_reference) {
  active_ = true;
  entry_ = tool;
  entry_reference_ = (walk_reference != nullptr ? *walk_reference : tool).translation();
  metrics_ = WindowMetrics{};
  metrics_.side_force_mm.assign(model_->needles.size(), 0.0);
  entry_points_.assign(model_->needles.size(), {});
  for (std::size_t k = 0; k < model_->needles.size(); ++k) {
    for (double z : model_->shaft_heights_mm) {
      entry_points_[k].push_back(tool * ShaftPoint(model_->needles[k], z));
    }
  }
}

void NeedleWindow::Update(const Eigen::Isometry3d& tool, const Eigen::Isometry3d* walk_reference) {
  if (!active_) return;
  // The walk moves both needles along head y, matched to the catcher (the tool point): it
  // cancels the tool point's travel along the head's current y axis. It runs with the drive,
  // so it follows the commanded travel; an arm lagging its command drifts the needles.
  const Eigen::Isometry3d& reference = walk_reference != nullptr ? *walk_reference : tool;
  const Eigen::Vector3d travel = reference.translation() - entry_reference_;
  const Eigen::Vector3d y = reference.linear().col(1);
  const double walk = -y.dot(travel);
  metrics_.walk_demand_mm = std::max(metrics_.walk_demand_mm, std::abs(walk));
  const Eigen::Vector3d walk_offset(0.0, walk, 0.0);
  for (std::size_t k = 0; k < model_->needles.size(); ++k) {
    const scene::NeedleSpec& n = model_->needles[k];
    const Eigen::Vector3d axis = tool.linear() * n.direction;
    for (std::size_t j = 0; j < model_->shaft_heights_mm.size(); ++j) {
      const Eigen::Vector3d now = tool * (ShaftPoint(n, model_->shaft_heights_mm[j]) + walk_offset);
      Eigen::Vector3d drift = now - entry_points_[k][j];
      drift -= drift.dot(axis) * axis;  // motion along the needle is the stitch itself
      metrics_.side_force_mm[k] = std::max(metrics_.side_force_mm[k], drift.norm());
    }
  }
  const Eigen::AngleAxisd rel(entry_.linear().transpose() * tool.linear());
  const Eigen::Vector3d rv = rel.axis() * rel.angle();
  metrics_.rotation_rad = metrics_.rotation_rad.cwiseMax(rv.cwiseAbs());
  metrics_.rotation_total_rad = std::max(metrics_.rotation_total_rad, std::abs(rel.angle()));
}

Eigen::Isometry3d InterpolatePose(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                                  double s) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = (1.0 - s) * from.translation() + s * to.translation();
  const Eigen::Quaterniond a(from.linear());
  const Eigen::Quaterniond b(to.linear());
  out.linear() = a.slerp(s, b).toRotationMatrix();
  return out;
}

namespace {

// A vector term of the coupled-stitch drift, as plain doubles for the sample loops.
struct Vec3 {
  double x, y, z;
  Vec3() = default;  // left uninitialised: filled before use
  explicit Vec3(const Eigen::Vector3d& v) : x(v.x()), y(v.y()), z(v.z()) {}
};

// One needle of EvaluateCoupledStitch: its axis and two shaft points (lowest and highest),
// each as entry value + sin * A-term + versine * B-term (see there).
struct CoupledNeedle {
  Vec3 axis0, axis_a, axis_b;
  Vec3 point_a[2], point_b[2];
  double max_sq;
};

// The slerp from `from` to `to` as one turn of `angle` (in [0, pi]) about `axis` (unit, in
// the `from` frame); angle 0 (axis z) when the rotations are equal.
void SlerpTurn(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to, double& angle,
               Eigen::Vector3d& axis) {
  angle = 0.0;
  axis = Eigen::Vector3d::UnitZ();
  if (from.linear() == to.linear()) return;  // a straight row repeats its frame exactly
  const Eigen::Quaterniond qa(from.linear());
  Eigen::Quaterniond qb(to.linear());
  if (qa.dot(qb) < 0.0) qb.coeffs() = -qb.coeffs();  // the short way, as slerp goes
  const Eigen::Quaterniond rel = qa.conjugate() * qb;
  const double vec_norm = rel.vec().norm();
  angle = 2.0 * std::atan2(vec_norm, std::abs(rel.w()));
  if (vec_norm > 0.0) axis = rel.vec() / vec_norm;
}

// Each needle's axis and its lowest and highest shaft points, as entry value (r_in) +
// sin * A-term (a_mat) + versine * B-term (b_mat).
void PrepareNeedles(const ProcessModel& model, const Eigen::Matrix3d& r_in,
                    const Eigen::Matrix3d& a_mat, const Eigen::Matrix3d& b_mat,
                    std::span<CoupledNeedle> needles) {
  double z[2] = {0.0, 0.0};
  if (!model.shaft_heights_mm.empty()) {
    const auto [lo, hi] =
        std::minmax_element(model.shaft_heights_mm.begin(), model.shaft_heights_mm.end());
    z[0] = *lo;
    z[1] = *hi;
  }
  for (std::size_t n = 0; n < needles.size(); ++n) {
    const scene::NeedleSpec& spec = model.needles[n];
    CoupledNeedle& nd = needles[n];
    nd.max_sq = 0.0;
    nd.axis0 = Vec3(r_in * spec.direction);
    nd.axis_a = Vec3(a_mat * spec.direction);
    nd.axis_b = Vec3(b_mat * spec.direction);
    for (int j = 0; j < 2; ++j) {
      const Eigen::Vector3d p = ShaftPoint(spec, z[j]);
      nd.point_a[j] = Vec3(a_mat * p);
      nd.point_b[j] = Vec3(b_mat * p);
    }
  }
}

// One block of `count` samples (sin sn, versine vs, shared drift h) for one needle: the
// largest squared drift of its shaft points across the needle, into nd.max_sq. q0 and q1 are
// scratch space of `count`.
inline void SideDriftBlock(int count, const double* sn, const double* vs, const double* hx,
                           const double* hy, const double* hz, double* q0, double* q1,
                           CoupledNeedle& nd) {
  for (int j = 0; j < count; ++j) {
    const double ax = nd.axis0.x + sn[j] * nd.axis_a.x + vs[j] * nd.axis_b.x;
    const double ay = nd.axis0.y + sn[j] * nd.axis_a.y + vs[j] * nd.axis_b.y;
    const double az = nd.axis0.z + sn[j] * nd.axis_a.z + vs[j] * nd.axis_b.z;
    double* q[2] = {q0, q1};
    for (int p = 0; p < 2; ++p) {
      double dx = sn[j] * nd.point_a[p].x + vs[j] * nd.point_b[p].x + hx[j];
      double dy = sn[j] * nd.point_a[p].y + vs[j] * nd.point_b[p].y + hy[j];
      double dz = sn[j] * nd.point_a[p].z + vs[j] * nd.point_b[p].z + hz[j];
      // Motion along the needle is the stitch itself.
      const double along = dx * ax + dy * ay + dz * az;
      dx -= along * ax;
      dy -= along * ay;
      dz -= along * az;
      q[p][j] = dx * dx + dy * dy + dz * dz;
    }
  }
  for (int j = 0; j < count; ++j) nd.max_sq = std::max(nd.max_sq, std::max(q0[j], q1[j]));
}

}  // namespace

// The metrics NeedleWindow gives for InterpolatePose at the phases
//   phase_in + (phase_out - phase_in) * i / samples,  i = 0 (entry) .. samples,
// computed without a quaternion conversion per sample (the planner calls this for every
// stitch). The drive advances linearly along the line, so line fraction = cycle phase.
//  - Slerp turns about one axis (in the `from` frame) at a constant rate:
//    R(s) = R_from Rot(axis, s angle). From the entry, sample i is turned by Rot(axis,
//    i delta), delta = angle (phase_out - phase_in) / samples, so
//    R_i = R_in (I + sin K + vers K^2) = R_in + sin A + vers B  (K = [axis]x), with sin
//    and versine of i delta from the angle-addition recurrence. The rotation since entry
//    grows with i: its largest value is at the last sample.
//  - A shaft point p drifts by (R_i - R_in) p + walk R_i e_y + travel: affine in its
//    height, with a convex norm, so over the shaft heights the largest drift is at the
//    lowest or the highest one.
//  - With no rotation every drift and the walk scale with the travel, so the last sample
//    holds every maximum.
WindowMetrics EvaluateCoupledStitch(const ProcessModel& model, const Eigen::Isometry3d& from,
                                    const Eigen::Isometry3d& to, int samples) {
  WindowMetrics m;
  m.side_force_mm.assign(model.needles.size(), 0.0);
  if (samples < 1) return m;

  double angle = 0.0;  // [0, pi]
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  SlerpTurn(from, to, angle, axis);

  const double s_in = model.phase_in;
  const double span = model.phase_out - model.phase_in;
  const Eigen::Matrix3d r_in =
      angle == 0.0 ? from.linear()
                   : Eigen::Matrix3d(from.linear() *
                                     Eigen::AngleAxisd(s_in * angle, axis).toRotationMatrix());
  const Eigen::Vector3d t_in = (1.0 - s_in) * from.translation() + s_in * to.translation();
  Eigen::Matrix3d k;
  k << 0.0, -axis.z(), axis.y(), axis.z(), 0.0, -axis.x(), -axis.y(), axis.x(), 0.0;
  const Eigen::Matrix3d a_mat = r_in * k;
  const Eigen::Matrix3d b_mat = a_mat * k;

  const double total = std::abs(span) * angle;  // rotation since entry at the last sample
  m.rotation_rad = axis.cwiseAbs() * total;
  m.rotation_total_rad = total;

  const bool have_heights = !model.shaft_heights_mm.empty();
  // Heads have one or two needles: no allocation (and no zeroing) for those.
  std::array<CoupledNeedle, 2> few;
  std::vector<CoupledNeedle> many;
  if (model.needles.size() > few.size()) many.resize(model.needles.size());
  const std::span<CoupledNeedle> needles =
      many.empty() ? std::span<CoupledNeedle>(few.data(), model.needles.size())
                   : std::span<CoupledNeedle>(many);
  PrepareNeedles(model, r_in, a_mat, b_mat, needles);
  const Vec3 y0(r_in.col(1)), ya(a_mat.col(1)), yb(b_mat.col(1));

  const double half = 0.5 * span * angle / samples;
  const double sin_half = std::sin(half);
  const double sin_d = 2.0 * sin_half * std::cos(half);
  const double vers_d = 2.0 * sin_half * sin_half;
  double sin_prev = 0.0, vers_prev = 0.0;  // of (i - 1) delta

  // Samples in blocks of plain arrays, so the per-sample arithmetic vectorises.
  constexpr int kBlock = 32;
  double sn[kBlock], vs[kBlock], hx[kBlock], hy[kBlock], hz[kBlock], q0[kBlock], q1[kBlock];
  // No rotation: the last sample only (sin and versine stay 0).
  const int first = angle == 0.0 ? samples : 1;
  for (int block = first; block <= samples; block += kBlock) {
    const int count = std::min(kBlock, samples - block + 1);
    for (int j = 0; j < count; ++j) {
      // sin and versine of i delta = (i - 1) delta + delta; the versine keeps its relative
      // precision at small angles.
      sn[j] = sin_prev * (1.0 - vers_d) + (1.0 - vers_prev) * sin_d;
      vs[j] = vers_prev + vers_d - vers_prev * vers_d + sin_prev * sin_d;
      sin_prev = sn[j];
      vers_prev = vs[j];
      const double s = s_in + span * static_cast<double>(block + j) / samples;
      const Eigen::Vector3d travel = ((1.0 - s) * from.translation() + s * to.translation()) - t_in;
      hx[j] = travel.x();
      hy[j] = travel.y();
      hz[j] = travel.z();
    }
    // Walk (cancels the tool point's travel along the current head y) and the drift every
    // shaft point shares: walk R_i e_y + travel.
    double walk_max = m.walk_demand_mm;
    for (int j = 0; j < count; ++j) {
      const double yx = y0.x + sn[j] * ya.x + vs[j] * yb.x;
      const double yy = y0.y + sn[j] * ya.y + vs[j] * yb.y;
      const double yz = y0.z + sn[j] * ya.z + vs[j] * yb.z;
      const double walk = -(yx * hx[j] + yy * hy[j] + yz * hz[j]);
      walk_max = std::max(walk_max, std::abs(walk));
      hx[j] += walk * yx;
      hy[j] += walk * yy;
      hz[j] += walk * yz;
    }
    m.walk_demand_mm = walk_max;
    if (!have_heights) continue;
    for (CoupledNeedle& nd : needles) SideDriftBlock(count, sn, vs, hx, hy, hz, q0, q1, nd);
  }
  for (std::size_t n = 0; n < needles.size(); ++n)
    m.side_force_mm[n] = std::sqrt(needles[n].max_sq);
  return m;
}

NeedleLimits NeedleLimitsFrom(const scene::RuleLimits& limits) {
  using scene::LimitKey;
  // No limit: a bound no window metric reaches.
  constexpr double kNoLimit = 1e9;
  NeedleLimits l;
  l.side_force_error_mm = limits.Get(LimitKey::kSideForceErrorMm).value_or(kNoLimit);
  const LimitKey axes[3] = {LimitKey::kRotationXErrorDeg, LimitKey::kRotationYErrorDeg,
                            LimitKey::kRotationZErrorDeg};
  for (int i = 0; i < 3; ++i) {
    l.rotation_error_rad[i] = limits.Get(axes[i]).value_or(kNoLimit) * kDeg;
  }
  l.rotation_total_error_rad =
      limits.Get(LimitKey::kRotationTotalErrorDeg).value_or(kNoLimit) * kDeg;
  return l;
}

std::string FirstExceededLimit(const WindowMetrics& m, const NeedleLimits& limits) {
  if (m.MaxSideForceMm() > limits.side_force_error_mm) return "needle.side_force";
  for (int i = 0; i < 3; ++i) {
    if (m.rotation_rad[i] > limits.rotation_error_rad[i]) return "needle.rotation_in_preform";
  }
  if (m.rotation_total_rad > limits.rotation_total_error_rad) return "needle.rotation_in_preform";
  return {};
}

std::vector<std::optional<Eigen::Vector3d>> PenetrationPoints(const ProcessModel& model,
                                                              const geom::Surface& surface,
                                                              const Eigen::Isometry3d& tool) {
  std::vector<std::optional<Eigen::Vector3d>> out;
  out.reserve(model.needles.size());
  for (const auto& n : model.needles) {
    Eigen::Vector3d hit;
    const Eigen::Vector3d p = tool * n.through_mm;
    const Eigen::Vector3d d = tool.linear() * n.direction;
    if (surface.IntersectLine(p, d, hit)) {
      out.emplace_back(hit);
    } else {
      out.emplace_back(std::nullopt);
    }
  }
  return out;
}

}  // namespace stitchsim::process
