// afp.steering_radius: the geodesic curvature of each laid tow's centre line (its turning in
// the tangent plane per arc length), as a radius, against the head's smallest steering radius.
// A tow's centre line is followed from line to line of a course; the turning is measured
// between the chords of consecutive lines (at their shared vertex, a finding of both lines,
// over the mean of their arcs) and between the two halves of each line (the tow sweeps when
// the head turns along a line). Chords and halves are at least one tow width long: shorter
// lines (a planner inserts them at tow cuts) are joined into one chord first, or the
// programme's number rounding (1e-6 mm) over a 0.01 mm move would read as a 100 mm radius. A curve
// in space that is a geodesic of the surface (a helix on a cylinder) does not steer: its turning
// lies along the normal.
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "stitchsim/geom/surface_walk.h"

namespace stitchsim::verify {
namespace {

using detail::LaidLine;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A tow's centre line over one line: its ends, the pose in the middle and the arc lengths.
struct TowPath {
  bool ok = false;
  Eigen::Vector3d start, mid, end;
  Eigen::Vector2d start_uv = Eigen::Vector2d::Zero(), mid_uv = Eigen::Vector2d::Zero();
  double arc_first = 0.0, arc_second = 0.0;  ///< mm, before and after `mid`
};

TowPath PathOf(const LaidLine& line, const geom::Surface& surface, int tow) {
  TowPath p;
  const std::size_t n = line.poses.size();
  const std::size_t m = n / 2;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!line.poses[i].cross.ok) return p;
    const Eigen::Vector2d uv = detail::TowCentreUv(line.poses[i].cross, tow);
    const Eigen::Vector3d q = surface.Point(uv);
    if (i == 0) p.start = q, p.start_uv = uv;
    if (i == m) p.mid = q, p.mid_uv = uv;
    if (i > 0) (i <= m ? p.arc_first : p.arc_second) += (q - previous).norm();
    previous = q;
  }
  p.end = previous;
  p.ok = n >= 2;
  return p;
}

// Radius of the turn from chord `a` to chord `b` in the tangent plane of normal `n`, over the
// arc length `arc` (mm); infinity without a turn.
double TurnRadius(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& n,
                  double arc) {
  if (a.norm() < 1e-9 || b.norm() < 1e-9) return kInfinity;
  const Eigen::Vector3d ta = geom::Tangential(a, n), tb = geom::Tangential(b, n);
  const double turn = std::abs(std::atan2(ta.cross(tb).dot(n), ta.dot(tb)));
  return turn < 1e-12 ? kInfinity : arc / turn;
}

