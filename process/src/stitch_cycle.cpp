#include "stitchsim/process/stitch_cycle.h"

#include <algorithm>
#include <cmath>

namespace stitchsim::process {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Point of needle `n` at tool-frame height z (on its axis).
Eigen::Vector3d ShaftPoint(const scene::NeedleSpec& n, double z_mm) {
  return n.through_mm + n.direction * (-z_mm / n.direction.z());
}

double Limit(const scene::RuleLimits& limits, const std::string& rule, const std::string& key,
             double fallback) {
  const auto r = limits.find(rule);
  if (r == limits.end()) return fallback;
  const auto k = r->second.find(key);
  return k == r->second.end() ? fallback : k->second;
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

void NeedleWindow::Enter(const Eigen::Isometry3d& tool) {
  active_ = true;
  entry_ = tool;
  metrics_ = WindowMetrics{};
  metrics_.side_force_mm.assign(model_->needles.size(), 0.0);
  entry_points_.assign(model_->needles.size(), {});
  for (std::size_t k = 0; k < model_->needles.size(); ++k) {
    for (double z : model_->shaft_heights_mm) {
      entry_points_[k].push_back(tool * ShaftPoint(model_->needles[k], z));
    }
  }
}

void NeedleWindow::Update(const Eigen::Isometry3d& tool) {
  if (!active_) return;
  // The walk moves both needles along head y, matched to the catcher (the tool point): it
  // cancels the tool point's travel along the head's current y axis.
  const Eigen::Vector3d travel = tool.translation() - entry_.translation();
  const Eigen::Vector3d y = tool.linear().col(1);
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

WindowMetrics EvaluateCoupledStitch(const ProcessModel& model, const Eigen::Isometry3d& from,
                                    const Eigen::Isometry3d& to, int samples) {
  // The drive advances linearly along the line, so line fraction = cycle phase.
  NeedleWindow window(model);
  window.Enter(InterpolatePose(from, to, model.phase_in));
  for (int i = 1; i <= samples; ++i) {
    const double phase =
        model.phase_in + (model.phase_out - model.phase_in) * static_cast<double>(i) / samples;
    window.Update(InterpolatePose(from, to, phase));
  }
  return window.Metrics();
}

NeedleLimits NeedleLimitsFrom(const scene::RuleLimits& limits) {
  NeedleLimits l;
  l.side_force_error_mm = Limit(limits, "needle.side_force", "error_mm", 1e9);
  const char* axes[3] = {"x_error_deg", "y_error_deg", "z_error_deg"};
  for (int i = 0; i < 3; ++i) {
    l.rotation_error_rad[i] = Limit(limits, "needle.rotation_in_preform", axes[i], 1e9) * kDeg;
  }
  l.rotation_total_error_rad =
      Limit(limits, "needle.rotation_in_preform", "total_error_deg", 1e9) * kDeg;
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
