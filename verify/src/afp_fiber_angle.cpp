// afp.fiber_angle: the direction every tow is laid in against its ply's design fibre
// direction (docs/report-format.md, the afp.* rules; issue 29). The design direction at a
// point of the surface is the ply's rosette reference (PlySpec::direction) projected onto the
// tangent plane there along the ply's projection direction (PlySpec::projection; the
// projected-rosette convention of fibre-placement CAM), turned by the ply angle about the
// surface normal (right-handed about the normal that points to the head, as the ply planner
// turns it). The laid direction is the tow's centre line between consecutive sampled poses of
// a line (at most half a tow width apart), laid into the tangent plane at their midpoint.
// Fibres are lines: the deviation is the angle between the two directions taken without sign,
// 0 to 90 deg. One figure per laying line, its worst tow; lines of plies the scene does not
// define are not judged.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "afp_thickness.h"
#include "afp_value_grid.h"
#include "detail/rule_registry.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

using detail::LaidLine;

/// The design fibre direction of `ply` in the tangent plane with unit normal `n`, or nullopt
/// where the reference does not project (its direction along the projection, or the
/// projection in the tangent plane).
std::optional<Eigen::Vector3d> DesignDirection(const scene::PlySpec& ply,
                                               const Eigen::Vector3d& n) {
  const double along = ply.projection.dot(n);
  if (std::abs(along) < 1e-9) return std::nullopt;
  // Oblique projection along `projection` onto the tangent plane.
  Eigen::Vector3d d0 = ply.direction - (ply.direction.dot(n) / along) * ply.projection;
  const double len = d0.norm();
  if (len < 1e-9) return std::nullopt;
  d0 /= len;
  return std::cos(ply.angle_rad) * d0 + std::sin(ply.angle_rad) * n.cross(d0);
}

