// Off-part moves between lay-ups (sequence/offpart.h, docs/sequence.md).
#include "stitchsim/planner/sequence/offpart.h"

#include <algorithm>
#include <cmath>

#include "stitchsim/common/units.h"

namespace stitchsim::planner {
namespace {

using program::Motion;
using program::OffPartBlock;

OffPartBlock Rapid(const Eigen::Isometry3d& pose, std::string comment) {
  OffPartBlock b;
  b.pose = pose;
  b.motion = Motion::kRapid;
  b.head_retracted = true;
  b.comment = std::move(comment);
  return b;
}

// Lifts `p` to `clearance` off the surface along the normal at its foot point.
Eigen::Vector3d Lifted(const geom::Surface& s, const Eigen::Vector3d& p, double clearance) {
  const geom::SurfaceProjection f = s.Project(p);
  return f.point + clearance * f.normal;
}

// Inserts via points between a and b (exclusive) until every sample of the polyline keeps
// `clearance` (less a small slack) off the surface, bisecting at the lowest sample.
void Refine(const geom::Surface& s, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
            const OffPartOptions& o, int depth, std::vector<Eigen::Vector3d>& out) {
  const double len = (b - a).norm();
  const int n = std::max(2, static_cast<int>(std::ceil(len / o.sample_mm)));
  double lowest = o.clearance_mm;
  int at = -1;
  for (int i = 1; i < n; ++i) {
    const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / n);
    const double h = HeightAboveSurface(s, p);
    if (h < lowest) {
      lowest = h;
      at = i;
    }
  }
  // 2 % slack: a chord between two points lifted to the clearance over a convex part dips a
  // little below it; bisection brings the dip under the slack.
  if (at < 0 || lowest >= 0.98 * o.clearance_mm || depth >= o.max_refinements) return;
  const Eigen::Vector3d m = Lifted(s, a + (b - a) * (static_cast<double>(at) / n), o.clearance_mm);
  Refine(s, a, m, o, depth + 1, out);
  out.push_back(m);
  Refine(s, m, b, o, depth + 1, out);
}

// Rapids from `a` to `b` through lifted via points, orientation slerped by distance.
void Travel(const geom::Surface& s, const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
            const OffPartOptions& o, std::vector<OffPartBlock>& out) {
  std::vector<Eigen::Vector3d> via;
  Refine(s, a.translation(), b.translation(), o, 0, via);
  std::vector<Eigen::Vector3d> pts;
  pts.push_back(a.translation());
  pts.insert(pts.end(), via.begin(), via.end());
  pts.push_back(b.translation());
  // A turn about the tool z of more than a right angle is made in steps under it (a via
  // point in the middle at least), so that every move's own (shortest) rotation goes the way
  // chosen.
  const double turn = o.turn_about_z_rad.value_or(TwistAboutZ(a.linear(), b.linear()));
  if (std::abs(turn) > 0.5 * kPi && pts.size() == 2)
    pts.insert(pts.begin() + 1, 0.5 * (pts[0] + pts[1]));
  double total = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) total += (pts[i] - pts[i - 1]).norm();
  // What is left once turned: a small tilt (the next course's normal), taken proportionally.
  const Eigen::Quaterniond rest(
      (a.linear() * Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ())).transpose() * b.linear());
  double run = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    run += (pts[i] - pts[i - 1]).norm();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const double t = total > 0.0 ? run / total : 1.0;
    // Turned about z by the fraction of the chosen turn, and the same fraction of the rest.
    pose.linear() = a.linear() * Eigen::AngleAxisd(t * turn, Eigen::Vector3d::UnitZ()) *
                    Eigen::Quaterniond::Identity().slerp(t, rest).toRotationMatrix();
    pose.translation() = pts[i];
    out.push_back(Rapid(pose, i + 1 == pts.size() ? "travel" : "travel via"));
  }
}

}  // namespace

Eigen::Isometry3d RaisedPose(const Eigen::Isometry3d& pose, double h) {
  Eigen::Isometry3d r = pose;
  r.translation() += h * pose.linear().col(2);
  return r;
}

double TwistAboutZ(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d r = a.transpose() * b;
  return std::atan2(r(1, 0) - r(0, 1), r(0, 0) + r(1, 1));
}

double UnwindingTurn(double twist, double shorter) {
  const double other = shorter > 0.0 ? shorter - 2.0 * kPi : shorter + 2.0 * kPi;
  const bool near_half = std::abs(shorter) > 0.5 * kPi;
  const bool winding = std::abs(twist + shorter) > 1.5 * kPi;
  if ((near_half || winding) && std::abs(twist + other) < std::abs(twist + shorter)) return other;
  return shorter;
}

double HeightAboveSurface(const geom::Surface& surface, const Eigen::Vector3d& p) {
  const geom::SurfaceProjection f = surface.Project(p);
  return (p - f.point).dot(f.normal);
}

std::vector<OffPartBlock> OffPartPath(const geom::Surface& surface,
                                      const std::optional<OffPartEnd>& from,
                                      const std::optional<OffPartEnd>& to,
                                      std::optional<double> feed_mm_per_min,
                                      const OffPartOptions& options) {
  std::vector<OffPartBlock> out;
  std::optional<Eigen::Isometry3d> here;
  if (from) {
    here = from->on_surface ? RaisedPose(from->pose, options.retract_mm) : from->pose;
    if (from->on_surface) out.push_back(Rapid(*here, "retract"));
  }
  if (!to) {
    return out;
  }
  const Eigen::Isometry3d above =
      to->on_surface ? RaisedPose(to->pose, options.retract_mm) : to->pose;
  if (here) {
    Travel(surface, *here, above, options, out);
  } else {
    out.push_back(Rapid(above, "travel"));
  }
  if (to->on_surface) {
    OffPartBlock down;
    down.pose = to->pose;
    down.motion = Motion::kFeed;
    down.head_retracted = false;
    down.feed_mm_per_min = feed_mm_per_min;
    down.comment = "approach";
    out.push_back(down);
  }
  return out;
}

double OffPartLength(const Eigen::Vector3d& from, const std::vector<OffPartBlock>& blocks) {
  double len = 0.0;
  Eigen::Vector3d p = from;
  for (const auto& b : blocks) {
    len += (b.pose.translation() - p).norm();
    p = b.pose.translation();
  }
  return len;
}

}  // namespace stitchsim::planner
