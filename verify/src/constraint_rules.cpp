// constraint.crossing (seed 001): no needle penetration inside a constraint's footprint, and
// no move with the needles down (stitching on, head not retracted) across one. The footprint
// is the raster planner's (scene/footprint.h): on a height-field surface the constraint's box
// projected on the part's (x, y) plane and grown by a margin, otherwise the grown box in 3D.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "stitchsim/scene/footprint.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

// A constraint's footprint: `outline` on a height-field surface, `box` otherwise.
struct Box {
  std::string name;
  scene::Footprint outline;
  scene::GrownBox box;
};

class ConstraintCrossingRule final : public Rule {
 public:
  explicit ConstraintCrossingRule(const RuleContext& ctx)
      : Rule("constraint.crossing",
             "needle penetrations and needles-down moves clear of the constraint footprints "
             "(stringers, intercostals, spar caps) plus a margin",
             "mm") {
    margin_mm_ = ctx.scene->limits.Value(scene::LimitKey::kConstraintMarginMm);
    summary_.error_limit = 0.0;
    planar_ = ctx.scene->surface && ctx.scene->surface->IsHeightField();
    for (const scene::Constraint& c : ctx.scene->constraints) {
      boxes_.push_back(
          {c.name, scene::ConstraintFootprint(c, margin_mm_), scene::ConstraintBox(c, margin_mm_)});
    }
  }

  void OnLine(const trace::LineRecord& l) override {
    if (!l.stitching || l.head_retracted) return;
    Counted();
    for (const Box& b : boxes_) {
      const double depth = SegmentDepth(b, l.from.translation(), l.to.translation());
      if (depth >= 0.0) {
        char msg[256];
        std::snprintf(msg, sizeof(msg),
                      "a move with the needles down (stitching on, head not retracted) crosses "
                      "the footprint of '%s' (margin %.3g mm)",
                      b.name.c_str(), margin_mm_);
        Record(FindingSeverity::kError, depth, 0.0, l.source_line, 0, b.name, msg, nullptr);
        return;
      }
    }
  }

  void OnPenetration(const PenetrationRecord& p) override {
    Counted();
    for (const Box& b : boxes_) {
      double worst = -1.0;
      for (const auto& pt : p.points) {
        if (pt) worst = std::max(worst, PointDepth(b, *pt));
      }
      worst = std::max(worst, PointDepth(b, p.foot.point));
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
  // How far inside (>= 0) the footprint the point is; negative outside.
  double PointDepth(const Box& b, const Eigen::Vector3d& p) const {
    return planar_ ? b.outline.Depth(p.head<2>()) : b.box.Depth(p);
  }
  // >= 0 if the segment meets the footprint (slab test), negative if not.
  double SegmentDepth(const Box& b, const Eigen::Vector3d& a, const Eigen::Vector3d& e) const {
    return planar_ ? b.outline.SegmentDepth(a.head<2>(), e.head<2>()) : b.box.SegmentDepth(a, e);
  }

  double margin_mm_ = 1.0;
  bool planar_ = true;
  std::vector<Box> boxes_;
};

}  // namespace

std::unique_ptr<Rule> MakeConstraintCrossingRule(const RuleContext& ctx) {
  return std::make_unique<ConstraintCrossingRule>(ctx);
}

}  // namespace stitchsim::verify
