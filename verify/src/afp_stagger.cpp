// afp.stagger: the course seams of same-angle plies of a laminate against its stagger rule
// (scene `laminates:` stagger: offset, plies_before_repeat; docs/report-format.md, the afp.*
// rules; issue 29): gaps and overlaps between courses must not line up through the thickness
// (the "chimney" defect). A seam is where two courses of one ply meet: the outer boundary of a
// course's outermost laid tow (at every sampled pose) that lies within half a tow width of
// another course's outer boundary in the same ply. Each ply's seams are compared with those
// of the nearest `plies_before_repeat` plies of the same fibre angle below it in the stack
// (plies of other angles between them do not count): every seam point must lie at least
// `offset` from every such seam, the distance taken in space from the point to the other
// seam's polyline (consecutive sampled points of one course edge). One finding per line (the
// nearest seam point it lays), naming both plies and the other seam's line. Judged at the end of
// the programme (plies may be laid in any order); skipped while the scene gives no laminate.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "afp_laid.h"
#include "detail/rule_registry.h"
#include "stitchsim/common/units.h"

namespace stitchsim::verify {
namespace {

/// One sampled point of a course's outer edge.
struct StaggerPoint {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  ///< part frame, mm
  int line = 0;
};
/// A course's two outer edges (left: tow 1's side), in laying order.
struct StaggerEdges {
  std::vector<StaggerPoint> side[2];
};
/// What one ply laid: its courses' edges.
using StaggerPly = std::map<int, StaggerEdges>;  // by course number

/// Points in a uniform grid of cubes of side `cell` (mm), for neighbour queries.
class StaggerGrid {
 public:
  explicit StaggerGrid(double cell) : cell_(cell) {}
  void Add(const Eigen::Vector3d& p, std::size_t id) { cells_[Key(p)].push_back(id); }
  /// Calls f(id) for every point within one cell of p.
  template <typename F>
  void Near(const Eigen::Vector3d& p, F&& f) const {
    const Eigen::Vector3i c = Cell(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(Pack(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (std::size_t id : it->second) f(id);
        }
  }

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3d& p) const {
    return (p / cell_).array().floor().cast<int>();
  }
  static long long Pack(const Eigen::Vector3i& c) {
    return (static_cast<long long>(c.x()) * 2000003LL + c.y()) * 2000003LL + c.z();
  }
  long long Key(const Eigen::Vector3d& p) const { return Pack(Cell(p)); }
  double cell_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

/// A seam point too near another ply's seam, waiting for the end of the comparisons.
struct StaggerNear {
  double value = 0.0;                               ///< mm
  int ply = 0;                                      ///< the ply whose seam point it is
  int below = 0;                                    ///< the ply whose seam it is near
  int other_line = 0;                               ///< the line that laid that seam
  double offset = 0.0;                              ///< the laminate's stagger offset, mm
  Eigen::Vector3d at = Eigen::Vector3d::Zero();     ///< the seam point, part frame, mm
  Eigen::Vector3d other = Eigen::Vector3d::Zero();  ///< the nearest point of the other seam
};

/// A piece of seam: two consecutive points of a course edge that is a seam.
struct StaggerPiece {
  Eigen::Vector3d a, b;
  int line = 0;
};

// The point of segment a-b nearest `p`.
Eigen::Vector3d StaggerNearestOnSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

class StaggerRule final : public Rule {
 public:
  StaggerRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.stagger",
             "distance from every course seam of a laminate's ply to the seams of the plies of "
             "the same angle within its stagger window below it, against the laminate's stagger "
             "offset (worst = nearest)",
             "mm"),
        laid_(std::move(laid)),
        scene_(ctx.scene) {
    worst_is_smallest_ = true;
    mergeable_ = false;  // judged over whole plies at the end (Rule::Mergeable)
    double smallest = std::numeric_limits<double>::infinity();
    for (const auto& lam : scene_->laminates) smallest = std::min(smallest, lam.stagger_offset_mm);
    summary_.error_limit = smallest;
    AddSubject("seams", summary_.error_limit, std::nullopt);
  }

  void OnLine(const trace::LineRecord& record) override {
    const detail::LaidLine* line = laid_->Sample(record);
    if (line == nullptr) return;
    const int k = laid_->Layout().tows;
    int lo = 0, hi = 0;  // outermost laid tows
    for (int t = 1; t <= k; ++t) {
      if (!detail::TowLaid(line->tows, t)) continue;
      if (lo == 0) lo = t;
      hi = t;
    }
    if (lo == 0) return;
    StaggerEdges& edges = plies_[line->ply][line->course];
    for (const detail::LaidPose& pose : line->poses) {
      if (!pose.cross.ok) continue;
      const auto& b = pose.cross.boundary;
      edges.side[0].push_back({b[static_cast<std::size_t>(lo) - 1], line->source_line});
      edges.side[1].push_back({b[static_cast<std::size_t>(hi)], line->source_line});
    }
  }

  void Finish(const RuleContext&) override {
    std::map<int, std::vector<StaggerPiece>> seams;  // by ply number (1-based)
    for (const auto& [ply, edges] : plies_) seams[ply] = Seams(edges);
    std::map<int, StaggerNear> near;  // per line: its nearest seam point under the offset
    for (const auto& lam : scene_->laminates) {
      for (std::size_t i = 0; i < lam.stack.size(); ++i) {
        const int ply = static_cast<int>(lam.stack[i].ply) + 1;
        const auto mine = seams.find(ply);
        if (mine == seams.end()) continue;
        // Down the stack to the plies_before_repeat-th ply of the same angle.
        int same = 0;
        for (std::size_t j = i; j-- > 0 && same < lam.stagger_plies_before_repeat;) {
          const int below = static_cast<int>(lam.stack[j].ply) + 1;
          if (!SameAngle(ply, below)) continue;
          ++same;
          const auto theirs = seams.find(below);
          if (theirs == seams.end() || theirs->second.empty()) continue;
          Compare(mine->second, theirs->second, {0.0, ply, below, 0, lam.stagger_offset_mm}, near);
        }
      }
    }
    for (const auto& [line, s] : near) {
      char buf[240];
      std::snprintf(buf, sizeof(buf),
                    "a course seam of ply %d lies %.4g mm from a seam of ply %d (line %d), the "
                    "same fibre angle within the stagger window: closer than the stagger offset "
                    "of %.4g mm",
                    s.ply, s.value, s.below, s.other_line, s.offset);
      Record(FindingSeverity::kError, s.value, s.offset, line, 0, "ply " + std::to_string(s.ply),
             buf, nullptr, &s.at);
      if (drawn_.empty() || s.value < (drawn_[1] - drawn_[0]).norm()) drawn_ = {s.at, s.other};
    }
  }

  // The nearest seams under the offset: the seam point, then the other ply's seam point
  // nearest it (part mm), for its close-up.
  std::vector<DrawnPoints> Drawings() const override {
    if (drawn_.empty()) return {};
    return {{"close_up:afp_stagger", drawn_}};
  }

 private:
  bool SameAngle(int a, int b) const {
    const auto& plies = scene_->plies;
    if (a < 1 || b < 1 || a > static_cast<int>(plies.size()) || b > static_cast<int>(plies.size()))
      return false;
    const double d = std::remainder(plies[static_cast<std::size_t>(a) - 1].angle_rad -
                                        plies[static_cast<std::size_t>(b) - 1].angle_rad,
                                    kPi);
    return std::abs(d) < 1e-6;
  }

  // The pieces of the ply's course edges that lie within half a tow width of another course's
  // edge.
  std::vector<StaggerPiece> Seams(const StaggerPly& edges) const {
    const double near = 0.5 * laid_->Layout().width_mm;
    std::vector<std::pair<int, const StaggerPoint*>> points;  // (course, point)
    StaggerGrid grid(std::max(near, 1.0));
    for (const auto& [course, e] : edges)
      for (const auto& side : e.side)
        for (const StaggerPoint& p : side) {
          grid.Add(p.p, points.size());
          points.push_back({course, &p});
        }
    const auto is_seam = [&](int course, const Eigen::Vector3d& p) {
      bool found = false;
      grid.Near(p, [&](std::size_t id) {
        found |= points[id].first != course && (points[id].second->p - p).norm() < near;
      });
      return found;
    };
    std::vector<StaggerPiece> out;
    for (const auto& [course, e] : edges)
      for (const auto& side : e.side)
        for (std::size_t q = 1; q < side.size(); ++q) {
          if (is_seam(course, side[q - 1].p) && is_seam(course, side[q].p)) {
            out.push_back({side[q - 1].p, side[q].p, side[q].line});
          }
        }
    return out;
  }

  // Every point of `mine` against the pieces of `theirs`: distances under `pair.offset` kept
  // per line, the nearest (`pair`: the two plies and the offset).
  void Compare(const std::vector<StaggerPiece>& mine, const std::vector<StaggerPiece>& theirs,
               const StaggerNear& pair, std::map<int, StaggerNear>& near) {
    const double offset = pair.offset;
    double longest = 0.0;
    for (const StaggerPiece& s : theirs) longest = std::max(longest, (s.b - s.a).norm());
    StaggerGrid grid(std::max(offset + longest, 1.0));
    for (std::size_t i = 0; i < theirs.size(); ++i) grid.Add(0.5 * (theirs[i].a + theirs[i].b), i);
    const double reach = offset + longest;
    for (const StaggerPiece& s : mine) {
      double best = std::numeric_limits<double>::infinity();
      int best_line = 0;
      Eigen::Vector3d best_point = Eigen::Vector3d::Zero();
      grid.Near(s.b, [&](std::size_t id) {
        const Eigen::Vector3d q = StaggerNearestOnSegment(s.b, theirs[id].a, theirs[id].b);
        const double d = (s.b - q).norm();
        if (d < best) {
          best = d;
          best_line = theirs[id].line;
          best_point = q;
        }
      });
      if (!(best < reach)) {  // no seam within reach: at least the offset away
        Counted();
        continue;
      }
      ObserveSmallest(best, s.line, 0);
      if (best >= offset) continue;
      const auto it = near.find(s.line);
      if (it == near.end() || best < it->second.value) {
        StaggerNear t = pair;
        t.value = best;
        t.other_line = best_line;
        t.at = s.b;
        t.other = best_point;
        near[s.line] = t;
      }
    }
  }

  std::shared_ptr<detail::LaidTows> laid_;
  const scene::Scene* scene_;
  std::map<int, StaggerPly> plies_;     ///< by ply number: what each laid
  std::vector<Eigen::Vector3d> drawn_;  ///< see Drawings()
};

}  // namespace

RuleEntry AfpStaggerRuleEntry() {
  return {"afp.stagger", CloseUpFamily::kAfp,
          [](const RuleContext& ctx) {
            if (ctx.scene->head.IsStitching()) return RulePresence::Absent();
            if (ctx.scene->laminates.empty()) {
              return RulePresence::Skipped("no laminate in the scene (laminates:)");
            }
            return RulePresence::Runs();
          },
          detail::MakeLaying<StaggerRule>};
}

}  // namespace stitchsim::verify
