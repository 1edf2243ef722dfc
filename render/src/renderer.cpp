#include "stitchsim/render/renderer.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "stitchsim/common/units.h"
#include "stitchsim/render/scene_model.h"

namespace stitchsim::render {

struct OffscreenRenderer::Impl {
  mjModel* model = nullptr;
  OSMesaContext gl = nullptr;
  std::vector<unsigned char> framebuffer;  // RGBA, owned by OSMesa while current
  int width = 0;
  int height = 0;
  mjrContext con;
  mjvScene scn;
  mjvOption opt;
  mjvCamera cam;
  bool have_con = false;
  bool have_scn = false;
  // Overlay labels of the user geoms appended in the last Draw (index = geom slot).
  std::vector<std::string> overlay_labels;
  int model_geom_count = 0;
};

std::unique_ptr<OffscreenRenderer> OffscreenRenderer::Create(mjModel* model, int width, int height,
                                                             std::string& error) {
  if (width < 16 || height < 16 || width > 8192 || height > 8192) {
    error = "image size must be between 16 and 8192 pixels";
    return nullptr;
  }
  std::unique_ptr<OffscreenRenderer> r(new OffscreenRenderer());
  r->impl_ = std::make_unique<Impl>();
  Impl& im = *r->impl_;
  im.model = model;
  im.width = width;
  im.height = height;
  im.gl = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (im.gl == nullptr) {
    error = "OSMesaCreateContextExt failed";
    return nullptr;
  }
  im.framebuffer.assign(static_cast<std::size_t>(width) * height * 4, 0);
  if (!OSMesaMakeCurrent(im.gl, im.framebuffer.data(), GL_UNSIGNED_BYTE, width, height)) {
    error = "OSMesaMakeCurrent failed";
    return nullptr;
  }
  model->vis.global.offwidth = width;
  model->vis.global.offheight = height;
  mjv_defaultOption(&im.opt);
  im.opt.geomgroup[kHiddenGeomGroup] = 0;  // omitted cell fixtures
  mjv_defaultCamera(&im.cam);
  mjv_defaultScene(&im.scn);
  mjv_makeScene(model, &im.scn, 20000);
  im.have_scn = true;
  mjr_defaultContext(&im.con);
  mjr_makeContext(model, &im.con, mjFONTSCALE_100);
  im.have_con = true;
  mjr_setBuffer(mjFB_OFFSCREEN, &im.con);
  if (im.con.currentBuffer != mjFB_OFFSCREEN) {
    error = "MuJoCo could not use its offscreen buffer under OSMesa";
    return nullptr;
  }
  return r;
}

OffscreenRenderer::~OffscreenRenderer() {
  if (!impl_) return;
  if (impl_->have_con) mjr_freeContext(&impl_->con);
  if (impl_->have_scn) mjv_freeScene(&impl_->scn);
  if (impl_->gl != nullptr) OSMesaDestroyContext(impl_->gl);
}

namespace {

bool Contains(const std::vector<int>& v, int x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

}  // namespace

// Recolours, makes see-through or drops the model's geoms (dropped: hidden ones; when
// segmenting, the see-through ones too). Segmentation ids follow the compacted slots.
void OffscreenRenderer::ApplyStyle(const DrawStyle& style, bool segment) {
  Impl& im = *impl_;
  int kept = 0;
  for (int i = 0; i < im.scn.ngeom; ++i) {
    mjvGeom g = im.scn.geoms[i];
    if (g.objtype == mjOBJ_GEOM) {
      const bool clear = Contains(style.transparent, g.objid);
      if (Contains(style.hidden, g.objid) || (segment && clear)) continue;
      const auto colour = std::find_if(style.colours.begin(), style.colours.end(),
                                       [&](const GeomColour& c) { return c.geom == g.objid; });
      if (colour != style.colours.end()) {
        for (int c = 0; c < 4; ++c) g.rgba[c] = colour->rgba[static_cast<std::size_t>(c)];
        // See-through, but still segmented (opaque there: drawn in depth order).
        g.transparent = !segment && g.rgba[3] < 1.0f ? 1 : 0;
      } else if (style.others) {
        for (int c = 0; c < 4; ++c) g.rgba[c] = (*style.others)[static_cast<std::size_t>(c)];
      }
      if (clear) {
        g.rgba[3] = style.transparent_alpha;
        g.transparent = 1;
      }
    }
    g.segid = kept;
    im.scn.geoms[kept++] = g;
  }
  im.scn.ngeom = kept;
}

void OffscreenRenderer::AddOverlays(const std::vector<Overlay>& overlays, const DrawStyle& style,
                                    bool segment) {
  Impl& im = *impl_;
  for (const Overlay& o : overlays) {
    if (segment && std::find(style.unsegmented_overlays.begin(), style.unsegmented_overlays.end(),
                             o.label) != style.unsegmented_overlays.end()) {
      continue;
    }
    auto add = [&](int type, const Eigen::Vector3d& a, const Eigen::Vector3d* b) {
      if (im.scn.ngeom >= im.scn.maxgeom) return;
      mjvGeom* g = im.scn.geoms + im.scn.ngeom;
      const mjtNum size[3] = {o.radius_m, o.radius_m, o.radius_m};
      const mjtNum pos[3] = {a.x(), a.y(), a.z()};
      mjv_initGeom(g, type, size, pos, nullptr, o.rgba);
      if (b != nullptr) {
        const bool arrow = type == mjGEOM_ARROW;
        mjv_makeConnector(g, type, arrow ? 2.0 * o.radius_m : o.radius_m, a.x(), a.y(), a.z(),
                          b->x(), b->y(), b->z());
      }
      g->category = mjCAT_DECOR;
      g->emission = 0.35f;
      g->segid = im.scn.ngeom;
      im.overlay_labels.push_back(o.label);
      ++im.scn.ngeom;
    };
    if (o.polyline && !o.normals.empty() && o.normals.size() == o.points_m.size()) {
      for (std::size_t i = 0; i + 1 < o.points_m.size(); ++i) {
        const Eigen::Vector3d d = o.points_m[i + 1] - o.points_m[i];
        const Eigen::Vector3d n = o.normals[i] + o.normals[i + 1];
        const Eigen::Vector3d across = n.cross(d);
        if (d.norm() < 1e-9 || across.norm() < 1e-12) continue;
        // Box axes: x across, y along the segment, z its normal (columns: local to world).
        Eigen::Matrix3d axes;
        axes.col(1) = d.normalized();
        axes.col(0) = across.normalized();
        axes.col(2) = axes.col(0).cross(axes.col(1));
        if (im.scn.ngeom >= im.scn.maxgeom) break;  // the scene is full
        add(mjGEOM_BOX, 0.5 * (o.points_m[i] + o.points_m[i + 1]), nullptr);
        mjvGeom* g = im.scn.geoms + im.scn.ngeom - 1;
        g->size[0] = static_cast<float>(o.radius_m);
        g->size[1] = static_cast<float>(0.5 * d.norm());
        g->size[2] = static_cast<float>(0.5 * o.ribbon_thickness_m);
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) g->mat[3 * r + c] = static_cast<float>(axes(r, c));
        }
      }
    } else if (o.polyline) {
      for (std::size_t i = 0; i + 1 < o.points_m.size(); ++i) {
        if ((o.points_m[i + 1] - o.points_m[i]).norm() < 1e-9) continue;
        const bool last = i + 2 == o.points_m.size();
        add(o.arrow_head && last ? mjGEOM_ARROW : mjGEOM_CAPSULE, o.points_m[i],
            &o.points_m[i + 1]);
      }
    } else {
      for (const auto& p : o.points_m) add(mjGEOM_SPHERE, p, nullptr);
    }
  }
}

