// afp.gap and afp.overlap: the distance between the facing edges of neighbouring courses of a
// ply. While a course lays, the outermost laid boundary on each side (tool -x and +x) at every
// pose is compared with the edges of the ply's earlier courses nearby (a spatial hash of their
// edge segments): the signed distance along the surface geodesic that leaves the edge point
// across the course (the tow walk's direction there) to where a facing edge crosses it,
// positive = gap, negative = overlap. A course's own edges join the hash when it ends. afp.gap also
// counts a run of tows cut inside a course while the tows on both sides lay (a gap of the run's
// width) and tow bits beyond the head's tows (they lay nothing).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "afp_laid.h"
#include "detail/rule_registry.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/polygon2.h"
#include "stitchsim/geom/surface_walk.h"

namespace stitchsim::verify {
namespace {

using detail::LaidLine;

// An edge segment of an earlier course, with the direction pointing away from that course.
struct EdgeSegment {
  Eigen::Vector3d a, b, outward;
};

// Edge segments of the ply's courses laid so far, hashed by their midpoints.
class EdgeHash {
 public:
  explicit EdgeHash(double cell_mm) : cell_mm_(cell_mm) {}
  void Clear() {
    segments_.clear();
    cells_.clear();
  }
  void Add(const EdgeSegment& s) {
    cells_[Key(Cell(0.5 * (s.a + s.b)))].push_back(segments_.size());
    segments_.push_back(s);
  }
  // Calls f(segment) for every segment whose midpoint lies within one cell of `p`.
  template <typename F>
  void Near(const Eigen::Vector3d& p, F&& f) const {
    const Eigen::Vector3i c = Cell(p);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(Key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const std::size_t i : it->second) f(segments_[i]);
        }
      }
    }
  }

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3d& p) const {
    return (p / cell_mm_).array().floor().cast<int>();
  }
  static std::int64_t Key(const Eigen::Vector3i& c) {
    const auto part = [](int v) { return static_cast<std::int64_t>(v & 0x1FFFFF); };
    return (part(c.x()) << 42) | (part(c.y()) << 21) | part(c.z());
  }
  double cell_mm_;
  std::vector<EdgeSegment> segments_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
};

// An edge point of the laying course: on the surface at `uv`, `outward` the unit tangent
// across the course away from it.
struct EdgePoint {
  Eigen::Vector2d uv;
  Eigen::Vector3d point, outward;
};

// The signed distance along the surface from edge point `e` outwards to the nearest facing edge
// segment crossing the surface's normal plane along e.outward, if one lies within `reach_mm`.
std::optional<double> FacingDistance(const geom::Surface& surface, const EdgeHash& hash,
                                     const EdgePoint& e, double reach_mm) {
  const Eigen::Vector3d& p = e.point;
  const Eigen::Vector3d& o = e.outward;
  const Eigen::Vector3d t = surface.Normal(e.uv).cross(o);  // along the edge
  std::optional<double> best;
  Eigen::Vector3d crossing = p;
  hash.Near(p, [&](const EdgeSegment& s) {
    if (s.outward.dot(o) > -0.5) return;  // not facing this edge
    const double at = (s.a - p).dot(t), bt = (s.b - p).dot(t);
    if (at * bt > 0.0 || at == bt) return;  // does not cross the plane across the course
    const Eigen::Vector3d q = s.a + (s.b - s.a) * (at / (at - bt));
    const double d = (q - p).dot(o);  // the chord's share: to pick the nearest
    if (std::abs(d) <= reach_mm && (!best || std::abs(d) < std::abs(*best))) {
      best = d;
      crossing = q;
    }
  });
  if (!best) return best;
  // The chord reads short on a curved surface (2 R sin(g / 2R) for a gap g across a curvature
  // 1 / R): walk the geodesic out to the crossing instead.
  return geom::DistanceAlongGeodesic(surface, e.uv, o, crossing);
}