class SteeringRadiusRule final : public Rule {
 public:
  SteeringRadiusRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.steering_radius",
             "steering radius (geodesic curvature of the centre line) of every laid tow against "
             "the smallest the head allows (worst = smallest)",
             "mm"),
        laid_(std::move(laid)),
        chains_(static_cast<std::size_t>(laid_->Layout().tows) + 1),
        paths_(chains_.size()),
        baseline_mm_(laid_->Layout().width_mm) {
    const std::optional<double> given = ctx.scene->limits.Get(scene::LimitKey::kAfpSteeringMinMm);
    summary_.error_limit = given ? *given : ctx.scene->head.afp.min_steering_radius_mm;
    worst_is_smallest_ = true;
    mergeable_ = false;  // judged over whole plies (Rule::Mergeable)
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      AddSubject("tow " + std::to_string(t), summary_.error_limit, std::nullopt);
    }
  }

  void OnLine(const trace::LineRecord& record) override {
    const LaidLine* line = laid_->Sample(record);
    if (line == nullptr) {
      Flush();
      for (Chain& c : chains_) c.ok = false;
      return;
    }
    const geom::Surface& surface = laid_->Surface();
    const double join_tol = 0.25 * laid_->Layout().width_mm;
    double vertex_radius = kInfinity;  // this line's start vertex, smallest over the tows
    int vertex_tow = 0;
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      Chain& chain = chains_[static_cast<std::size_t>(t)];
      TowPath& path = paths_[static_cast<std::size_t>(t)];
      path = detail::TowLaid(line->tows, t) ? PathOf(*line, surface, t) : TowPath{};
      if (!path.ok) {
        chain.ok = false;
        continue;
      }
      const double arc = path.arc_first + path.arc_second;
      const Eigen::Vector3d& last_end = chain.acc ? chain.acc_end : chain.end;
      const bool continues =
          chain.ok && chain.course == line->course && (last_end - path.start).norm() < join_tol;
      if (!continues) {
        chain = Chain{true, line->course, path.start, path.end, arc};
      } else if (chain.arc < baseline_mm_) {
        chain.end = path.end;  // the first chord of the course, not a baseline long yet
        chain.arc += arc;
      } else {
        // The chord after the last one grows over short lines until it is a baseline long.
        const Eigen::Vector3d from = chain.acc ? chain.acc_start : path.start;
        const double grown = (chain.acc ? chain.acc_arc : 0.0) + arc;
        if (grown < baseline_mm_) {
          chain.acc = true;
          chain.acc_start = from;
          chain.acc_end = path.end;
          chain.acc_arc = grown;
        } else {
          // The vertex between the two chords: reported on the line before it and this one.
          const double r = TurnRadius(chain.end - chain.start, path.end - from,
                                      surface.Normal(path.start_uv), 0.5 * (chain.arc + grown));
          Consider(r, pending_line_, t);
          if (r < vertex_radius) vertex_radius = r, vertex_tow = t;
          chain = Chain{true, line->course, from, path.end, grown};
        }
      }
    }
    Flush();
    // The vertex belongs to both lines; then the turn inside this line, between its halves.
    pending_line_ = line->source_line;
    pending_radius_ = vertex_radius;
    pending_tow_ = vertex_tow;
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      const TowPath& path = paths_[static_cast<std::size_t>(t)];
      if (!path.ok || line->poses.size() < 3) continue;
      if (path.arc_first < baseline_mm_ || path.arc_second < baseline_mm_) continue;
      Consider(TurnRadius(path.mid - path.start, path.end - path.mid, surface.Normal(path.mid_uv),
                          0.5 * (path.arc_first + path.arc_second)),
               line->source_line, t);
    }
  }

  void Finish(const RuleContext&) override { Flush(); }

 private:
  struct Chain {
    bool ok = false;
    int course = 0;
    Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();
    double arc = 0.0;
    /// Lines after the chord above, shorter together than a baseline: not measured yet.
    bool acc = false;
    Eigen::Vector3d acc_start = Eigen::Vector3d::Zero(), acc_end = Eigen::Vector3d::Zero();
    double acc_arc = 0.0;
  };

  // Counts one measurement of tow `tow` and tracks the smallest radius (the rule's and the
  // tow's: Rule::Observe keeps the largest).
  void Consider(double radius, int line, int tow) {
    Counted();
    if (!summary_.worst_value || radius < *summary_.worst_value) {
      summary_.worst_value = radius;
      summary_.worst_line = line;
    }
    SubjectFigure& figure = summary_.subjects[static_cast<std::size_t>(tow) - 1];
    ++figure.checked;
    if (!figure.worst_value || radius < *figure.worst_value) {
      figure.worst_value = radius;
      figure.worst_line = line;
    }
    if (line == pending_line_ && radius < pending_radius_) {
      pending_radius_ = radius;
      pending_tow_ = tow;
    }
  }

  // Records the pending line's smallest radius, if below the limit (one finding per line).
  void Flush() {
    if (pending_line_ > 0 && pending_radius_ < *summary_.error_limit) {
      char buf[200];
      std::snprintf(buf, sizeof(buf),
                    "tow %d steers on a radius of %.4g mm, below the head's smallest steering "
                    "radius of %.4g mm",
                    pending_tow_, pending_radius_, *summary_.error_limit);
      Record(FindingSeverity::kError, pending_radius_, *summary_.error_limit, pending_line_, 0,
             "tow " + std::to_string(pending_tow_), buf, nullptr);
    }
    pending_line_ = 0;
    pending_radius_ = kInfinity;
  }

  std::shared_ptr<detail::LaidTows> laid_;
  std::vector<Chain> chains_;   ///< per tow (index 1..k): its centre line over the last line
  std::vector<TowPath> paths_;  ///< per tow: over the current line
  double baseline_mm_;          ///< shortest chord a turn is measured over: one tow width
  int pending_line_ = 0;        ///< the last laying line, whose end vertex is not measured yet
  double pending_radius_ = kInfinity;
  int pending_tow_ = 0;
};

}  // namespace

std::unique_ptr<Rule> MakeAfpSteeringRule(const RuleContext& ctx,
                                          std::shared_ptr<detail::LaidTows> laid) {
  return std::make_unique<SteeringRadiusRule>(ctx, std::move(laid));
}

}  // namespace stitchsim::verify
