// The AFP close-ups (run/close_up.h, family kAfp): the worst finding's place on the part seen
// from above its normal. The subject is the rule's own drawn points near it (afp.gap: the
// laying course's edge points with a gap, red; afp.overlap: amber) joined into lines, and the
// finding's point; around it the laid material the verifier drew (course edges and tow
// centres, blue); the head posed clear above. Overlays are drawn on the preform slab's top
// (the scene model's) and a fraction of a millimetre above it so its facets do not hide them.
#include <algorithm>
#include <cmath>

#include "detail/close_up_draw.h"
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

struct AfpLook {
  const char* drawn;  // the rule's DrawnPoints label ("" none)
  Rgba colour;
  const char* what;
};

AfpLook LookOf(const std::string& id) {
  if (id == "afp.gap") return {"afp_gap", kAfpGap, "gap"};
  if (id == "afp.overlap") return {"afp_overlap", kAfpOverlap, "overlap"};
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

// Each laying line's tow boundaries within kAfpHalfFrameMm of `at` (part frame, mm) as
// polylines on the preform top: the course's outer edges 0.35 mm thick, the others 0.12 mm.
void AddTowBoundaries(const verify::LaidMaterial& laid, const Eigen::Vector3d& at, double base_mm,
                      const geom::Surface& surface, const Eigen::Isometry3d& part,
                      CloseUpPlan& plan) {
  const float reach = static_cast<float>(kAfpHalfFrameMm + laid.tow_width_mm * laid.tows);
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

}  // namespace

bool PlanAfp(const CloseUpContext& ctx, const verify::Rule& rule, const verify::Finding& focus,
             CloseUpPlan& plan, std::string& error) {
  const geom::Surface& surface = *ctx.ls->scene->surface;
  // The model draws the preform as a slab on the surface: overlays go on its top.
  const double base_mm = ctx.ls->scene->preform_thickness_mm + kAfpLiftMm;
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
  const Eigen::Isometry3d part = PartWorld(*ctx.model, *ctx.data);
  const Eigen::Vector3d n = part.linear() * foot.normal;
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  plan.centre_m = part * (foot.point / 1000.0);
  plan.radius_m = kAfpHalfFrameMm / 1000.0;
  plan.directions = {-n, -n + 0.35 * t1, -n - 0.35 * t1, -n + 0.35 * t2, -n - 0.35 * t2};

  const AfpLook look = LookOf(rule.Summary().id);
  // The subject to scale where it is wider than kAfpThinnestMm (a gap or overlap: its width).
  const bool to_scale = focus.unit == "mm" && focus.value >= kAfpThinnestMm;
  const double radius_mm =
      focus.unit == "mm" ? std::clamp(0.5 * focus.value, 0.5 * kAfpThinnestMm, 3.0) : 1.0;
  ShotSubject subject{look.what, {}, {}};
  std::vector<std::vector<Eigen::Vector3d>> runs =
      Runs(DrawnNear(ctx.verifier, look.drawn, at, kAfpHalfFrameMm));
  runs.push_back({at});  // the finding's own point, always
  for (std::size_t k = 0; k < runs.size(); ++k) {
    std::vector<Eigen::Vector3d> world;
    for (const Eigen::Vector3d& p : runs[k]) {
      world.push_back(LiftedWorld(surface, part, p, base_mm + radius_mm));
    }
    const std::string label = "afp_subject_" + std::to_string(k);
    plan.overlays.push_back(
        MakeOverlay(label, look.colour, radius_mm / 1000.0, world, world.size() > 1));
    subject.overlays.push_back(label);
  }
  plan.subjects.push_back(subject);
  const std::string unit = focus.unit.empty() ? "" : " " + focus.unit;
  plan.legend.push_back(
      {render::ToRgb(look.colour),
       std::string(look.what) + " " + Fmt("%.3g", focus.value) + unit + " (limit " +
           Fmt("%.3g", focus.limit) + unit + "), " + focus.subject +
           (to_scale || focus.unit != "mm"
                ? ""
                : "; drawn " + Fmt("%.2g", kAfpThinnestMm) + " mm wide (enlarged)")});
  // The laid material around it: each line's tow boundaries near the finding (course edges
  // thicker), else the verifier's thinned course edge and centre points.
  const std::size_t before = plan.overlays.size();
  if (ctx.verifier != nullptr)
    AddTowBoundaries(ctx.verifier->Laid(), at, base_mm, surface, part, plan);
  if (plan.overlays.size() > before) {
    plan.legend.push_back(
        {render::ToRgb(kAfpLaid), "laid tows: course edges (thick), tow boundaries"});
  } else {
    std::vector<Eigen::Vector3d> laid;
    for (const Eigen::Vector3d& p : DrawnNear(ctx.verifier, "afp_laid", at, kAfpHalfFrameMm)) {
      laid.push_back(LiftedWorld(surface, part, p, base_mm));
    }
    if (!laid.empty()) {
      plan.overlays.push_back(MakeOverlay("afp_laid", kAfpLaid, 0.0004, laid, false));
      plan.legend.push_back({render::ToRgb(kAfpLaid), "laid tows: course edges and centres"});
    }
  }
  return true;
}

}  // namespace stitchsim::run::close_up
