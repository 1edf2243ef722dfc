// The camera work of a close-up (run/close_up.h): the direction that shows the subjects
// largest and least hidden, then whatever still hides them made see-through; and the posing
// and drawing helpers the planners share (detail/close_up_draw.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "detail/close_up_draw.h"
#include "stitchsim/common/units.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::run {
namespace {

// Probe pictures are small: only proportions matter when comparing directions.
constexpr int kProbeWidth = 256;
constexpr int kProbeHeight = 192;

// What a segmented pixel shows, for a plan: subject index, or one of these.
constexpr int kBackground = -1;
constexpr int kOtherGeom = -2;   ///< a model geom of no subject: it may hide a subject
constexpr int kOtherThing = -3;  ///< an overlay or decoration of no subject

std::vector<int> SlotSubjects(const render::Segmentation& seg, const CloseUpPlan& plan) {
  std::vector<int> out(seg.names.size(), kOtherThing);
  for (std::size_t slot = 0; slot < seg.names.size(); ++slot) {
    const int g = seg.geoms[slot];
    const bool overlay = seg.names[slot].rfind("overlay:", 0) == 0;
    const std::string label = overlay ? seg.names[slot].substr(8) : std::string();
    if (g >= 0) out[slot] = kOtherGeom;
    for (std::size_t i = 0; i < plan.subjects.size(); ++i) {
      const ShotSubject& s = plan.subjects[i];
      const bool hit = g >= 0 ? std::find(s.geoms.begin(), s.geoms.end(), g) != s.geoms.end()
                              : overlay && std::find(s.overlays.begin(), s.overlays.end(), label) !=
                                               s.overlays.end();
      if (hit) {
        out[slot] = static_cast<int>(i);
        break;
      }
    }
  }
  return out;
}

// Per pixel: the subject index or a kBackground / kOtherGeom / kOtherThing class.
std::vector<int> ClassifyPixels(const render::Segmentation& seg, const CloseUpPlan& plan) {
  const std::vector<int> slots = SlotSubjects(seg, plan);
  std::vector<int> out(seg.label.size(), kBackground);
  for (std::size_t p = 0; p < seg.label.size(); ++p) {
    if (seg.label[p] >= 0) out[p] = slots[static_cast<std::size_t>(seg.label[p])];
  }
  return out;
}

// The plan's style with everything but subject `i` left out (the subject "alone").
render::DrawStyle AloneStyle(const mjModel& model, const CloseUpPlan& plan, std::size_t i) {
  const ShotSubject& subject = plan.subjects[i];
  render::DrawStyle style = plan.style;
  for (int g = 0; g < model.ngeom; ++g) {
    if (std::find(subject.geoms.begin(), subject.geoms.end(), g) == subject.geoms.end()) {
      style.hidden.push_back(g);
    }
  }
  for (const render::Overlay& o : plan.overlays) {
    if (std::find(subject.overlays.begin(), subject.overlays.end(), o.label) ==
        subject.overlays.end()) {
      style.unsegmented_overlays.push_back(o.label);
    }
  }
  return style;
}

// How one view shows the subjects: per subject, the pixels it covers drawn alone and those
// where it is the nearest thing; the pixels of the subjects' silhouettes other geoms cover
// (by geom). The subjects are drawn see-through, so one subject in front of another does not
// count as hiding it.
struct ViewCount {
  std::vector<long> alone, visible, hidden_each;
  long silhouette = 0;
  std::map<int, long> hiders;  ///< geom id -> silhouette pixels it covers
  long hidden = 0;
};

ViewCount CountView(render::OffscreenRenderer& r, mjData* data, const mjModel& model,
                    const CloseUpPlan& plan, const render::CameraView& view,
                    const render::DrawStyle& style) {
  ViewCount c;
  const std::size_t n = plan.subjects.size();
  c.alone.assign(n, 0);
  c.visible.assign(n, 0);
  c.hidden_each.assign(n, 0);
  const render::Segmentation full = r.RenderSegmentation(data, view, plan.overlays, style);
  const std::vector<int> full_class = ClassifyPixels(full, plan);
  for (std::size_t i = 0; i < n; ++i) {
    const render::Segmentation solo =
        r.RenderSegmentation(data, view, plan.overlays, AloneStyle(model, plan, i));
    for (std::size_t p = 0; p < solo.label.size(); ++p) {
      if (solo.label[p] < 0) continue;
      ++c.alone[i];
      ++c.silhouette;
      if (full_class[p] == kOtherGeom) {
        ++c.hidden;
        ++c.hidden_each[i];
        ++c.hiders[full.geoms[static_cast<std::size_t>(full.label[p])]];
      }
    }
  }
  for (int k : full_class) {
    if (k >= 0) ++c.visible[static_cast<std::size_t>(k)];
  }
  return c;
}

// Larger subjects (the smallest counts) and fewer of their pixels hidden score higher; a
// subject behind another one (drawn see-through) counts at a third.
double ViewScore(const ViewCount& c) {
  if (c.alone.empty()) return 0.0;
  double smallest = 1e18;
  for (std::size_t i = 0; i < c.alone.size(); ++i) {
    const long behind = std::max(0L, c.alone[i] - c.visible[i] - c.hidden_each[i]);
    smallest = std::min(smallest, static_cast<double>(c.visible[i]) + behind / 3.0);
  }
  const double hidden = c.silhouette > 0 ? static_cast<double>(c.hidden) / c.silhouette : 1.0;
  return smallest * (1.0 - 0.8 * hidden);
}

double FrameDistance(const mjModel& model, double radius_m) {
  const double half_fovy = 0.5 * model.vis.global.fovy * kPi / 180.0;
  return radius_m / std::tan(half_fovy) * 1.05;
}

}  // namespace

