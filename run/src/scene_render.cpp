// The scene render behind `stitchsim render` and the overview snapshot: the cell, the part
// and its paths (or point sets), the robot posed, rendered headless through OSMesa.
#include "stitchsim/run/scene_render.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "detail/close_up_draw.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/curve.h"
#include "stitchsim/render/scene_model.h"

namespace stitchsim::run {
namespace {

std::vector<render::Overlay> ScenePathOverlays(const scene::Scene& scene,
                                               const Eigen::Isometry3d& part_world_m,
                                               double radius_m) {
  // Each overlay geom costs the software renderer ~100 KB: all paths together get at most
  // kMaxPathSegments segments (one per 5 mm of a path, thinned to its share), and beyond
  // kMaxPathSegments / 2 paths an evenly spaced subset is drawn (at most ~3000 points).
  constexpr std::size_t kMaxPathSegments = 2000;
  const std::size_t count = scene.paths.size();
  const std::size_t stride =
      std::max<std::size_t>(1, (2 * count + kMaxPathSegments - 1) / kMaxPathSegments);
  const std::size_t drawn = (count + stride - 1) / stride;
  const int share = static_cast<int>(std::max<std::size_t>(1, kMaxPathSegments / drawn));
  std::vector<render::Overlay> out;
  for (std::size_t k = 0; k < count; k += stride) {
    const auto& path = scene.paths[k];
    geom::SurfacePath sp(*scene.surface, *path.curve);
    render::Overlay o;
    o.label = "path";
    o.radius_m = radius_m;
    const int n =
        std::clamp(static_cast<int>(std::min(sp.Length() / 5.0, 1e6)), std::min(16, share), share);
    for (int i = 0; i <= n; ++i) {
      const geom::PathPoint p = sp.AtArcLength(sp.Length() * i / n);
      // Drawn on top of the preform so it is not hidden inside it.
      const Eigen::Vector3d top = p.position + (scene.preform_thickness_mm + 0.5) * p.normal;
      o.points_m.push_back(part_world_m * (top / 1000.0));
    }
    out.push_back(std::move(o));
  }
  return out;
}

// Which part of the picture a segmented geom belongs to.
std::string PixelCoverageClass(const std::string& geom, const std::string& body) {
  if (geom.rfind("overlay:", 0) == 0) return geom.substr(8);
  if (geom == render::kMoldGeom) return "mold";
  if (geom == render::kPreformGeom) return "preform";
  if (geom.rfind(render::kConstraintGeomPrefix, 0) == 0) return "constraint";
  if (body == "head") return "head";
  if (body == "base_link" || body.rfind("link_", 0) == 0) return "robot";
  if (body == "carriage" || body == "rail") return "rail";
  if (body == "rotator" || body == "rotator_base") return "rotator";
  if (body == "table") return "table";
  return "other";
}

nlohmann::json PixelCoverageJson(const render::Segmentation& seg, const render::Image& img) {
  std::map<std::string, long> counts;
  for (int label : seg.label) {
    if (label < 0) {
      ++counts["background"];
      continue;
    }
    const auto i = static_cast<std::size_t>(label);
    ++counts[PixelCoverageClass(seg.names[i], seg.body_names[i])];
  }
  // Colour spread of the picture itself: a blank image has none.
  double mean = 0, sq = 0;
  for (auto v : img.rgb) {
    mean += v;
    sq += static_cast<double>(v) * v;
  }
  const double n = static_cast<double>(img.rgb.size());
  mean /= n;
  nlohmann::json j;
  j["width"] = seg.width;
  j["height"] = seg.height;
  j["pixels"] = counts;
  j["rgb_stddev"] = std::sqrt(std::max(0.0, sq / n - mean * mean));
  return j;
}

render::CameraView RenderFrameView(const std::vector<Eigen::Vector3d>& points_m, bool close_up) {
  Eigen::Vector3d lo = points_m.front(), hi = points_m.front();
  for (const auto& p : points_m) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  render::CameraView v;
  v.lookat_m = (lo + hi) / 2;
  const double radius = std::max(0.5 * (hi - lo).norm(), close_up ? 0.25 : 1.0);
  v.distance_m = radius / std::tan(DegToRad(20.0)) * (close_up ? 1.1 : 1.25);
  v.azimuth_deg = close_up ? 35.0 : 35.0;
  v.elevation_deg = close_up ? -28.0 : -22.0;
  return v;
}

// What to draw: the scene's paths, or the request's point sets instead; `radius_scale` gets
// each overlay's radius factor (-1: the set's own width, no view minimum).
std::vector<render::Overlay> RequestOverlays(const LoadedScene& ls, const RenderRequest& req,
                                             const Eigen::Isometry3d& part_world, bool close_up,
                                             std::vector<double>& radius_scale) {
  std::vector<render::Overlay> overlays;
  if (req.point_sets.empty()) {
    overlays = ScenePathOverlays(*ls.scene, part_world, close_up ? 0.0015 : 0.006);
  }
  radius_scale.assign(overlays.size(), 1.0);
  for (const auto& set : req.point_sets) {
    render::Overlay o;
    o.label = set.label;
    o.polyline = set.polyline;
    o.radius_m = close_up ? 0.0015 : 0.005;
    for (int i = 0; i < 4; ++i) o.rgba[i] = set.rgba[static_cast<std::size_t>(i)];
    for (const auto& p : set.points_part_mm) {
      // Stitch points sit on the mold surface, under the preform: draw them on its top.
      Eigen::Vector3d q = p;
      if (!set.polyline) {
        const geom::SurfaceProjection f = ls.scene->surface->Project(p);
        q = f.point + (ls.scene->preform_thickness_mm + 0.5) * f.normal;
      }
      o.points_m.push_back(part_world * (q / 1000.0));
    }
    for (const auto& n : set.normals_part) o.normals.push_back(part_world.linear() * n);
    // A set of its own width is kept at it (negative: no view minimum, see RenderScene).
    if (set.radius_mm > 0) o.radius_m = set.radius_mm / 1000.0;
    overlays.push_back(std::move(o));
    radius_scale.push_back(set.radius_mm > 0 ? -1.0 : set.radius_scale);
  }
  return overlays;
}

// The world points (m) the camera must frame for the requested view.
std::vector<Eigen::Vector3d> InterestPoints(const RenderRequest& req,
                                            const std::vector<render::Overlay>& overlays,
                                            const mjModel& model, const mjData& data,
                                            const Eigen::Isometry3d& part_world, bool close_up,
                                            bool part_view) {
  std::vector<Eigen::Vector3d> interest;
  if (close_up) {
    interest.push_back(req.tool_world_m.translation());
    interest.push_back(req.tool_world_m.translation() + Eigen::Vector3d(0, 0, 0.6));
    return interest;
  }
  for (const auto& o : overlays)
    interest.insert(interest.end(), o.points_m.begin(), o.points_m.end());
  if (part_view) {
    interest.push_back(req.tool_world_m.translation());
    return interest;
  }
  const int base = mj_name2id(&model, mjOBJ_BODY, "base_link");
  const int l3 = mj_name2id(&model, mjOBJ_BODY, "link_3");
  for (int b : {base, l3}) {
    interest.emplace_back(data.xpos[3 * b], data.xpos[3 * b + 1], data.xpos[3 * b + 2]);
  }
  // A stretch of the rail on either side of the carriage, so it reads as a rail.
  const Eigen::Vector3d carriage(data.xpos[3 * base], data.xpos[3 * base + 1], 0.0);
  interest.push_back(carriage - Eigen::Vector3d(1.5, 0, 0));
  interest.push_back(carriage + Eigen::Vector3d(1.5, 0, 0));
  interest.emplace_back(part_world.translation());
  return interest;
}

}  // namespace

Status RenderScene(const LoadedScene& ls, const RenderRequest& req, DiagnosticSink& sink) {
  render::MjModelPtr model = render::LoadSceneModel(*ls.scene, sink);
  if (sink.HasErrors() || !model) return Status::InSink();
  render::MjDataPtr data(mj_makeData(model.get()));
  std::string error;
  if (!close_up::PoseModel(*model, *data, req.joints, error)) {
    return Status::Error("model-missing-joint", error);
  }
  auto renderer = render::OffscreenRenderer::Create(model.get(), req.width, req.height, error);
  if (!renderer) return Status::Error("render-context", error);
  const Eigen::Isometry3d part_world = close_up::PartWorld(*model, *data);
  const bool close_up = req.view == "head";
  std::vector<double> radius_scale;
  std::vector<render::Overlay> overlays =
      RequestOverlays(ls, req, part_world, close_up, radius_scale);
  const bool part_view = req.view == "part";
  const std::vector<Eigen::Vector3d> interest =
      InterestPoints(req, overlays, *model, *data, part_world, close_up, part_view);
  render::CameraView view = RenderFrameView(interest, close_up);
  if (part_view) {
    // The stitches from above at a slant, close enough to tell them apart.
    Eigen::Vector3d lo = interest.front(), hi = interest.front();
    for (const auto& p : interest) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    view.lookat_m = 0.5 * (lo + hi);
    view.distance_m = std::max(0.5, 1.6 * 0.5 * (hi - lo).norm() / std::tan(DegToRad(20.0)));
    // From the far side of the part (the robot works from the rail side, -y).
    view.azimuth_deg = -60.0;
    view.elevation_deg = -55.0;
    // Laid tows on a standing skin (ribbons whose mean normal is within 45 deg of level):
    // from their side of the part, down that normal, from above and along the span past the arm.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (const auto& o : overlays) {
      for (const auto& n : o.normals) normal += n;
    }
    if (normal.norm() > 1e-9 && std::abs(normal.normalized().z()) < 0.7) {  // a standing skin
      const Eigen::Vector3d forward = -normal.normalized() + Eigen::Vector3d(1.0, 0.0, -0.9);
      const render::CameraView along = render::LookAlong(view.lookat_m, forward, view.distance_m);
      view.azimuth_deg = along.azimuth_deg;
      view.elevation_deg = along.elevation_deg;
    }
  }
  if (close_up) {
    // Look along the tool y axis (the stitch direction), low, so both needles and the
    // presser foot show side by side under the head.
    const Eigen::Vector3d y = req.tool_world_m.linear().col(1);
    view.lookat_m = req.tool_world_m.translation() + 0.03 * req.tool_world_m.linear().col(2);
    view.distance_m = 0.38;
    view.azimuth_deg = RadToDeg(std::atan2(y.y(), y.x())) + 20.0;
    view.elevation_deg = -12.0;
  }
  // Paths and stitches are drawn thick enough to see at the chosen distance.
  const double min_radius = view.distance_m * (close_up ? 0.0006 : (part_view ? 0.003 : 0.0012));
  for (std::size_t i = 0; i < overlays.size(); ++i) {
    if (radius_scale[i] < 0) continue;  // a width of its own (RequestOverlays)
    overlays[i].radius_m = std::max(overlays[i].radius_m, min_radius) * radius_scale[i];
  }
  render::Image img = renderer->Render(data.get(), view, overlays);
  if (req.decorate) req.decorate(img);
  if (std::string err = render::WritePng(req.output, img); !err.empty()) {
    return Status::Error("io-write", err);
  }
  if (!req.coverage_json.empty()) {
    const render::Segmentation seg = renderer->RenderSegmentation(data.get(), view, overlays);
    const std::string text = PixelCoverageJson(seg, img).dump(2) + "\n";
    if (std::string err = WriteFileAtomically(req.coverage_json, text); !err.empty()) {
      return Status::Error("io-write", err);
    }
  }
  return Status::Ok();
}

}  // namespace stitchsim::run