void OffscreenRenderer::Draw(mjData* data, const CameraView& camera,
                             const std::vector<Overlay>& overlays, const DrawStyle& style,
                             bool segment) {
  Impl& im = *impl_;
  OSMesaMakeCurrent(im.gl, im.framebuffer.data(), GL_UNSIGNED_BYTE, im.width, im.height);
  im.cam.type = mjCAMERA_FREE;
  for (int i = 0; i < 3; ++i) im.cam.lookat[i] = camera.lookat_m[i];
  im.cam.distance = camera.distance_m;
  im.cam.azimuth = camera.azimuth_deg;
  im.cam.elevation = camera.elevation_deg;
  mjv_updateScene(im.model, data, &im.opt, nullptr, &im.cam, mjCAT_ALL, &im.scn);
  ApplyStyle(style, segment);
  im.model_geom_count = im.scn.ngeom;
  im.overlay_labels.clear();
  AddOverlays(overlays, style, segment);
  im.scn.flags[mjRND_SEGMENT] = segment ? 1 : 0;
  im.scn.flags[mjRND_IDCOLOR] = segment ? 1 : 0;
  im.scn.flags[mjRND_SHADOW] = segment ? 0 : 1;
  im.scn.flags[mjRND_SKYBOX] = segment ? 0 : 1;
  const mjrRect viewport = {0, 0, im.width, im.height};
  mjr_render(viewport, &im.scn, &im.con);
}

