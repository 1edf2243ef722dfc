// constraint.crossing (seed 001): no needle penetration inside a constraint's footprint, and
// no move with the needles down (stitching on, head not retracted) across one. The footprint
// is the raster planner's (scene/footprint.h), grown by the rule's margin: on a height-field
// surface the constraint's box projected on the part's (x, y) plane; on any other surface the
// box projected onto the surface, in its (u, v), where points and moves are judged by their
// closest points on the surface; the grown box in 3D for a constraint that does not project.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

#include "detail/rule_registry.h"
#include "stitchsim/scene/footprint.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

// A constraint's footprint: `outline` in the footprint plane (x, y) or (u, v) where the
// constraint projects onto the surface, else `box` in 3D.
struct Box {
  std::string name;
  std::optional<scene::Footprint> outline;
  scene::GrownBox box;
};

// A move of the needles down is judged in the (u, v) plane in pieces of at most this length,
// each piece's ends mapped by their closest points (a long move follows the surface's curve).
constexpr double kUvPieceMm = 10.0;
constexpr int kMaxUvPieces = 256;

class ConstraintCrossingRule final : public Rule {
 public:
  explicit ConstraintCrossingRule(const RuleContext& ctx)
      : Rule("constraint.crossing",
             "needle penetrations and needles-down moves clear of the constraint footprints "
             "(stringers, intercostals, spar caps) plus a margin",
             "mm") {
    margin_mm_ = ctx.scene->limits.Value(scene::LimitKey::kConstraintMarginMm);
    summary_.error_limit = 0.0;
    surface_ = ctx.scene->surface.get();
    planar_ = surface_ && surface_->IsHeightField();
    for (const scene::Constraint& c : ctx.scene->constraints) {
      Box b{c.name, std::nullopt, scene::ConstraintBox(c, margin_mm_)};
      std::string error;
      if (surface_) b.outline = scene::ConstraintFootprintOn(c, *surface_, margin_mm_, error);
      boxes_.push_back(std::move(b));
    }
  }

  void OnLine(const trace::LineRecord& l) override {
    if (!l.stitching || l.head_retracted) return;
    Counted();
    const Eigen::Vector3d a = l.from.translation(), e = l.to.translation();
    if (!planar_) MovePieces(a, e);
    for (const Box& b : boxes_) {
      const double depth = SegmentDepth(b, a, e);
      if (depth >= 0.0) {
        char msg[256];
        std::snprintf(msg, sizeof(msg),
                      "a move with the needles down (stitching on, head not retracted) crosses "
                      "the footprint of '%s' (margin %.3g mm)",
                      b.name.c_str(), margin_mm_);
        Record(FindingSeverity::kError, depth, 0.0, l.source_line, 0, b.name, msg, nullptr, &e);
        return;
      }
    }
  }

  void OnPenetration(const PenetrationRecord& p) override {
    Counted();
    // Each point's place in the footprint plane, found once for every constraint.
    points_.clear();
    for (const auto& pt : p.points) {
      if (pt) points_.push_back({*pt, PlanePoint(*pt)});
    }
    points_.push_back({p.foot.point, PlanePoint(p.foot.point)});
    for (const Box& b : boxes_) {
      double worst = -1.0;
      for (const auto& [pt, uv] : points_) worst = std::max(worst, PointDepth(b, pt, uv));
      if (worst >= 0.0) {
        char msg[256];
        std::snprintf(msg, sizeof(msg),
                      "needle penetration %.3g mm inside the footprint of '%s' (margin %.3g mm)",
                      worst, b.name.c_str(), margin_mm_);
        Record(FindingSeverity::kError, worst, 0.0, p.line, p.stitch, b.name, msg, &p.sample);
        return;
      }
    }
  }

 private:
  Eigen::Vector2d PlanePoint(const Eigen::Vector3d& p) const {
    return planar_ || !surface_ ? Eigen::Vector2d(p.head<2>())
                                : scene::FootprintPlanePoint(*surface_, p);
  }
  // How far inside (>= 0) the footprint the point (at `plane` in the footprint plane) is;
  // negative outside.
  double PointDepth(const Box& b, const Eigen::Vector3d& p, const Eigen::Vector2d& plane) const {
    return b.outline ? b.outline->Depth(plane) : b.box.Depth(p);
  }
  // The move a-e off a height field: its pieces' ends in (u, v), into uv_pieces_.
  void MovePieces(const Eigen::Vector3d& a, const Eigen::Vector3d& e) {
    const int n =
        std::clamp(static_cast<int>(std::ceil((e - a).norm() / kUvPieceMm)), 1, kMaxUvPieces);
    uv_pieces_.clear();
    for (int k = 0; k <= n; ++k) uv_pieces_.push_back(PlanePoint(a + (e - a) * (double(k) / n)));
  }
  // >= 0 if the segment meets the footprint (slab test; off a height field, the deepest of its
  // pieces in (u, v)), negative if not.
  double SegmentDepth(const Box& b, const Eigen::Vector3d& a, const Eigen::Vector3d& e) const {
    if (!b.outline) return b.box.SegmentDepth(a, e);
    if (planar_) return b.outline->SegmentDepth(a.head<2>(), e.head<2>());
    double depth = -1.0;
    for (std::size_t k = 0; k + 1 < uv_pieces_.size(); ++k) {
      depth = std::max(depth, b.outline->SegmentDepth(uv_pieces_[k], uv_pieces_[k + 1]));
    }
    return depth;
  }

  double margin_mm_ = 1.0;
  bool planar_ = true;
  const geom::Surface* surface_ = nullptr;
  std::vector<Box> boxes_;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector2d>> points_;  // penetration, plane
  std::vector<Eigen::Vector2d> uv_pieces_;                           // this move off a height field
};

}  // namespace

RuleEntry ConstraintCrossingRuleEntry() {
  // Only a scene with constraints.
  return {
      "constraint.crossing", CloseUpFamily::kConstraint,
      [](const RuleContext& ctx) { return RulePresence::RunsIf(!ctx.scene->constraints.empty()); },
      detail::Make<ConstraintCrossingRule>};
}

}  // namespace stitchsim::verify
