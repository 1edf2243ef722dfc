// The AFP close-ups (run/close_up.h, family kAfp): the worst finding's place on the part seen
// from above its normal. The subject is the rule's own drawn points near it (afp.gap: the
// laying course's edge points with a gap, red; afp.overlap: amber) joined into lines, and the
// finding's point; afp.steering_radius: the steered tow's centre line over the window the
// rule measured and the circle through its three centres; afp.compaction: the roller's line
// across the tows at its height over the laid surface and its foot line below. Around it the
// laid material the verifier drew (course edges and tow boundaries, blue); the head posed
// clear above. Overlays are drawn on the preform slab's top
// (the scene model's) and a fraction of a millimetre above it so its facets do not hide them.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "detail/close_up_draw.h"
#include "stitchsim/common/units.h"
#include "stitchsim/run/start_pose.h"

namespace stitchsim::run::close_up {
namespace {

constexpr double kAfpHalfFrameMm = 25.0;  // the picture holds this radius round the finding
constexpr double kAfpLiftMm = 0.3;  // overlays this far above the preform top, plus their radius
constexpr double kAfpHeadClearMm = 300.0;  // the tool point this far above the finding
constexpr double kAfpJoinMm = 8.0;      // drawn points nearer each other than this join into a line
constexpr double kAfpThinnestMm = 0.8;  // subjects drawn at least this wide (enlarged)
constexpr Rgba kAfpGap = {0.95f, 0.05f, 0.05f, 1.0f};
constexpr Rgba kAfpOverlap = {1.0f, 0.65f, 0.0f, 1.0f};
constexpr Rgba kAfpOther = {0.9f, 0.0f, 0.9f, 1.0f};
constexpr Rgba kAfpLaid = {0.15f, 0.45f, 0.95f, 1.0f};
constexpr Rgba kAfpSteered = {0.95f, 0.1f, 0.6f, 1.0f};
constexpr Rgba kAfpArc = {0.1f, 0.1f, 0.1f, 1.0f};
constexpr Rgba kAfpRoller = {1.0f, 0.55f, 0.0f, 1.0f};
constexpr Rgba kAfpFoot = {0.1f, 0.7f, 0.2f, 1.0f};

struct AfpLook {
  const char* drawn;  // the rule's DrawnPoints label ("" none)
  Rgba colour;
  const char* what;
};

AfpLook LookOf(const std::string& id) {
  if (id == "afp.gap") return {"afp_gap", kAfpGap, "gap"};
  if (id == "afp.overlap") return {"afp_overlap", kAfpOverlap, "overlap"};
  if (id == "afp.steering_radius") return {"close_up:afp_steering", kAfpSteered, "steering radius"};
  if (id == "afp.compaction") return {"close_up:afp_roller", kAfpRoller, "roller"};
  if (id == "afp.fiber_angle") return {"close_up:afp_fiber", kAfpSteered, "fibre angle"};
  if (id == "afp.min_tow_length")
    return {"close_up:afp_short_piece", kAfpSteered, "short tow piece"};
  if (id == "afp.restart_distance") return {"close_up:afp_restart", kAfpSteered, "restart"};
  if (id == "afp.stagger") return {"close_up:afp_stagger", kAfpSteered, "seams"};
  return {"", kAfpOther, "finding"};
}

// A point of the part (mm) moved onto the surface and lifted along its normal, world (m).
Eigen::Vector3d LiftedWorld(const geom::Surface& surface, const Eigen::Isometry3d& part,
                            const Eigen::Vector3d& p_mm, double lift_mm) {
  const geom::SurfaceProjection f = surface.Project(p_mm);
  return part * ((f.point + lift_mm * f.normal) / 1000.0);
}

// The points labelled `label` that the verifier's rules draw, within `radius_mm` of `centre`
// (part frame, mm), in the order drawn.
std::vector<Eigen::Vector3d> DrawnNear(const verify::Verifier* v, const std::string& label,
                                       const Eigen::Vector3d& centre, double radius_mm) {
  std::vector<Eigen::Vector3d> out;
  if (v == nullptr || label.empty()) return out;
  for (const auto& rule : v->Rules()) {
    for (const verify::DrawnPoints& d : rule->Drawings()) {
      if (d.label != label) continue;
      for (const Eigen::Vector3d& p : d.points_mm) {
        if ((p - centre).norm() <= radius_mm) out.push_back(p);
      }
    }
  }
  return out;
}

// `points` (in order) cut into runs wherever two consecutive ones lie kAfpJoinMm apart or more.
std::vector<std::vector<Eigen::Vector3d>> Runs(const std::vector<Eigen::Vector3d>& points) {
  std::vector<std::vector<Eigen::Vector3d>> runs;
  for (const Eigen::Vector3d& p : points) {
    if (runs.empty() || (runs.back().back() - p).norm() >= kAfpJoinMm) runs.emplace_back();
    runs.back().push_back(p);
  }
  return runs;
}

// Each laying line's tow boundaries within `frame_mm` of `at` (part frame, mm) as
// polylines on the preform top: the course's outer edges 0.35 mm thick, the others 0.12 mm.
void AddTowBoundaries(const verify::LaidMaterial& laid, const Eigen::Vector3d& at, double frame_mm,
                      double base_mm, const geom::Surface& surface, const Eigen::Isometry3d& part,
                      CloseUpPlan& plan) {
  const float reach = static_cast<float>(frame_mm + laid.tow_width_mm * laid.tows);
  for (const verify::LaidStrip& s : laid.strips) {
    for (int b = 0; b <= laid.tows; ++b) {
      std::vector<Eigen::Vector3d> line;
      for (std::uint32_t j = 0; j < s.station_count; ++j) {
        const std::size_t i = s.first_station + j;
        const Eigen::Vector3f& q = laid.Boundary(i, b);
        if (!laid.stations[i].on_surface || !q.allFinite()) continue;
        if ((laid.stations[i].tool - at.cast<float>()).norm() > reach) continue;
        line.push_back(LiftedWorld(surface, part, q.cast<double>(), base_mm));
      }
      if (line.size() < 2) continue;
      const bool edge = b == 0 || b == laid.tows;
      plan.overlays.push_back(
          MakeOverlay("afp_laid", kAfpLaid, edge ? 0.00035 : 0.00012, std::move(line), true));
    }
  }
}

// Where a close-up looks: the part's pose, the preform top's lift, the finding's point.
struct AfpFrame {
  const geom::Surface* surface;
  Eigen::Isometry3d part;
  double base_mm;      // overlays on the preform top: this far along the normal, mm
  Eigen::Vector3d at;  // the finding's point, part frame, mm
  Eigen::Vector3d n;   // the surface normal there, world
};

// Adds the polyline `points` (part frame, mm; lifted by `lift_mm`) as a subject overlay.
void AddSubjectLine(const AfpFrame& f, const std::vector<Eigen::Vector3d>& points, double lift_mm,
                    const Rgba& colour, double radius_mm, ShotSubject& subject, CloseUpPlan& plan,
                    bool polyline = true) {
  std::vector<Eigen::Vector3d> world;
  for (const Eigen::Vector3d& p : points) {
    world.push_back(LiftedWorld(*f.surface, f.part, p, lift_mm));
  }
  const std::string label = "afp_subject_" + std::to_string(plan.overlays.size());
  plan.overlays.push_back(
      MakeOverlay(label, colour, radius_mm / 1000.0, world, polyline && world.size() > 1));
  subject.overlays.push_back(label);
}

// afp.gap / afp.overlap: the rule's drawn points near the finding joined into lines, and the
// finding's own point, at least kAfpThinnestMm wide.
void AddSeamSubject(const CloseUpContext& ctx, const AfpFrame& f, const AfpLook& look,
                    const verify::Finding& focus, ShotSubject& subject, CloseUpPlan& plan) {
  const bool to_scale = focus.unit == "mm" && focus.value >= kAfpThinnestMm;
  const double radius_mm =
      focus.unit == "mm" ? std::clamp(0.5 * focus.value, 0.5 * kAfpThinnestMm, 3.0) : 1.0;
  std::vector<std::vector<Eigen::Vector3d>> runs =
      Runs(DrawnNear(ctx.verifier, look.drawn, f.at, kAfpHalfFrameMm));
  runs.push_back({f.at});  // the finding's own point, always
  for (const auto& run : runs) {
    AddSubjectLine(f, run, f.base_mm + radius_mm, look.colour, radius_mm, subject, plan);
  }
  const std::string unit = focus.unit.empty() ? "" : " " + focus.unit;
  plan.legend.push_back(
      {render::ToRgb(look.colour),
       std::string(look.what) + " " + Fmt("%.3g", focus.value) + unit + " (limit " +
           Fmt("%.3g", focus.limit) + unit + "), " + focus.subject +
           (to_scale || focus.unit != "mm"
                ? ""
                : "; drawn " + Fmt("%.2g", kAfpThinnestMm) + " mm wide (enlarged)")});
}

// The circle through a, b, c (part frame, mm) from a through b to c, `n` points; the chord
// a-c when they are in line.
std::vector<Eigen::Vector3d> AfpArcThrough(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           const Eigen::Vector3d& c, int n) {
  const Eigen::Vector3d ab = b - a, ac = c - a, normal = ab.cross(ac);
  if (normal.squaredNorm() < 1e-12 * ab.squaredNorm() * ac.squaredNorm()) return {a, c};
  const Eigen::Vector3d centre =
      a + (ac.squaredNorm() * normal.cross(ab) + ab.squaredNorm() * ac.cross(normal)) /
              (2.0 * normal.squaredNorm());
  const Eigen::Vector3d e1 = a - centre, e2 = normal.normalized().cross(e1);
  double end = std::atan2((c - centre).dot(e2), (c - centre).dot(e1));
  if (end < 0) end += 2.0 * kPi;
  std::vector<Eigen::Vector3d> arc;
  for (int k = 0; k <= n; ++k) {
    const double t = end * k / n;
    arc.push_back(centre + std::cos(t) * e1 + std::sin(t) * e2);
  }
  return arc;
}

// Head tow `tow`'s centre line on every strip within `reach_mm` of `at` (part frame, mm).
std::vector<std::vector<Eigen::Vector3d>> AfpTowCentreLines(const verify::LaidMaterial& laid,
                                                            int tow, const Eigen::Vector3d& at,
                                                            double reach_mm) {
  std::vector<std::vector<Eigen::Vector3d>> lines;
  if (tow < 1 || tow > laid.tows) return lines;
  for (const verify::LaidStrip& s : laid.strips) {
    if (((s.tows >> (tow - 1)) & 1U) == 0) continue;
    std::vector<Eigen::Vector3d> line;
    for (std::uint32_t j = 0; j < s.station_count; ++j) {
      const std::size_t i = s.first_station + j;
      const Eigen::Vector3d c =
          (0.5f * (laid.Boundary(i, tow - 1) + laid.Boundary(i, tow))).cast<double>();
      if (laid.stations[i].on_surface && c.allFinite() && (c - at).norm() <= reach_mm) {
        line.push_back(c);
      }
    }
    if (line.size() >= 2) lines.push_back(std::move(line));
  }
  return lines;
}

// The head tow a finding names ("tow 5": 5; 0: none).
int AfpTowOf(const verify::Finding& focus) {
  return focus.subject.rfind("tow ", 0) == 0 ? std::atoi(focus.subject.c_str() + 4) : 0;
}

// afp.min_tow_length / afp.restart_distance / afp.stagger: the two points the rule names (the
// piece's add and cut; the tow's cut and re-add; the two plies' seam points) as dark dots and
// the stretch between them: the tow's laid centre line (`laid_between`), else the straight
// line; both thinner where the points are under 20 mm apart. `dots` says what the dots are.
bool AddSpanSubject(const CloseUpContext& ctx, const AfpFrame& f, const AfpLook& look,
                    const verify::Finding& focus, bool laid_between, const char* dots,
                    ShotSubject& subject, CloseUpPlan& plan) {
  const std::vector<Eigen::Vector3d> e = DrawnNear(ctx.verifier, look.drawn, f.at, 1000.0);
  if (e.size() != 2 || ctx.verifier == nullptr) return false;
  const double size = std::clamp((e[1] - e[0]).norm() / 20.0, 0.5, 1.0);
  const double half = 0.25 * ctx.verifier->Laid().tow_width_mm * (size < 1.0 ? 0.4 * size : 1.0);
  const double dot = 0.75 * 0.25 * ctx.verifier->Laid().tow_width_mm * size;
  const Eigen::Vector3d mid = 0.5 * (e[0] + e[1]);
  const double reach = 0.5 * (e[1] - e[0]).norm() + 0.5;
  bool drawn = false;
  if (laid_between) {
    for (const auto& line : AfpTowCentreLines(ctx.verifier->Laid(), AfpTowOf(focus), mid, reach)) {
      AddSubjectLine(f, line, f.base_mm + half, look.colour, half, subject, plan);
      drawn = true;
    }
  }
  if (!drawn) {
    std::vector<Eigen::Vector3d> stretch;
    for (int k = 0; k <= 16; ++k) stretch.push_back(e[0] + (e[1] - e[0]) * k / 16.0);
    AddSubjectLine(f, stretch, f.base_mm + half, look.colour, half, subject, plan);
  }
  for (const Eigen::Vector3d& p : e) {
    AddSubjectLine(f, {p}, f.base_mm + 2.0 * half + dot, kAfpArc, dot, subject, plan);
  }
  plan.legend.push_back({render::ToRgb(look.colour),
                         std::string(look.what) + " " + Fmt("%.4g", focus.value) + " mm (limit " +
                             Fmt("%.4g", focus.limit) + " mm), " + focus.subject});
  plan.legend.push_back({render::ToRgb(kAfpArc), dots});
  plan.centre_m = LiftedWorld(*f.surface, f.part, mid, 0.0);
  plan.radius_m = std::max(reach + 8.0, 10.0) / 1000.0;  // both points and 8 mm round them
  return true;
}

// An arrow on the surface from `tail` to `tip` (part mm) with a head 3 mm long: a polyline.
std::vector<Eigen::Vector3d> AfpArrow(const geom::Surface& surface, const Eigen::Vector3d& tail,
                                      const Eigen::Vector3d& tip) {
  const Eigen::Vector3d dir = (tip - tail).normalized();
  const Eigen::Vector3d side = surface.Project(tip).normal.cross(dir);
  const Eigen::Vector3d back = tip - 3.0 * dir;
  return {tail, tip, back + 1.5 * side, tip, back - 1.5 * side};
}

// afp.fiber_angle: the tow's centre line where it deviates most (half a tow wide), the laid
// direction (amber arrow) and the ply's design direction (dark arrow) from that point.
bool AddFibreSubject(const CloseUpContext& ctx, const AfpFrame& f, const AfpLook& look,
                     const verify::Finding& focus, ShotSubject& subject, CloseUpPlan& plan) {
  const std::vector<Eigen::Vector3d> d = DrawnNear(ctx.verifier, look.drawn, f.at, kAfpHalfFrameMm);
  if (d.size() != 3 || ctx.verifier == nullptr) return false;
  const double half = 0.25 * ctx.verifier->Laid().tow_width_mm;
  for (const auto& line : AfpTowCentreLines(ctx.verifier->Laid(), AfpTowOf(focus), d[0], 24.0)) {
    AddSubjectLine(f, line, f.base_mm + half, look.colour, half, subject, plan);
  }
  // Both from the point, 2.2 times as long as drawn: a wedge as wide as the angle.
  for (const auto& [tip, colour] : {std::pair{d[1], kAfpOverlap}, std::pair{d[2], kAfpArc}}) {
    AddSubjectLine(f, AfpArrow(*f.surface, d[0], d[0] + 2.2 * (tip - d[0])),
                   f.base_mm + 2.0 * half + 0.4, colour, 0.4, subject, plan);
  }
  plan.legend.push_back({render::ToRgb(look.colour), "fibre angle " + Fmt("%.3g", focus.value) +
                                                         " deg (limit " + Fmt("%.3g", focus.limit) +
                                                         " deg), " + focus.subject});
  plan.legend.push_back({render::ToRgb(kAfpOverlap), "the direction it is laid in"});
  plan.legend.push_back({render::ToRgb(kAfpArc), "the ply's design fibre direction"});
  return true;
}

// afp.steering_radius: the steered tow's centre line over the measured window (a quarter tow
// wide each side) and the circle through the window's three centres (thin, dark), with them.
bool AddSteeringSubject(const CloseUpContext& ctx, const AfpFrame& f, const AfpLook& look,
                        const verify::Finding& focus, ShotSubject& subject, CloseUpPlan& plan) {
  const std::vector<Eigen::Vector3d> w =
      DrawnNear(ctx.verifier, look.drawn, f.at, 3.0 * kAfpHalfFrameMm);
  if (w.size() != 3 || ctx.verifier == nullptr) return false;
  const verify::LaidMaterial& laid = ctx.verifier->Laid();
  const double half = 0.25 * laid.tow_width_mm;
  const int tow = AfpTowOf(focus);
  const double reach = std::max((w[0] - w[1]).norm(), (w[2] - w[1]).norm()) + 0.5;
  for (const auto& line : AfpTowCentreLines(laid, tow, w[1], reach)) {
    AddSubjectLine(f, line, f.base_mm + half, look.colour, half, subject, plan);
  }
  AddSubjectLine(f, AfpArcThrough(w[0], w[1], w[2], 32), f.base_mm + 2.0 * half + 0.2, kAfpArc, 0.2,
                 subject, plan);
  AddSubjectLine(f, w, f.base_mm + 2.0 * half + 0.8, kAfpArc, 0.8, subject, plan, false);
  plan.legend.push_back({render::ToRgb(look.colour), "steering radius " + Fmt("%.4g", focus.value) +
                                                         " mm (limit " + Fmt("%.4g", focus.limit) +
                                                         " mm), " + focus.subject});
  plan.legend.push_back({render::ToRgb(look.colour), "its centre line over the measured window"});
  plan.legend.push_back({render::ToRgb(kAfpArc), "the circle through 3 of its centres (dots), " +
                                                     Fmt("%.3g", (w[1] - w[0]).norm()) + " / " +
                                                     Fmt("%.3g", (w[2] - w[1]).norm()) +
                                                     " mm apart"});
  plan.radius_m = std::max(plan.radius_m, (reach + 5.0) / 1000.0);
  return true;
}

// afp.compaction: the roller across the tows at its measured height over the tool surface
// (the rule's drawing: its k + 1 points over the tow boundaries, then its foot's k + 1 on the
// laid surface), seen along the travel so the lift shows.
bool AddRollerSubject(const CloseUpContext& ctx, const AfpFrame& f, const AfpLook& look,
                      const verify::Finding& focus, ShotSubject& subject, CloseUpPlan& plan) {
  const std::vector<Eigen::Vector3d> r = DrawnNear(ctx.verifier, look.drawn, f.at, 500.0);
  if (r.size() < 4 || r.size() % 2 != 0) return false;
  const std::size_t k1 = r.size() / 2;
  // On the preform top as every overlay: each point raised by base_mm (+ the tube's radius).
  auto raised = [&](std::size_t from, double radius_mm) {
    std::vector<Eigen::Vector3d> world;
    for (std::size_t i = from; i < from + k1; ++i) {
      world.push_back(
          f.part * ((r[i] + (f.base_mm + radius_mm) * f.surface->Project(r[i]).normal) / 1000.0));
    }
    return world;
  };
  const std::string roller = "afp_subject_" + std::to_string(plan.overlays.size());
  plan.overlays.push_back(MakeOverlay(roller, look.colour, 0.001, raised(0, 1.0), true));
  const std::string foot = "afp_subject_" + std::to_string(plan.overlays.size());
  plan.overlays.push_back(MakeOverlay(foot, kAfpFoot, 0.0004, raised(k1, 0.4), true));
  subject.overlays.insert(subject.overlays.end(), {roller, foot});
  const std::string unit = focus.unit.empty() ? "" : " " + focus.unit;
  plan.legend.push_back(
      {render::ToRgb(look.colour), "roller: " + focus.subject + " " + Fmt("%.4g", focus.value) +
                                       unit + " (limit " + Fmt("%.4g", focus.limit) + unit + ")"});
  // Its height over its foot at the middle (the tool point), as drawn.
  const double over = (r[k1 / 2] - r[k1 + k1 / 2]).norm();
  plan.legend.push_back({render::ToRgb(look.colour),
                         "roller " + Fmt("%.3g", over) + " mm over its foot at the tool point"});
  plan.legend.push_back({render::ToRgb(kAfpFoot), "its foot on the laid surface"});
  const Eigen::Vector3d across = f.part.linear() * (r[k1 - 1] - r[0]).normalized();
  const Eigen::Vector3d travel = f.n.cross(across);
  plan.radius_m = std::max(plan.radius_m, (0.5 * (r[k1 - 1] - r[0]).norm() + 8.0) / 1000.0);
  plan.directions = {-0.4 * f.n + travel, -0.4 * f.n - travel, -f.n + 0.8 * travel,
                     -f.n - 0.8 * travel, -f.n};
  return true;
}

}  // namespace

bool PlanAfp(const CloseUpContext& ctx, const verify::Rule& rule, const verify::Finding& focus,
             CloseUpPlan& plan, std::string& error) {
  const geom::Surface& surface = *ctx.ls->scene->surface;
  const Eigen::Vector3d at((*focus.position_mm)[0], (*focus.position_mm)[1],
                           (*focus.position_mm)[2]);
  const geom::SurfaceProjection foot = surface.Project(at);
  // The head clear above the finding, its axis on the normal (a laying pose lifted).
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d z = foot.normal, x = z.unitOrthogonal();
  tool.linear() << x, z.cross(x), z;
  tool.translation() = foot.point + kAfpHeadClearMm * z;
  plan.joints = SolveStartPose(*ctx.ls, tool).joints;
  if (!PoseModel(*ctx.model, *ctx.data, plan.joints, error)) return false;
  // The model draws the preform as a slab on the surface: overlays go on its top.
  const Eigen::Isometry3d part = PartWorld(*ctx.model, *ctx.data);
  const AfpFrame f{&surface, part, ctx.ls->scene->preform_thickness_mm + kAfpLiftMm, at,
                   part.linear() * foot.normal};
  const Eigen::Vector3d t1 = f.n.unitOrthogonal(), t2 = f.n.cross(t1);
  plan.centre_m = f.part * (foot.point / 1000.0);
  plan.radius_m = kAfpHalfFrameMm / 1000.0;
  plan.directions = {-f.n, -f.n + 0.35 * t1, -f.n - 0.35 * t1, -f.n + 0.35 * t2, -f.n - 0.35 * t2};

  const std::string id = rule.Summary().id;
  const AfpLook look = LookOf(id);
  ShotSubject subject{look.what, {}, {}};
  const bool drawn =
      (id == "afp.steering_radius" && AddSteeringSubject(ctx, f, look, focus, subject, plan)) ||
      (id == "afp.compaction" && AddRollerSubject(ctx, f, look, focus, subject, plan)) ||
      (id == "afp.fiber_angle" && AddFibreSubject(ctx, f, look, focus, subject, plan)) ||
      (id == "afp.min_tow_length" &&
       AddSpanSubject(ctx, f, look, focus, true, "its add and its cut (dots), laid between",
                      subject, plan)) ||
      (id == "afp.restart_distance" &&
       AddSpanSubject(ctx, f, look, focus, false, "its cut and its re-add (dots), bare between",
                      subject, plan)) ||
      (id == "afp.stagger" &&
       AddSpanSubject(ctx, f, look, focus, false, "its seam and the nearest of a ply below (dots)",
                      subject, plan));
  if (!drawn) AddSeamSubject(ctx, f, look, focus, subject, plan);
  plan.subjects.push_back(subject);
  // The laid material around it: each line's tow boundaries near the finding (course edges
  // thicker), else the verifier's thinned course edge and centre points.
  const std::size_t before = plan.overlays.size();
  const double reach_mm = 1000.0 * plan.radius_m;
  if (ctx.verifier != nullptr)
    AddTowBoundaries(ctx.verifier->Laid(), at, reach_mm, f.base_mm, surface, f.part, plan);
  if (plan.overlays.size() > before) {
    plan.legend.push_back(
        {render::ToRgb(kAfpLaid), "laid tows: course edges (thick), tow boundaries"});
  } else {
    std::vector<Eigen::Vector3d> laid;
    for (const Eigen::Vector3d& p : DrawnNear(ctx.verifier, "afp_laid", at, reach_mm)) {
      laid.push_back(LiftedWorld(surface, f.part, p, f.base_mm));
    }
    if (!laid.empty()) {
      plan.overlays.push_back(MakeOverlay("afp_laid", kAfpLaid, 0.0004, laid, false));
      plan.legend.push_back({render::ToRgb(kAfpLaid), "laid tows: course edges and centres"});
    }
  }
  return true;
}

}  // namespace stitchsim::run::close_up
