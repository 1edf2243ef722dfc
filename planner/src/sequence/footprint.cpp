// Tow footprints of a programme's courses and their overlap (sequence/precedence.h).
#include <algorithm>
#include <array>
#include <cmath>

#include "grid.h"
#include "stitchsim/planner/sequence/precedence.h"

namespace stitchsim::planner {
namespace {

using Quad = CourseFootprint::Quad;

double AreaElement(const geom::Surface& s, const Eigen::Vector2d& uv) {
  const Eigen::Matrix<double, 3, 2> j = s.Jacobian(uv);
  return j.col(0).cross(j.col(1)).norm();
}

double SignedArea(const std::array<Eigen::Vector2d, 4>& q) {
  double a = 0.0;
  for (int i = 0; i < 4; ++i) {
    const auto& p = q[static_cast<std::size_t>(i)];
    const auto& r = q[static_cast<std::size_t>((i + 1) % 4)];
    a += p.x() * r.y() - r.x() * p.y();
  }
  return 0.5 * a;
}

// Tow quads between two crossings, for every tow of `tows` (bit t - 1: tow t).
void AddQuads(const process::TowCross& a, const process::TowCross& b, std::uint64_t tows,
              int tow_count, CourseFootprint& f) {
  for (int t = 1; t <= tow_count; ++t) {
    if (((tows >> (t - 1)) & 1U) == 0) continue;
    std::array<Eigen::Vector2d, 4> q = {
        a.boundary_uv[static_cast<std::size_t>(t - 1)], a.boundary_uv[static_cast<std::size_t>(t)],
        b.boundary_uv[static_cast<std::size_t>(t)], b.boundary_uv[static_cast<std::size_t>(t - 1)]};
    if (SignedArea(q) < 0.0) std::reverse(q.begin(), q.end());
    Quad out;
    for (int i = 0; i < 4; ++i) out.uv[i] = q[static_cast<std::size_t>(i)];
    f.quads.push_back(out);
  }
}

Eigen::Isometry3d Between(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double t) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = (1.0 - t) * a.translation() + t * b.translation();
  p.linear() =
      Eigen::Quaterniond(a.linear()).slerp(t, Eigen::Quaterniond(b.linear())).toRotationMatrix();
  return p;
}

CourseFootprint FootprintOf(const geom::Surface& surface, const process::TowLayout& layout,
                            const program::AfpCourse& c) {
  CourseFootprint f;
  std::optional<process::TowCross> prev;
  Eigen::Vector2d hint = Eigen::Vector2d::Zero();
  auto cross = [&](const Eigen::Isometry3d& pose) {
    process::TowCross x = process::TowsAt(surface, pose, layout, prev ? &hint : nullptr);
    if (!x.ok) f.ok = false;
    if (x.ok) hint = x.centre_uv;
    return x;
  };
  std::optional<process::TowCross> carried;  // the last sub-step's crossing: this station's
  for (std::size_t i = 0; i < c.stations.size(); ++i) {
    const auto& st = c.stations[i];
    process::TowCross here = carried ? *carried : cross(st.pose);
    carried.reset();
    if (i + 1 < c.stations.size()) {
      const bool lays = st.tows != 0 && !st.head_retracted && st.motion == program::Motion::kFeed;
      const auto& next = c.stations[i + 1];
      // Sub-steps of at most two tow widths, so quads follow a curved surface (12.7 mm chords
      // sag 0.04 mm on a 500 mm radius).
      const double len = (next.pose.translation() - st.pose.translation()).norm();
      const int n =
          lays ? std::max(1, static_cast<int>(std::ceil(len / (2.0 * layout.width_mm)))) : 1;
      process::TowCross from = here;
      for (int k = 1; k <= n && lays; ++k) {
        prev = from;
        process::TowCross to = cross(Between(st.pose, next.pose, static_cast<double>(k) / n));
        if (from.ok && to.ok) AddQuads(from, to, st.tows, layout.tows, f);
        from = to;
      }
      if (lays) carried = from;
    }
    prev = here;
  }
  if (f.quads.empty()) return f;
  f.uv_min = f.uv_max = f.quads.front().uv[0];
  for (const Quad& q : f.quads) {
    std::array<Eigen::Vector2d, 4> a = {q.uv[0], q.uv[1], q.uv[2], q.uv[3]};
    for (const auto& p : a) {
      f.uv_min = f.uv_min.cwiseMin(p);
      f.uv_max = f.uv_max.cwiseMax(p);
    }
    f.area_mm2 +=
        SignedArea(a) * AreaElement(surface, 0.25 * (q.uv[0] + q.uv[1] + q.uv[2] + q.uv[3]));
  }
  return f;
}

}  // namespace

namespace detail {

// Sutherland-Hodgman: the part of convex polygon `subject` inside convex CCW `clip`.
double ClippedArea(const CourseFootprint::Quad& subject, const CourseFootprint::Quad& clip) {
  std::vector<Eigen::Vector2d> poly(subject.uv, subject.uv + 4), next;
  for (int e = 0; e < 4 && !poly.empty(); ++e) {
    const Eigen::Vector2d a = clip.uv[e], b = clip.uv[(e + 1) % 4];
    const Eigen::Vector2d d = b - a;
    auto side = [&](const Eigen::Vector2d& p) {
      return d.x() * (p.y() - a.y()) - d.y() * (p.x() - a.x());
    };
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& p = poly[i];
      const Eigen::Vector2d& q = poly[(i + 1) % poly.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0.0) next.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) next.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    poly.swap(next);
  }
  double area = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& p = poly[i];
    const auto& q = poly[(i + 1) % poly.size()];
    area += p.x() * q.y() - q.x() * p.y();
  }
  return std::max(0.0, 0.5 * area);
}

double QuadAreaElement(const geom::Surface& s, const CourseFootprint::Quad& q) {
  return AreaElement(s, 0.25 * (q.uv[0] + q.uv[1] + q.uv[2] + q.uv[3]));
}

}  // namespace detail

std::vector<CourseFootprint> CourseFootprints(const geom::Surface& surface,
                                              const process::TowLayout& layout,
                                              const program::AfpProgram& program) {
  std::vector<CourseFootprint> out;
  out.reserve(program.courses.size());
  for (const auto& c : program.courses) out.push_back(FootprintOf(surface, layout, c));
  return out;
}

double OverlapAreaMm2(const geom::Surface& surface, const CourseFootprint& a,
                      const CourseFootprint& b) {
  if (a.quads.empty() || b.quads.empty()) return 0.0;
  if ((a.uv_max.array() < b.uv_min.array()).any() || (b.uv_max.array() < a.uv_min.array()).any())
    return 0.0;
  double area = 0.0;
  for (const auto& qa : a.quads) {
    const double da = detail::QuadAreaElement(surface, qa);
    for (const auto& qb : b.quads) area += detail::ClippedArea(qa, qb) * da;
  }
  return area;
}

}  // namespace stitchsim::planner