namespace close_up {

bool PoseModel(const mjModel& model, mjData& data, const trace::JointVector& joints,
               std::string& error) {
  for (int j = 0; j < trace::kNumJoints; ++j) {
    const std::string name(sim::kJointNames[static_cast<std::size_t>(j)]);
    const int id = mj_name2id(&model, mjOBJ_JOINT, name.c_str());
    if (id < 0) {
      error = "MuJoCo model lacks joint " + name;
      return false;
    }
    data.qpos[model.jnt_qposadr[id]] = joints[j];
  }
  mj_kinematics(&model, &data);
  return true;
}

Eigen::Isometry3d PartWorld(const mjModel& model, const mjData& data) {
  const int b = mj_name2id(&model, mjOBJ_BODY, "part");
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  if (b < 0) return t;
  for (int r = 0; r < 3; ++r) {
    t.translation()[r] = data.xpos[3 * b + r];
    for (int c = 0; c < 3; ++c) t.linear()(r, c) = data.xmat[9 * b + 3 * r + c];
  }
  return t;
}

Eigen::Vector3d GeomCentre(const mjData& data, int geom) {
  return {data.geom_xpos[3 * geom], data.geom_xpos[3 * geom + 1], data.geom_xpos[3 * geom + 2]};
}

render::Overlay MakeOverlay(const std::string& label, const Rgba& rgba, double radius_m,
                            std::vector<Eigen::Vector3d> points_m, bool polyline) {
  render::Overlay o;
  o.label = label;
  for (int c = 0; c < 4; ++c) o.rgba[c] = rgba[static_cast<std::size_t>(c)];
  o.radius_m = radius_m;
  o.points_m = std::move(points_m);
  o.polyline = polyline;
  return o;
}

void Recolour(CloseUpPlan& plan, const std::vector<int>& geoms, const Rgba& rgba) {
  for (int g : geoms) plan.style.colours.push_back({g, rgba});
}

std::vector<Eigen::Vector3d> Ring(int azimuths, std::initializer_list<double> elevations_deg) {
  std::vector<Eigen::Vector3d> out;
  for (double el : elevations_deg) {
    for (int k = 0; k < azimuths; ++k) {
      const double az = 2 * kPi * k / azimuths, e = el * kPi / 180.0;
      out.emplace_back(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e));
    }
  }
  return out;
}

std::string Fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

}  // namespace close_up

bool ShootCloseUp(mjModel* model, mjData* data, const CloseUpPlan& plan, int width, int height,
                  Shot& shot, std::string& error) {
  const double distance = FrameDistance(*model, plan.radius_m);
  std::vector<Eigen::Vector3d> directions = plan.directions;
  if (directions.empty()) directions.emplace_back(1.0, 1.0, -0.7);
  render::CameraView best = render::LookAlong(plan.centre_m, directions.front(), distance);
  if (directions.size() > 1) {
    auto probe = render::OffscreenRenderer::Create(model, kProbeWidth, kProbeHeight, error);
    if (!probe) return false;
    double best_score = -1.0;
    for (std::size_t i = 0; i < directions.size(); ++i) {
      const render::CameraView v = render::LookAlong(plan.centre_m, directions[i], distance);
      // Earlier directions are preferred on a near tie.
      const double score = ViewScore(CountView(*probe, data, *model, plan, v, plan.style)) *
                           (1.0 - 0.03 * static_cast<double>(i));
      if (score > best_score) {
        best_score = score;
        best = v;
      }
    }
  }
  auto r = render::OffscreenRenderer::Create(model, width, height, error);
  if (!r) return false;
  render::DrawStyle style = plan.style;
  ViewCount count;
  // More than one round: a geom behind one made see-through may hide the subjects in turn.
  for (int round = 0;; ++round) {
    count = CountView(*r, data, *model, plan, best, style);
    if (round == 3) break;
    const long enough = std::max(4L, count.silhouette / 500);
    bool changed = false;
    for (const auto& [geom, pixels] : count.hiders) {
      if (pixels < enough || geom < 0) continue;
      style.transparent.push_back(geom);
      const char* n = mj_id2name(model, mjOBJ_GEOM, geom);
      shot.see_through.emplace_back(n != nullptr ? n : "geom " + std::to_string(geom));
      changed = true;
    }
    if (!changed) break;
  }
  shot.view = best;
  shot.pixels.clear();
  for (std::size_t i = 0; i < plan.subjects.size(); ++i) {
    shot.pixels.push_back(
        {plan.subjects[i].name, count.visible[i], count.alone[i], count.hidden_each[i]});
  }
  shot.transparent = style.transparent;
  shot.image = r->Render(data, best, plan.overlays, style);
  return true;
}

}  // namespace stitchsim::run
