// The close-ups of the arm (kin.*, dyn.*), of constraint crossings and of the head (afp.*).
#include <algorithm>
#include <cmath>

#include "detail/close_up_draw.h"
#include "stitchsim/render/scene_model.h"

namespace stitchsim::run::close_up {
namespace {

using namespace colours;  // NOLINT: the palette

Eigen::Vector3d BodyPos(const mjData& d, int body) {
  return {d.xpos[3 * body], d.xpos[3 * body + 1], d.xpos[3 * body + 2]};
}

// The model joint a finding's subject names: a joint ("a5", "rail_x"), or a singular pose's
// joint ("wrist": a5, "shoulder": a2, "elbow": a3); -1 for none ("arm", "tool").
int SubjectJoint(const mjModel& m, const std::string& subject) {
  const int id = mj_name2id(&m, mjOBJ_JOINT, subject.c_str());
  if (id >= 0) return id;
  if (subject == "wrist") return mj_name2id(&m, mjOBJ_JOINT, "a5");
  if (subject == "shoulder") return mj_name2id(&m, mjOBJ_JOINT, "a2");
  if (subject == "elbow") return mj_name2id(&m, mjOBJ_JOINT, "a3");
  return -1;
}

// The camera's sphere around a set of world points: centre and radius (at least `min_m`).
void Frame(const std::vector<Eigen::Vector3d>& points, double min_m, CloseUpPlan& plan) {
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  plan.centre_m = 0.5 * (lo + hi);
  plan.radius_m = std::max(min_m, 0.45 * (hi - lo).norm());
}

// The tool point of a sample in the world (m), the model posed at the sample.
Eigen::Vector3d ToolPoint(const CloseUpContext& ctx, const trace::TraceSample& s) {
  return PartWorld(*ctx.model, *ctx.data) * (s.tool_part.translation() / 1000.0);
}

}  // namespace

bool PlanKinematics(const CloseUpContext& ctx, const verify::Rule& rule,
                    const trace::TraceSample& s, CloseUpPlan& plan) {
  const mjModel& m = *ctx.model;
  const mjData& d = *ctx.data;
  const verify::Finding* f = FocusFinding(rule);
  const int joint = f != nullptr ? SubjectJoint(m, f->subject) : -1;
  std::vector<Eigen::Vector3d> points;
  for (const char* b : {"base_link", "link_2", "link_3", "link_5", "flange"}) {
    const int id = mj_name2id(&m, mjOBJ_BODY, b);
    if (id >= 0) points.push_back(BodyPos(d, id));
  }
  const Eigen::Vector3d tool = ToolPoint(ctx, s);
  points.push_back(tool);
  Frame(points, 0.6, plan);
  plan.directions = Ring(8, {-20.0, -45.0});
  plan.style.others = kGrey;
  plan.overlays.push_back(MakeOverlay("tool", kMarker, 0.02, {tool}, false));
  if (joint >= 0) {
    const int body = m.jnt_bodyid[joint];
    const std::vector<int> link = render::GeomsOfBody(m, body);
    const char* jn = mj_id2name(&m, mjOBJ_JOINT, joint);
    const char* bn = mj_id2name(&m, mjOBJ_BODY, body);
    const std::string jname = jn != nullptr ? jn : "?", bname = bn != nullptr ? bn : "?";
    Recolour(plan, link, kHighlight);
    plan.subjects.push_back({bname, link, {}});
    plan.legend.push_back({render::ToRgb(kHighlight), bname + " (moved by joint " + jname + ")"});
    const Eigen::Vector3d anchor(d.xanchor[3 * joint], d.xanchor[3 * joint + 1],
                                 d.xanchor[3 * joint + 2]);
    const Eigen::Vector3d axis(d.xaxis[3 * joint], d.xaxis[3 * joint + 1], d.xaxis[3 * joint + 2]);
    const double half = 0.35 * plan.radius_m;
    render::Overlay a =
        MakeOverlay("joint_axis", kAxis, 0.012, {anchor - half * axis, anchor + half * axis}, true);
    a.arrow_head = true;
    plan.overlays.push_back(std::move(a));
    plan.legend.push_back({render::ToRgb(kAxis), jname + " axis"});
  } else {  // no joint named: the head, where the tool point is
    const std::vector<int> head = render::GeomsOfBody(m, mj_name2id(&m, mjOBJ_BODY, "head"));
    Recolour(plan, head, kHighlight);
    plan.subjects.push_back({"head", head, {}});
    plan.legend.push_back({render::ToRgb(kHighlight), "head"});
  }
  plan.legend.push_back({render::ToRgb(kMarker), "tool point"});
  plan.legend.push_back({render::ToRgb(kGrey), "rest of the cell"});
  return !plan.subjects.front().geoms.empty();
}

bool PlanConstraint(const CloseUpContext& ctx, const verify::Rule& rule,
                    const trace::TraceSample* s, CloseUpPlan& plan) {
  const mjModel& m = *ctx.model;
  const verify::Finding* f = FocusFinding(rule);
  std::vector<int> geoms;
  if (f != nullptr) geoms = render::GeomsOfCollisionBody(m, "constraint:" + f->subject);
  if (geoms.empty()) return false;
  const Eigen::Isometry3d part = PartWorld(m, *ctx.data);
  // Where the crossing is: the stitch's tool point, else the constraint's centre.
  Eigen::Vector3d at = GeomCentre(*ctx.data, geoms.front());
  Eigen::Vector3d normal = part.linear() * Eigen::Vector3d::UnitZ();
  // Every kept finding on this constraint with a place (tool point, part frame), on the
  // preform's top.
  auto on_top = [&](const Eigen::Vector3d& p_mm) {
    const geom::SurfaceProjection p = ctx.ls->scene->surface->Project(p_mm);
    return part * ((p.point + (ctx.ls->scene->preform_thickness_mm + 0.5) * p.normal) / 1000.0);
  };
  std::vector<Eigen::Vector3d> marks;
  for (const verify::Finding& x : rule.Summary().findings) {
    if (x.subject == f->subject && x.position_mm) {
      marks.push_back(
          on_top(Eigen::Vector3d((*x.position_mm)[0], (*x.position_mm)[1], (*x.position_mm)[2])));
    }
  }
  if (s != nullptr) {
    const geom::SurfaceProjection p = ctx.ls->scene->surface->Project(s->tool_part.translation());
    at = on_top(s->tool_part.translation());
    normal = part.linear() * p.normal;
    marks.push_back(at);
  } else if (f->position_mm) {
    at = on_top(Eigen::Vector3d((*f->position_mm)[0], (*f->position_mm)[1], (*f->position_mm)[2]));
  }
  plan.centre_m = at;
  plan.radius_m = 0.15;
  // From above the stitch, looking down its normal (and a little off it, if that is hidden).
  const Eigen::Vector3d side = normal.unitOrthogonal(), side2 = normal.cross(side);
  plan.directions = {-normal, -normal + 0.35 * side, -normal - 0.35 * side, -normal + 0.35 * side2,
                     -normal - 0.35 * side2};
  Recolour(plan, geoms, kHighlight);
  plan.subjects.push_back({"constraint:" + f->subject, geoms, {}});
  plan.legend.push_back({render::ToRgb(kHighlight), "constraint " + f->subject});
  // The seam's other stitches around it, so the crossing reads as a place on the seam.
  std::vector<Eigen::Vector3d> around;
  if (ctx.stitches != nullptr) {
    for (const verify::StitchMark& st : *ctx.stitches) {
      const Eigen::Vector3d w = on_top(st.position_mm.cast<double>());
      if (st.line > 0 && (w - at).norm() < plan.radius_m) around.push_back(w);
    }
  }
  if (!around.empty()) {
    plan.overlays.push_back(MakeOverlay("stitch", kAxis, 0.003, around, false));
    plan.style.unsegmented_overlays.push_back("stitch");
    plan.legend.push_back({render::ToRgb(kAxis), "stitches of the programme"});
  }
  if (!marks.empty()) {
    plan.overlays.push_back(MakeOverlay("crossing", kDrift, 0.008, marks, false));
    plan.subjects.push_back({"crossing stitches", {}, {"crossing"}});
    plan.legend.push_back({render::ToRgb(kDrift), "stitches crossing the constraint"});
  }
  return true;
}

bool PlanHead(const CloseUpContext& ctx, const trace::TraceSample& s, CloseUpPlan& plan) {
  const mjModel& m = *ctx.model;
  const Eigen::Isometry3d tool = PartWorld(m, *ctx.data) * ToMetres(s.tool_part);
  plan.centre_m = tool * Eigen::Vector3d(0, 0, 0.05);
  plan.radius_m = 0.25;
  const Eigen::Vector3d x = tool.linear().col(0), y = tool.linear().col(1),
                        z = tool.linear().col(2);
  // From the side of the tool frame (the roller's axis is x), a little from above.
  plan.directions = {-x - 0.4 * z,          x - 0.4 * z, -x + 0.5 * y - 0.4 * z,
                     x - 0.5 * y - 0.4 * z, y - 0.6 * z, -y - 0.6 * z};
  std::vector<int> subject = render::GeomsOfCollisionBody(m, "head:roller");
  const char* what = "roller";
  if (subject.empty()) {
    subject = render::GeomsOfCollisionBody(m, "head:presser_foot");
    what = "presser foot";
  }
  if (!subject.empty()) {
    Recolour(plan, subject, kHighlight);
    plan.subjects.push_back({what, subject, {}});
    plan.legend.push_back({render::ToRgb(kHighlight), what});
  }
  plan.overlays.push_back(MakeOverlay("tool", kMarker, 0.006, {tool.translation()}, false));
  plan.subjects.push_back({"tool point", {}, {"tool"}});
  plan.legend.push_back({render::ToRgb(kMarker), "tool point at the finding"});
  return true;
}

}  // namespace stitchsim::run::close_up
