#pragma once
// Shared by the afp.* rule tests: an AFP scene made in code (a plane or a cylinder, the
// default 16-tow head of 6.35 mm), tool poses on its surface, hand-made laying lines, and a
// verifier run over them (no simulator: verify reads only the trace).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/surface_walk.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::verify::testing {

inline constexpr double kTowWidth = 6.35;
/// Every tow of the default 16-tow head, as a line's tow mask.
inline constexpr std::uint64_t kAllTows = 0xFFFF;
/// Every tow of the default head but `tow` (1-based).
inline constexpr std::uint64_t AllTowsBut(int tow) { return kAllTows & ~(1ULL << (tow - 1)); }

inline std::unique_ptr<scene::Scene> AfpScene(std::unique_ptr<geom::Surface> surface) {
  auto s = std::make_unique<scene::Scene>();
  s->name = "afp_test";
  s->head.kind = scene::HeadKind::kAfp;
  s->head.name = "afp";
  s->surface = std::move(surface);
  return s;
}

/// The tool pose with its point on the surface at `uv`, travelling along the surface image of
/// the (u, v) direction `dir_uv`, head axis on the normal; `lift_mm` along the normal.
inline Eigen::Isometry3d ToolAt(const geom::Surface& s, const Eigen::Vector2d& uv,
                                const Eigen::Vector2d& dir_uv, double lift_mm = 0.0) {
  const Eigen::Vector3d z = s.Normal(uv);
  const Eigen::Vector3d y = geom::Tangential(s.Jacobian(uv) * dir_uv, z);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = y.cross(z);
  t.linear().col(1) = y;
  t.linear().col(2) = z;
  t.translation() = s.Point(uv) + lift_mm * z;
  return t;
}

/// The tool at arc angle `theta` (rad) round a convex cylinder of radius `r` (mm; axis along
/// x at z = -r), travelling round it: built from the closed form, not the surface model.
inline Eigen::Isometry3d RoundCylinder(double r, double theta) {
  const Eigen::Vector3d normal(0, std::sin(theta), std::cos(theta));
  const Eigen::Vector3d travel(0, std::cos(theta), -std::sin(theta));
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = travel.cross(normal);
  t.linear().col(1) = travel;
  t.linear().col(2) = normal;
  t.translation() = Eigen::Vector3d(0, r * std::sin(theta), r * std::cos(theta) - r);
  return t;
}

/// A feed move with the head down, laying `tows` in course `course` of ply `ply`.
inline trace::LineRecord LayLine(int line, const Eigen::Isometry3d& from,
                                 const Eigen::Isometry3d& to, std::uint64_t tows = 0xFFFF,
                                 int course = 1, int ply = 1) {
  trace::LineRecord l;
  l.source_line = line;
  l.from = from;
  l.to = to;
  l.tows = tows;
  l.course = course;
  l.ply = ply;
  l.feed_mm_per_min = 6000;
  return l;
}

/// Runs the verifier over `lines` (no samples: the afp.* rules read lines); `then`, when
/// given, reads the finished verifier. `keep_stitch_marks`: as verify --snapshots / --html
/// (the verifier keeps what was laid, Verifier::Laid()).
inline Report RunLines(const scene::Scene& scene, const std::vector<trace::LineRecord>& lines,
                       const std::function<void(const Verifier&)>& then = {},
                       bool keep_stitch_marks = false) {
  const process::ProcessModel model = process::MakeProcessModel(scene, 5.0);
  trace::CellDescription cell;
  cell.lower_limits.setConstant(-10.0);
  cell.upper_limits.setConstant(10.0);
  cell.max_velocities.setConstant(10.0);
  Verifier v(RuleContext{&scene, &cell, &model}, keep_stitch_marks);
  for (const auto& l : lines) v.OnLine(l);
  Report r;
  v.Finish(r);
  if (then) then(v);
  return r;
}

inline const RuleSummary* RuleOf(const Report& r, const std::string& id) {
  for (const auto& s : r.rules) {
    if (s.id == id) return &s;
  }
  return nullptr;
}
// A temporary report would die before its rule is read (the sanitizer run caught one).
const RuleSummary* RuleOf(Report&& r, const std::string& id) = delete;

/// The figure of subject `name` of `rule` (a test failure if it has none).
inline const SubjectFigure& SubjectOf(const RuleSummary& rule, const std::string& name) {
  for (const auto& s : rule.subjects) {
    if (s.subject == name) return s;
  }
  ADD_FAILURE() << "no subject " << name;
  return rule.subjects.front();
}

}  // namespace stitchsim::verify::testing
