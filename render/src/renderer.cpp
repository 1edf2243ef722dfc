#include "stitchsim/render/renderer.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <cstring>

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

void OffscreenRenderer::Draw(mjData* data, const CameraView& camera,
                             const std::vector<Overlay>& overlays, bool segment) {
  Impl& im = *impl_;
  OSMesaMakeCurrent(im.gl, im.framebuffer.data(), GL_UNSIGNED_BYTE, im.width, im.height);
  im.cam.type = mjCAMERA_FREE;
  for (int i = 0; i < 3; ++i) im.cam.lookat[i] = camera.lookat_m[i];
  im.cam.distance = camera.distance_m;
  im.cam.azimuth = camera.azimuth_deg;
  im.cam.elevation = camera.elevation_deg;
  mjv_updateScene(im.model, data, &im.opt, nullptr, &im.cam, mjCAT_ALL, &im.scn);
  im.model_geom_count = im.scn.ngeom;
  im.overlay_labels.clear();
  for (const Overlay& o : overlays) {
    auto add = [&](int type, const Eigen::Vector3d& a, const Eigen::Vector3d* b) {
      if (im.scn.ngeom >= im.scn.maxgeom) return;
      mjvGeom* g = im.scn.geoms + im.scn.ngeom;
      const mjtNum size[3] = {o.radius_m, o.radius_m, o.radius_m};
      const mjtNum pos[3] = {a.x(), a.y(), a.z()};
      mjv_initGeom(g, type, size, pos, nullptr, o.rgba);
      if (b != nullptr) {
        mjv_makeConnector(g, mjGEOM_CAPSULE, o.radius_m, a.x(), a.y(), a.z(), b->x(), b->y(),
                          b->z());
      }
      g->category = mjCAT_DECOR;
      g->emission = 0.35f;
      g->segid = im.scn.ngeom;
      im.overlay_labels.push_back(o.label);
      ++im.scn.ngeom;
    };
    if (o.polyline) {
      for (std::size_t i = 0; i + 1 < o.points_m.size(); ++i) {
        if ((o.points_m[i + 1] - o.points_m[i]).norm() < 1e-9) continue;
        add(mjGEOM_CAPSULE, o.points_m[i], &o.points_m[i + 1]);
      }
    } else {
      for (const auto& p : o.points_m) add(mjGEOM_SPHERE, p, nullptr);
    }
  }
  im.scn.flags[mjRND_SEGMENT] = segment ? 1 : 0;
  im.scn.flags[mjRND_IDCOLOR] = segment ? 1 : 0;
  im.scn.flags[mjRND_SHADOW] = segment ? 0 : 1;
  im.scn.flags[mjRND_SKYBOX] = segment ? 0 : 1;
  const mjrRect viewport = {0, 0, im.width, im.height};
  mjr_render(viewport, &im.scn, &im.con);
}

Image OffscreenRenderer::Render(mjData* data, const CameraView& camera,
                                const std::vector<Overlay>& overlays) {
  Draw(data, camera, overlays, false);
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
                                                   const std::vector<Overlay>& overlays) {
  Draw(data, camera, overlays, true);
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
    } else if (g.objtype == mjOBJ_GEOM) {
      const char* n = mj_id2name(im.model, mjOBJ_GEOM, g.objid);
      seg.names.emplace_back(n != nullptr ? n : "");
      const char* b = mj_id2name(im.model, mjOBJ_BODY, im.model->geom_bodyid[g.objid]);
      seg.body_names.emplace_back(b != nullptr ? b : "");
    } else {
      seg.names.emplace_back("decor");
      seg.body_names.emplace_back();
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

}  // namespace stitchsim::render