class FiberAngleRule final : public Rule {
 public:
  FiberAngleRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.fiber_angle",
             "angle between every laid tow's centre line and its ply's design fibre direction "
             "(the rosette reference projected onto the surface, turned by the ply angle)",
             "deg"),
        laid_(std::move(laid)),
        plies_(&ctx.scene->plies),
        map_(detail::LaminateGrid(laid_->Surface(), ctx.scene->plies, laid_->Layout())) {
    summary_.error_limit = ctx.scene->limits.Value(scene::LimitKey::kAfpFiberAngleMaxDeg);
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      AddSubject("tow " + std::to_string(t), summary_.error_limit, std::nullopt);
    }
  }

  void OnLine(const trace::LineRecord& record) override {
    const LaidLine* line = laid_->Sample(record);
    if (line == nullptr || line->ply < 1 || line->ply > static_cast<int>(plies_->size())) return;
    const scene::PlySpec& ply = (*plies_)[static_cast<std::size_t>(line->ply) - 1];
    const geom::Surface& surface = laid_->Surface();
    double worst = -1.0;
    int worst_tow = 0;
    Seen worst_seen, tow_seen;  // where the line's worst tow and this tow deviate most
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      if (!detail::TowLaid(line->tows, t)) continue;
      double tow_worst = -1.0;
      // The previous pose's centre on the surface, carried: each point is evaluated once.
      const detail::LaidPose* prev = nullptr;
      Eigen::Vector2d ua = Eigen::Vector2d::Zero();
      Eigen::Vector3d pa = Eigen::Vector3d::Zero();
      for (const detail::LaidPose& pose : line->poses) {
        if (!pose.cross.ok) {
          prev = nullptr;
          continue;
        }
        const Eigen::Vector2d ub = detail::TowCentreUv(pose.cross, t);
        const Eigen::Vector3d pb = surface.Point(ub);
        const detail::LaidPose* pair = prev;
        const Eigen::Vector2d u_prev = ua;
        const Eigen::Vector3d p_prev = pa;
        prev = &pose;
        ua = ub;
        pa = pb;
        if (pair == nullptr) continue;
        const Eigen::Vector3d n = surface.Normal(0.5 * (u_prev + ub)).normalized();
        Eigen::Vector3d laid = pb - p_prev;
        laid -= laid.dot(n) * n;
        if (laid.norm() < 1e-9) continue;
        const std::optional<Eigen::Vector3d> design = DesignDirection(ply, n);
        if (!design) continue;
        const double c = std::clamp(std::abs(laid.normalized().dot(*design)), 0.0, 1.0);
        const double deg = RadToDeg(std::acos(c));
        if (deg > tow_worst) {
          tow_worst = deg;
          tow_seen = {0.5 * (p_prev + pb), laid.normalized(), *design};
        }
        const auto k = static_cast<std::size_t>(t);
        map_.PaintMax({pair->cross.boundary_uv[k - 1], pair->cross.boundary_uv[k],
                       pose.cross.boundary_uv[k], pose.cross.boundary_uv[k - 1]},
                      deg);
      }
      if (tow_worst < 0.0) continue;
      ObserveSubject(static_cast<std::size_t>(t) - 1, tow_worst, line->source_line, 0);
      if (detail::LaidFigures* f = laid_->Figures()) f->FiberAngle(line->source_line, t, tow_worst);
      if (tow_worst > worst) {
        worst = tow_worst;
        worst_tow = t;
        worst_seen = tow_seen;
      }
    }
    if (worst < 0.0) return;
    double& ply_worst = ply_worst_.try_emplace(line->ply, worst).first->second;
    ply_worst = std::max(ply_worst, worst);
    CheckUpper(
        worst, line->source_line, 0, "tow " + std::to_string(worst_tow),
        [&] {
          char buf[160];
          std::snprintf(buf, sizeof(buf),
                        "ply %d course %d tow %d laid off its design fibre direction (ply angle "
                        "%.4g deg) by",
                        line->ply, line->course, worst_tow, RadToDeg(ply.angle_rad));
          return std::string(buf);
        },
        nullptr, &worst_seen.at);
    if (worst > *summary_.error_limit && worst > drawn_deg_) {
      drawn_deg_ = worst;
      // Fibres are lines: the design direction drawn on the laid one's side.
      const double sign = worst_seen.design.dot(worst_seen.laid) < 0 ? -1.0 : 1.0;
      drawn_ = {worst_seen.at, worst_seen.at + kDrawnMm * worst_seen.laid,
                worst_seen.at + sign * kDrawnMm * worst_seen.design};
    }
  }

  // The worst deviation over the limit: the tow's centre there, then the tips of the laid and
  // the design directions kDrawnMm from it (part mm), for its close-up.
  std::vector<DrawnPoints> Drawings() const override {
    if (drawn_.empty()) return {};
    return {{"close_up:afp_fiber", drawn_}};
  }

  void AddLaydownFigures(std::vector<LaydownFigures>& figures) const override {
    for (LaydownFigures& f : figures) {
      if (f.ply == 0) {
        for (const auto& [ply, worst] : ply_worst_) {
          f.worst_fiber_angle_deg = std::max(f.worst_fiber_angle_deg.value_or(worst), worst);
        }
      } else if (const auto it = ply_worst_.find(f.ply); it != ply_worst_.end()) {
        f.worst_fiber_angle_deg = it->second;
      }
    }
  }

  const detail::WorstValueGrid& Map() const { return map_; }

 private:
  static constexpr double kDrawnMm = 10.0;
  struct Seen {
    Eigen::Vector3d at = Eigen::Vector3d::Zero();       ///< tow centre, part mm
    Eigen::Vector3d laid = Eigen::Vector3d::UnitX();    ///< laid direction, unit
    Eigen::Vector3d design = Eigen::Vector3d::UnitX();  ///< design direction, unit
  };

  std::shared_ptr<detail::LaidTows> laid_;
  const std::vector<scene::PlySpec>* plies_;
  double drawn_deg_ = 0.0;              ///< the deviation drawn_ shows, deg
  std::vector<Eigen::Vector3d> drawn_;  ///< see Drawings()
  std::map<int, double> ply_worst_;     ///< the worst deviation per ply (M70 P<n>), deg
  /// The worst deviation per cell over the plies, deg: the tow quads painted.
  detail::WorstValueGrid map_;
};

}  // namespace

const detail::WorstValueGrid* detail::FiberAngleGridOf(const Rule& rule) {
  const auto* f = dynamic_cast<const FiberAngleRule*>(&rule);
  return f != nullptr ? &f->Map() : nullptr;
}

RuleEntry AfpFiberAngleRuleEntry() {
  return {"afp.fiber_angle", CloseUpFamily::kAfp, detail::RunsWhenLaying,
          detail::MakeLaying<FiberAngleRule>};
}

}  // namespace stitchsim::verify