class CourseEdgeRule final : public Rule {
 public:
  // `gap`: afp.gap (positive distances); else afp.overlap (negative distances).
  CourseEdgeRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid, bool gap)
      : Rule(gap ? "afp.gap" : "afp.overlap",
             gap ? "gap between the facing edges of neighbouring courses of a ply, and tows cut "
                   "inside a course between laid ones"
                 : "overlap of the facing edges of neighbouring courses of a ply",
             "mm"),
        laid_(std::move(laid)),
        gap_(gap),
        width_mm_(laid_->Layout().width_mm),
        hash_(2.5 * width_mm_) {
    summary_.error_limit = ctx.scene->limits.Get(gap ? scene::LimitKey::kAfpGapMaxMm
                                                     : scene::LimitKey::kAfpOverlapMaxMm);
    mergeable_ = false;  // judged over whole plies (Rule::Mergeable)
    for (const scene::PlySpec& ply : ctx.scene->plies) boundaries_.push_back(ply.boundary_uv);
  }

  void OnLine(const trace::LineRecord& record) override {
    if (record.ply != ply_) {
      hash_.Clear();
      pending_.clear();
      ply_ = record.ply;
    }
    if (record.course != course_) EndCourse(record.course);
    const LaidLine* line = laid_->Sample(record);
    if (line == nullptr) {
      for (Side& s : sides_) s.have = false;
      return;
    }
    if (gap_) CheckTowMask(*line);
    int lo = 0, hi = 0;  // leftmost and rightmost laid tow
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      if (!detail::TowLaid(line->tows, t)) continue;
      if (lo == 0) lo = t;
      hi = t;
    }
    if (lo == 0) return;  // only bits beyond the head's tows
    // Under the laid width: the next course but one faces this edge from one course width
    // beyond the neighbour, and the neighbour on the other side from two (courses of one or two
    // tows of a narrow ply; issue 26 item 1). From three tows on, two tow widths.
    reach_mm_ = std::min(2.0, 0.75 * (hi - lo + 1)) * width_mm_;
    for (const detail::LaidPose& pose : line->poses) {
      if (!pose.cross.ok) {
        for (Side& s : sides_) s.have = false;
        continue;
      }
      const auto left = static_cast<std::size_t>(lo) - 1, right = static_cast<std::size_t>(hi);
      const process::TowCross& c = pose.cross;
      Edge(0, {c.boundary_uv[left], c.boundary[left], -c.across[left]}, *line, lo);
      Edge(1, {c.boundary_uv[right], c.boundary[right], c.across[right]}, *line, hi);
    }
  }

 private:
  struct Side {
    bool have = false;
    Eigen::Vector3d last = Eigen::Vector3d::Zero();
  };

  void EndCourse(int next_course) {
    for (const EdgeSegment& s : pending_) hash_.Add(s);
    pending_.clear();
    for (Side& s : sides_) s.have = false;
    course_ = next_course;
  }

  // One edge point of the laying course: measured against the earlier courses, then kept.
  void Edge(int side, const EdgePoint& e, const LaidLine& line, int tow) {
    Side& s = sides_[side];
    const Eigen::Vector3d& p = e.point;
    // Consecutive points of one edge join (a tow cut or added makes the edge jump across).
    if (s.have && (p - s.last).norm() < 0.75 * width_mm_) {
      pending_.push_back({s.last, p, e.outward});
    }
    s.have = true;
    s.last = p;
    const std::optional<double> d = FacingDistance(laid_->Surface(), hash_, e, reach_mm_);
    if (!d) return;
    double value = std::max(0.0, gap_ ? *d : -*d);
    if (value > 0.0 && LeftToCoverage(line, e, *d)) value = 0.0;
    if (value >= kDrawnFromMm) drawn_.Add(p);
    CheckUpper(
        value, line.source_line, 0,
        "course " + std::to_string(line.course) + (side == 0 ? " left" : " right"),
        [&] {
          char buf[160];
          std::snprintf(buf, sizeof(buf), "%s beside tow %d of course %d (%s edge) to a neighbour",
                        gap_ ? "gap" : "overlap", tow, line.course, side == 0 ? "left" : "right");
          return std::string(buf);
        },
        nullptr, &p);
  }

  // True when the edge point `e` is left to the coverage policy: within one tow width of a
  // stretch of the line's ply boundary that meets the course at a slant of kSlantDeg or more
  // (tows cut one by one there leave bare triangles: the band afp.coverage judges bare and
  // doubled area beyond; a seam beside an edge parallel to the courses is judged), or outside
  // the ply with the stretch to the facing edge `d` mm along e.outward (a gap; back against
  // it: an overlap) outside too: that material is trimmed off the part (an extended tow end
  // beside a neighbour's), so the ply has no gap or overlap there.
  bool LeftToCoverage(const LaidLine& line, const EdgePoint& e, double d) const {
    if (line.ply < 1 || line.ply > static_cast<int>(boundaries_.size())) return false;
    const geom::Polygon2& boundary = boundaries_[static_cast<std::size_t>(line.ply - 1)];
    if (SlantedBoundaryNear(boundary, e)) return true;
    if (geom::InsidePolygon(boundary, e.uv)) return false;
    for (int k = 1; k <= 4; ++k) {  // a stretch may cut a corner of the ply: four points on it
      const Eigen::Vector3d at = e.point + 0.25 * k * d * e.outward;
      if (geom::InsidePolygon(boundary, laid_->Surface().ProjectFrom(at, e.uv).uv)) return false;
    }
    return true;
  }

  // True when a segment of `boundary` within a tow width of `e` meets the course (the edge's
  // direction there, in (u, v)) at kSlantDeg or more.
  bool SlantedBoundaryNear(const geom::Polygon2& boundary, const EdgePoint& e) const {
    constexpr double kSlantDeg = 5.0;
    std::optional<Eigen::Vector2d> t;  // the edge's direction in (u, v), found when needed
    double sin_min = 0.0;
    for (std::size_t i = 0, n = boundary.size(); i < n; ++i) {
      const Eigen::Vector2d& a = boundary[i];
      const Eigen::Vector2d& b = boundary[(i + 1) % n];
      if (geom::DistanceToSegment(a, b, e.uv) > width_mm_) continue;
      if (!t) {  // a projection: only for points in the band
        const geom::Surface& surface = laid_->Surface();
        const Eigen::Vector3d along = surface.Normal(e.uv).cross(e.outward);
        t = surface.ProjectFrom(e.point + along, e.uv).uv - e.uv;
        sin_min = std::sin(kSlantDeg * kPi / 180.0) * t->norm();
      }
      const Eigen::Vector2d ab = b - a;
      if (std::abs(t->x() * ab.y() - t->y() * ab.x()) >= sin_min * ab.norm()) return true;
    }
    return false;
  }

  // True when the course's centre passes within half a course and a tow width of the boundary
  // of the line's ply (M70 P<n>: the n-th of the scene's plies) on this line: where the coverage
  // policy cuts tows one by one across a boundary that meets the course at a slant or curves
  // under it, and afp.coverage judges what is left bare.
  bool AtPlyBoundary(const LaidLine& line) const {
    if (line.ply < 1 || line.ply > static_cast<int>(boundaries_.size())) return false;
    const geom::Polygon2& boundary = boundaries_[static_cast<std::size_t>(line.ply - 1)];
    const double reach = (0.5 * laid_->Layout().tows + 1.0) * width_mm_;
    for (const detail::LaidPose& pose : line.poses) {
      if (pose.cross.ok && geom::DistanceToPolygon(boundary, pose.cross.centre_uv) <= reach) {
        return true;
      }
    }
    return false;
  }

  // Runs of cut tows with laid tows on both sides leave a gap of their width, away from the
  // ply's boundary.
  void CheckTowMask(const LaidLine& line) {
    if (line.extra_tows != 0) {
      char buf[160];
      std::snprintf(buf, sizeof(buf),
                    "the tow mask sets bits beyond the head's %d tows (they lay nothing)",
                    laid_->Layout().tows);
      Record(FindingSeverity::kError, 0.0, *summary_.error_limit, line.source_line, 0, "tow mask",
             buf, nullptr);
    }
    if (AtPlyBoundary(line)) return;
    int last_laid = 0;
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      if (!detail::TowLaid(line.tows, t)) continue;
      if (last_laid != 0 && t - last_laid > 1) {
        const double gap = (t - last_laid - 1) * width_mm_;
        CheckUpper(
            gap, line.source_line, 0, "tow " + std::to_string(last_laid + 1),
            [&] {
              return "tows " + std::to_string(last_laid + 1) + ".." + std::to_string(t - 1) +
                     " cut between laid tows in course " + std::to_string(line.course) + ": gap";
            },
            nullptr);
      }
      last_laid = t;
    }
  }

  std::vector<DrawnPoints> Drawings() const override {
    return {drawn_.Drawn(gap_ ? "afp_gap" : "afp_overlap")};
  }

  static constexpr double kDrawnFromMm = 0.1;  ///< smaller gaps and overlaps are not drawn
  std::shared_ptr<detail::LaidTows> laid_;
  detail::ThinnedPoints drawn_;  ///< edge points with a gap (overlap) of kDrawnFromMm or more
  bool gap_;
  double width_mm_;
  double reach_mm_ = 0.0;                   ///< how far across an edge a facing one is looked for
  std::vector<geom::Polygon2> boundaries_;  ///< the scene's plies, (u, v)
  EdgeHash hash_;                           ///< the ply's earlier courses
  std::vector<EdgeSegment> pending_;        ///< the laying course's edges
  Side sides_[2];                           ///< left, right
  int ply_ = 0;
  int course_ = 0;
};

}  // namespace

// Gaps and overlaps show on the overview, the coverage map and a close-up of the worst one.
RuleEntry AfpGapRuleEntry() {
  return {"afp.gap", CloseUpFamily::kAfp, detail::RunsWhenLaying,
          [](const RuleContext& ctx, detail::RuleMaking& making) -> std::unique_ptr<Rule> {
            return std::make_unique<CourseEdgeRule>(ctx, making.Laid(ctx), true);
          }};
}
RuleEntry AfpOverlapRuleEntry() {
  return {"afp.overlap", CloseUpFamily::kAfp, detail::RunsWhenLaying,
          [](const RuleContext& ctx, detail::RuleMaking& making) -> std::unique_ptr<Rule> {
            return std::make_unique<CourseEdgeRule>(ctx, making.Laid(ctx), false);
          }};
}

}  // namespace stitchsim::verify
