// constraint.crossing (seed 001): no needle penetration inside a constraint's footprint, and
// no move with the needles down (stitching on, head not retracted) across one. The footprint
// is the constraint box grown by a margin; on a height-field surface (plane, polynomial,
// mesh: u = x, v = y) the box is projected on the part's (x, y) plane, otherwise the grown
// box itself is tested in 3D. Independent of the planner's own footprints (two routes).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "stitchsim/verify/rule.h"

namespace stitchsim::verify {
namespace {

struct Box {
  std::string name;
  Eigen::Isometry3d to_local = Eigen::Isometry3d::Identity();  // part frame -> box frame
  Eigen::Vector3d half_mm = Eigen::Vector3d::Zero();           // margin included
};

class ConstraintCrossingRule final : public Rule {
 public:
  explicit ConstraintCrossingRule(const RuleContext& ctx)
      : Rule("constraint.crossing",
             "needle penetrations and needles-down moves clear of the constraint footprints "
             "(stringers, intercostals, spar caps) plus a margin",
             "mm") {
    margin_mm_ = LimitOf(ctx, summary_.id, "margin_mm").value_or(1.0);
    summary_.error_limit = 0.0;
    const std::string kind = ctx.scene->surface ? ctx.scene->surface->Kind() : "";
    planar_ = kind == "plane" || kind == "polynomial" || kind == "mesh";
    for (const scene::Constraint& c : ctx.scene->constraints) {
      Box b;
      b.name = c.name;
      if (c.shape == scene::Constraint::Shape::kMesh && !c.mesh.vertices.empty()) {
        Eigen::AlignedBox3d box;
        for (const auto& v : c.mesh.vertices) box.extend(v);
        b.to_local = Eigen::Translation3d(-box.center());
        b.half_mm = 0.5 * box.sizes();
      } else {
        b.to_local = c.pose_mm.inverse();
        b.half_mm = 0.5 * c.size_mm;
      }
      b.half_mm.array() += margin_mm_;
      if (planar_) b.half_mm.z() = 1e30;  // a projection: any height
      boxes_.push_back(std::move(b));
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
  // How far inside (>= 0) the grown box the point is; negative outside.
  double PointDepth(const Box& b, const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = b.to_local * p;
    const int dims = planar_ ? 2 : 3;
    double depth = 1e300;
    for (int k = 0; k < dims; ++k) depth = std::min(depth, b.half_mm[k] - std::abs(q[k]));
    return depth;
  }
  // >= 0 if the segment meets the grown box (slab test), negative if not.
  double SegmentDepth(const Box& b, const Eigen::Vector3d& a, const Eigen::Vector3d& e) const {
    const Eigen::Vector3d la = b.to_local * a;
    const Eigen::Vector3d d = b.to_local * e - la;
    const int dims = planar_ ? 2 : 3;
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < dims; ++k) {
      if (std::abs(d[k]) < 1e-12) {
        if (std::abs(la[k]) > b.half_mm[k]) return -1.0;
        continue;
      }
      double ta = (-b.half_mm[k] - la[k]) / d[k];
      double tb = (b.half_mm[k] - la[k]) / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      if (t0 > t1) return -1.0;
    }
    return std::max(0.0, PointDepth(b, a + (e - a) * (0.5 * (t0 + t1))));
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