Image OffscreenRenderer::Render(mjData* data, const CameraView& camera,
                                const std::vector<Overlay>& overlays, const DrawStyle& style) {
  Draw(data, camera, overlays, style, false);
  Impl& im = *impl_;
  Image img;
  img.width = im.width;
  img.height = im.height;
  std::vector<unsigned char> raw(static_cast<std::size_t>(im.width) * im.height * 3);
  const mjrRect viewport = {0, 0, im.width, im.height};
  mjr_readPixels(raw.data(), nullptr, viewport, &im.con);
  img.rgb.resize(raw.size());
  const std::size_t row = static_cast<std::size_t>(im.width) * 3;
  for (int y = 0; y < im.height; ++y) {  // OpenGL rows are bottom-up
    std::memcpy(img.rgb.data() + static_cast<std::size_t>(y) * row,
                raw.data() + static_cast<std::size_t>(im.height - 1 - y) * row, row);
  }
  return img;
}

Segmentation OffscreenRenderer::RenderSegmentation(mjData* data, const CameraView& camera,
                                                   const std::vector<Overlay>& overlays,
                                                   const DrawStyle& style) {
  Draw(data, camera, overlays, style, true);
  Impl& im = *impl_;
  std::vector<unsigned char> raw(static_cast<std::size_t>(im.width) * im.height * 3);
  const mjrRect viewport = {0, 0, im.width, im.height};
  mjr_readPixels(raw.data(), nullptr, viewport, &im.con);
  Segmentation seg;
  seg.width = im.width;
  seg.height = im.height;
  seg.label.assign(static_cast<std::size_t>(im.width) * im.height, -1);
  // Names per scene geom slot.
  for (int i = 0; i < im.scn.ngeom; ++i) {
    const mjvGeom& g = im.scn.geoms[i];
    if (i >= im.model_geom_count) {
      seg.names.push_back("overlay:" +
                          im.overlay_labels[static_cast<std::size_t>(i - im.model_geom_count)]);
      seg.body_names.emplace_back();
      seg.geoms.push_back(-1);
    } else if (g.objtype == mjOBJ_GEOM) {
      seg.geoms.push_back(g.objid);
      const char* n = mj_id2name(im.model, mjOBJ_GEOM, g.objid);
      seg.names.emplace_back(n != nullptr ? n : "");
      const char* b = mj_id2name(im.model, mjOBJ_BODY, im.model->geom_bodyid[g.objid]);
      seg.body_names.emplace_back(b != nullptr ? b : "");
    } else {
      seg.names.emplace_back("decor");
      seg.body_names.emplace_back();
      seg.geoms.push_back(-1);
    }
  }
  for (int y = 0; y < im.height; ++y) {
    for (int x = 0; x < im.width; ++x) {
      const std::size_t src = (static_cast<std::size_t>(im.height - 1 - y) * im.width + x) * 3;
      const int id = raw[src] | (raw[src + 1] << 8) | (raw[src + 2] << 16);
      const int slot = id - 1;
      if (slot >= 0 && slot < im.scn.ngeom) {
        seg.label[static_cast<std::size_t>(y) * im.width + x] = slot;
      }
    }
  }
  return seg;
}

CameraView LookAlong(const Eigen::Vector3d& lookat_m, const Eigen::Vector3d& forward,
                     double distance_m) {
  // MuJoCo's free camera looks along (cos el cos az, cos el sin az, sin el).
  const Eigen::Vector3d f = forward.normalized();
  CameraView v;
  v.lookat_m = lookat_m;
  v.distance_m = distance_m;
  v.azimuth_deg = std::atan2(f.y(), f.x()) * kRadToDeg;
  v.elevation_deg = std::clamp(std::asin(std::clamp(f.z(), -1.0, 1.0)) * kRadToDeg, -89.0, 89.0);
  return v;
}

Eigen::Vector3d ViewDirection(const CameraView& view) {
  const double az = view.azimuth_deg * kDeg, el = view.elevation_deg * kDeg;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

}  // namespace stitchsim::render
