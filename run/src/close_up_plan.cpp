// What a close-up shows, per rule family (run/close_up.h): collisions, needles and stitches
// here; the arm, constraint crossings and the head in close_up_arm.cpp.
#include <algorithm>
#include <cmath>
#include <optional>

#include "detail/close_up_draw.h"
#include "stitchsim/common/units.h"
#include "stitchsim/render/scene_model.h"
#include "stitchsim/run/start_pose.h"

namespace stitchsim::run {
namespace close_up {
namespace {

using namespace colours;  // NOLINT: the palette

// The farthest a body reaches from `from` (world, m): its geoms' centres plus bounding radii.
double Reach(const mjModel& m, const mjData& d, const std::vector<int>& geoms,
             const Eigen::Vector3d& from) {
  double r = 0.0;
  for (int g : geoms) r = std::max(r, (GeomCentre(d, g) - from).norm() + m.geom_rbound[g]);
  return r;
}

// The geom of `geoms` whose centre is nearest `p`.
Eigen::Vector3d NearestCentre(const mjData& d, const std::vector<int>& geoms,
                              const Eigen::Vector3d& p) {
  Eigen::Vector3d best = p;
  double dist = 1e18;
  for (int g : geoms) {
    const Eigen::Vector3d c = GeomCentre(d, g);
    if ((c - p).norm() < dist) {
      dist = (c - p).norm();
      best = c;
    }
  }
  return best;
}

// Viewing directions along the surface at `point_m` (world; `normal` its normal there), the
// straightest way first (how far the surface leaves its tangent plane 50 mm away), both ways,
// level and from a little above; from the normal's side.
std::vector<Eigen::Vector3d> StraightestTangents(const geom::Surface& surface,
                                                 const Eigen::Isometry3d& part,
                                                 const Eigen::Vector3d& point_m,
                                                 const Eigen::Vector3d& normal) {
  const Eigen::Vector3d t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  std::vector<std::pair<double, Eigen::Vector3d>> ways;
  for (int k = 0; k < 4; ++k) {  // a half turn: each line both ways below
    const double a = kPi * k / 4;
    const Eigen::Vector3d t = std::cos(a) * t1 + std::sin(a) * t2;
    double bend = 0.0;
    for (double s : {-0.05, 0.05}) {
      const Eigen::Vector3d q = part.inverse() * (point_m + s * t) * 1000.0;
      bend += std::abs((part * (surface.Project(q).point / 1000.0) - point_m).dot(normal));
    }
    ways.emplace_back(bend, t);
  }
  std::sort(ways.begin(), ways.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Eigen::Vector3d> out;
  for (const auto& [bend, t] : ways) {
    for (double tilt : {0.15, 0.5}) {
      out.push_back(t - tilt * normal);
      out.push_back(-t - tilt * normal);
    }
  }
  return out;
}

// Joints for the picture: the sample's, else a solved pose at its tool point.
trace::JointVector PictureJoints(const CloseUpContext& ctx, const trace::TraceSample& s) {
  if (s.has_joints) return s.joints;
  return SolveStartPose(*ctx.ls, s.tool_part).joints;
}

// Collision rules: the two bodies of the deepest contact (or the closest pair).
bool PlanCollision(const CloseUpContext& ctx, const verify::Rule& rule, const trace::TraceSample& s,
                   CloseUpPlan& plan) {
  const mjModel& m = *ctx.model;
  const mjData& d = *ctx.data;
  const std::string& id = rule.Summary().id;
  const trace::Contact* contact = nullptr;
  for (const trace::Contact& c : s.collision.contacts) {
    const bool fits = id == "collision.head_mold" ? c.kind == trace::ContactClass::kHeadPart
                                                  : c.kind == trace::ContactClass::kRobotCell;
    if ((fits || id == "collision.clearance") && (!contact || c.depth_m > contact->depth_m)) {
      contact = &c;
    }
  }
  const int ia = contact ? contact->body_a : s.collision.clearance_body_a;
  const int ib = contact ? contact->body_b : s.collision.clearance_body_b;
  const auto& names = ctx.cell->bodies;
  if (ia < 0 || ib < 0 || static_cast<std::size_t>(std::max(ia, ib)) >= names.size()) {
    return false;
  }
  const std::string& a = names[static_cast<std::size_t>(ia)];
  const std::string& b = names[static_cast<std::size_t>(ib)];
  const std::vector<int> ga = render::GeomsOfCollisionBody(m, a);
  const std::vector<int> gb = render::GeomsOfCollisionBody(m, b);
  if (ga.empty() || gb.empty()) return false;
  Eigen::Vector3d point;
  if (contact) {
    point = contact->point_world_m;
  } else {  // clearance: between the nearest geoms of the pair
    const Eigen::Vector3d ca = NearestCentre(d, ga, GeomCentre(d, gb.front()));
    point = 0.5 * (ca + NearestCentre(d, gb, ca));
  }
  plan.centre_m = point;
  // The smaller body whole with room around it (the other one is often a rail or a mold).
  plan.radius_m =
      std::clamp(1.6 * std::min(Reach(m, d, ga, point), Reach(m, d, gb, point)), 0.08, 1.0);
  // The head in the part: the part's normal there. Looked at first along the surface where it
  // runs straightest (a cylinder's axis: the mold's section shows), from the head's side.
  std::optional<Eigen::Vector3d> normal;
  if (contact && contact->kind == trace::ContactClass::kHeadPart) {
    const Eigen::Isometry3d part = PartWorld(m, d);
    normal =
        part.linear() * ctx.ls->scene->surface->Project(part.inverse() * point * 1000.0).normal;
    plan.directions = StraightestTangents(*ctx.ls->scene->surface, part, point, *normal);
  }
  for (const Eigen::Vector3d& dir : Ring(8, {-30.0, -60.0, 5.0})) plan.directions.push_back(dir);
  if (normal) {  // the head opaque, the part (large) more see-through
    Recolour(plan, ga, {kBodyA[0], kBodyA[1], kBodyA[2], 1.0f});
    Recolour(plan, gb, {kBodyB[0], kBodyB[1], kBodyB[2], 0.35f});
  } else {
    Recolour(plan, ga, kBodyA);
    Recolour(plan, gb, kBodyB);
  }
  plan.subjects.push_back({a, ga, {}});
  plan.subjects.push_back({b, gb, {}});
  plan.legend.push_back({render::ToRgb(kBodyA), a});
  plan.legend.push_back({render::ToRgb(kBodyB), b});
  const double marker = std::max(0.003, plan.radius_m * 0.02);
  plan.overlays.push_back(MakeOverlay("contact", kMarker, marker, {point}, false));
  plan.legend.push_back({render::ToRgb(kMarker), contact ? "deepest contact point" : "gap"});
  if (contact && contact->depth_m > 0.0) {
    // The depth as a bar out of the contact point: along the part's normal for the head in
    // the part, else towards the first body's nearest geom (the one that moved in).
    const Eigen::Vector3d dir =
        normal ? *normal : (NearestCentre(d, ga, point) - point).normalized();
    render::Overlay bar =
        MakeOverlay("depth", kDepth, marker * 0.35, {point, point + contact->depth_m * dir}, true);
    bar.arrow_head = true;
    plan.overlays.push_back(std::move(bar));
    plan.legend.push_back(
        {render::ToRgb(kDepth), "depth " + Fmt("%.1f", contact->depth_m * 1e3) + " mm" +
                                    (contact->depth_measured ? "" : " (one facet)")});
  } else if (!contact) {
    plan.legend.push_back({render::ToRgb(kMarker),
                           "clearance " + Fmt("%.1f", s.collision.min_clearance_m * 1e3) + " mm"});
  }
  return true;
}

// A "nice" magnification (1, 2, 5 x 10^k) that draws `largest_mm` about `target_mm` long.
double Magnification(double largest_mm, double target_mm) {
  if (largest_mm <= 1e-9) return 10.0;
  const double want = target_mm / largest_mm;
  double best = 1.0;
  for (double decade = 1.0; decade <= 1000.0; decade *= 10.0) {
    for (double k : {1.0, 2.0, 5.0}) {
      if (k * decade <= want) best = k * decade;
    }
  }
  return best;
}

std::vector<int> HeadGeomsNamed(const mjModel& m, const std::string& part_of_name) {
  const int head = mj_name2id(&m, mjOBJ_BODY, "head");
  std::vector<int> out;
  for (int g : render::GeomsOfBody(m, head)) {
    const char* n = mj_id2name(&m, mjOBJ_GEOM, g);
    if (n != nullptr && std::string(n).find(part_of_name) != std::string::npos) out.push_back(g);
  }
  return out;
}

// The preform as a section across the stitch line: its top and the mold surface under it.
void AddSection(const CloseUpContext& ctx, const Eigen::Isometry3d& tool_mm,
                const Eigen::Vector3d& across, const Eigen::Isometry3d& part_world,
                double half_width_mm, CloseUpPlan& plan) {
  const scene::Scene& scene = *ctx.ls->scene;
  std::vector<Eigen::Vector3d> top, bottom;
  for (int k = -12; k <= 12; ++k) {
    const Eigen::Vector3d q = tool_mm.translation() + (half_width_mm * k / 12.0) * across;
    const geom::SurfaceProjection f = scene.surface->Project(q);
    bottom.push_back(part_world * (f.point / 1000.0));
    top.push_back(part_world * ((f.point + scene.preform_thickness_mm * f.normal) / 1000.0));
  }
  plan.overlays.push_back(MakeOverlay("preform_top", kPreformTop, 0.0008, top, true));
  plan.overlays.push_back(MakeOverlay("mold_surface", kMoldLine, 0.0008, bottom, true));
  plan.legend.push_back({render::ToRgb(kPreformTop), "preform top (section)"});
  plan.legend.push_back({render::ToRgb(kMoldLine), "mold surface (preform underside)"});
}

// Arrows from where each needle's shaft points went in to where they are at the worst sample
// after the walk (the side-force proxy's drift, process/stitch_cycle.h), magnified; part
// frame mm in, world out.
Eigen::Vector3d AddDrift(const CloseUpContext& ctx, const Eigen::Isometry3d& entry_mm,
                         const Eigen::Isometry3d& now_mm, const Eigen::Isometry3d& part_world,
                         CloseUpPlan& plan) {
  // The walk moves the needles along head y, cancelling the tool point's travel along it.
  const Eigen::Vector3d walk(
      0.0, -now_mm.linear().col(1).dot(now_mm.translation() - entry_mm.translation()), 0.0);
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> moves;  // part frame, mm
  double largest_mm = 0.0;
  Eigen::Vector3d largest = Eigen::Vector3d::Zero();
  for (const scene::NeedleSpec& n : ctx.process->needles) {
    if (std::abs(n.direction.z()) < 1e-6) continue;
    const Eigen::Vector3d axis = now_mm.linear() * n.direction;
    for (double z : ctx.process->shaft_heights_mm) {
      const Eigen::Vector3d shaft =
          n.through_mm + (z - n.through_mm.z()) / n.direction.z() * n.direction;
      const Eigen::Vector3d from = entry_mm * shaft;
      Eigen::Vector3d drift = now_mm * (shaft + walk) - from;
      drift -= drift.dot(axis) * axis;  // along the needle is the stitch itself
      moves.emplace_back(from, drift);
      if (drift.norm() > largest_mm) {
        largest_mm = drift.norm();
        largest = drift;
      }
    }
  }
  const double k = Magnification(largest_mm, 20.0);
  for (const auto& [from, drift] : moves) {
    const Eigen::Vector3d a = part_world * (from / 1000.0);
    const Eigen::Vector3d b = part_world * ((from + k * drift) / 1000.0);
    render::Overlay arrow = MakeOverlay("drift", kDrift, 0.0006, {a, b}, true);
    arrow.arrow_head = true;
    if ((b - a).norm() < 1e-4) arrow = MakeOverlay("drift", kDrift, 0.0008, {a}, false);
    plan.overlays.push_back(std::move(arrow));
  }
  plan.legend.push_back({render::ToRgb(kDrift), "needle drift after the walk, x" + Fmt("%.0f", k) +
                                                    " (largest " + Fmt("%.3f", largest_mm) +
                                                    " mm)"});
  return largest;
}

// Needle and stitch rules: the needles and the presser foot, the preform as a section.
bool PlanNeedles(const CloseUpContext& ctx, const verify::Rule& rule, const trace::TraceSample& s,
                 CloseUpPlan& plan) {
  const mjModel& m = *ctx.model;
  const Eigen::Isometry3d part = PartWorld(m, *ctx.data);
  const Eigen::Isometry3d now = part * ToMetres(s.tool_part);
  std::vector<int> needles;
  for (int g : HeadGeomsNamed(m, "needle")) {
    if (m.geom_type[g] == mjGEOM_CAPSULE || m.geom_type[g] == mjGEOM_CYLINDER) {
      needles.push_back(g);
    }
  }
  const std::vector<int> foot = HeadGeomsNamed(m, "presser_foot");
  if (needles.empty()) return false;
  // The needles from the mold surface up into the head, the presser foot across.
  plan.centre_m =
      now * Eigen::Vector3d(0, 0, (0.5 * ctx.ls->scene->preform_thickness_mm + 10.0) / 1000.0);
  plan.radius_m = 0.05;
  // Drift arrows seen side on: looking across the largest drift (with no drift, along the
  // stitch line), the section drawn along it.
  Eigen::Vector3d across = s.tool_part.linear().col(0);  // part frame
  if (rule.WorstEntryTool()) {
    const Eigen::Vector3d d = AddDrift(ctx, *rule.WorstEntryTool(), s.tool_part, part, plan);
    const Eigen::Vector3d z_part = s.tool_part.linear().col(2);
    if ((d - d.dot(z_part) * z_part).norm() > 1e-6)
      across = (d - d.dot(z_part) * z_part).normalized();
  }
  const Eigen::Vector3d z = now.linear().col(2), x = part.linear() * across, y = z.cross(x);
  for (double side : {1.0, -1.0}) {
    for (double tilt : {12.0, 30.0}) {
      for (double yaw : {0.0, 25.0}) {
        const double t = tilt * kPi / 180.0, w = yaw * kPi / 180.0;
        const Eigen::Vector3d along = side * (std::cos(w) * y + std::sin(w) * x);
        plan.directions.push_back(std::cos(t) * along - std::sin(t) * z);
      }
    }
  }
  for (int g : render::GeomsOfCollisionBody(m, "mold")) plan.style.transparent.push_back(g);
  for (int g : render::GeomsOfCollisionBody(m, "preform")) plan.style.transparent.push_back(g);
  Recolour(plan, needles, kNeedles);
  plan.subjects.push_back({"needles", needles, {}});
  plan.legend.push_back({render::ToRgb(kNeedles), "needles"});
  if (!foot.empty()) {
    Recolour(plan, foot, kFoot);
    plan.subjects.push_back({"presser foot", foot, {}});
    plan.legend.push_back({render::ToRgb(kFoot), "presser foot"});
  }
  AddSection(ctx, s.tool_part, across, part, 40.0, plan);
  std::vector<Eigen::Vector3d> pierced;
  for (const auto& p :
       process::PenetrationPoints(*ctx.process, *ctx.ls->scene->surface, s.tool_part)) {
    if (p) pierced.push_back(part * (*p / 1000.0));
  }
  if (!pierced.empty()) {
    plan.overlays.push_back(MakeOverlay("penetration", kMarker, 0.0015, pierced, false));
    plan.legend.push_back({render::ToRgb(kMarker), "where the needles pierce the surface"});
  }
  return true;
}

}  // namespace
}  // namespace close_up

const verify::Finding* FocusFinding(const verify::Rule& rule) {
  const auto& f = rule.Summary().findings;
  // The worst sample's line; afp.* rules judge lines, not samples: their worst line.
  const bool by_line = !rule.WorstSample() && rule.CloseUp() == verify::CloseUpFamily::kAfp;
  const int line = rule.WorstSample() ? rule.WorstSample()->source_line
                                      : (by_line ? rule.Summary().worst_line : -1);
  for (const auto& x : f) {
    if (x.line == line && x.severity == verify::FindingSeverity::kError) return &x;
  }
  for (const auto& x : f) {
    if (x.severity == verify::FindingSeverity::kError) return &x;
  }
  return f.empty() ? nullptr : &f.front();
}

bool PlanCloseUp(const CloseUpContext& ctx, const verify::Rule& rule,
                 std::optional<CloseUpPlan>& plan, std::string& error) {
  plan.reset();
  using verify::CloseUpFamily;
  const CloseUpFamily family = rule.CloseUp();
  const auto& s = rule.WorstSample();
  if (family == CloseUpFamily::kAfp) {
    // The worst finding's place on the part from above (close_up_afp.cpp), else the head.
    const verify::Finding* focus = FocusFinding(rule);
    if (focus != nullptr && focus->position_mm) {
      CloseUpPlan p;
      p.family = family;
      if (!close_up::PlanAfp(ctx, rule, *focus, p, error)) return false;
      plan = std::move(p);
      return true;
    }
  }
  if (family == CloseUpFamily::kNone || (!s && family != CloseUpFamily::kConstraint)) return true;
  CloseUpPlan p;
  p.family = family;
  p.joints =
      s ? close_up::PictureJoints(ctx, *s)
        : SolveStartPose(*ctx.ls, PathStartTool(*ctx.ls->scene, ctx.ls->scene->paths.front()))
              .joints;
  if (!close_up::PoseModel(*ctx.model, *ctx.data, p.joints, error)) return false;
  bool ok = false;
  if (family == CloseUpFamily::kCollision) {
    ok = close_up::PlanCollision(ctx, rule, *s, p);
  } else if (family == CloseUpFamily::kNeedle || family == CloseUpFamily::kStitch) {
    ok = close_up::PlanNeedles(ctx, rule, *s, p);
  } else if (family == CloseUpFamily::kKinematics) {
    ok = close_up::PlanKinematics(ctx, rule, *s, p);
  } else if (family == CloseUpFamily::kConstraint) {
    ok = close_up::PlanConstraint(ctx, rule, s ? &*s : nullptr, p);
  }
  // A family plan that finds nothing to frame falls back to the head at the sample.
  if (!ok && s) ok = close_up::PlanHead(ctx, *s, p);
  if (ok) plan = std::move(p);
  return true;
}

}  // namespace stitchsim::run
