#include "detail/collision_mjcf.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <optional>

#include "stitchsim/common/files.h"

namespace stitchsim::sim::detail {
namespace {

// Worldbody contents of a stand-alone MJCF fragment (a head file).
std::string WorldbodyInner(const std::string& xml) {
  const auto b = xml.find("<worldbody>");
  const auto e = xml.rfind("</worldbody>");
  if (b == std::string::npos || e == std::string::npos || e < b) return {};
  return xml.substr(b + std::strlen("<worldbody>"), e - b - std::strlen("<worldbody>"));
}

Eigen::Isometry3d PoseOf(const mjtNum* pos, const mjtNum* quat) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pos[0], pos[1], pos[2]);
  t.linear() = Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]).normalized().matrix();
  return t;
}

}  // namespace

std::string WithoutGeoms(const std::string& xml) {
  std::string out;
  out.reserve(xml.size());
  std::size_t at = 0;
  for (std::size_t g = xml.find("<geom"); g != std::string::npos; g = xml.find("<geom", at)) {
    out.append(xml, at, g - at);
    const std::size_t close = xml.find('>', g);
    if (close == std::string::npos) return xml;  // malformed: let the compiler say so
    at = close + 1;
    if (xml[close - 1] != '/') {  // <geom ...> ... </geom>
      const std::size_t end = xml.find("</geom>", close);
      if (end == std::string::npos) return xml;
      at = end + std::strlen("</geom>");
    }
  }
  out.append(xml, at, std::string::npos);
  return out;
}

MjModelPtr CompileCellWithHead(const std::filesystem::path& cell_mjcf,
                               const std::filesystem::path& head_mjcf, DiagnosticSink& sink,
                               const std::string& head_root_extra, const std::string& code,
                               bool strip_geoms) {
  const auto cell = ReadFile(cell_mjcf);
  const auto head = ReadFile(head_mjcf);
  if (!cell || !head) {
    sink.Error(code, {(!cell ? cell_mjcf : head_mjcf).string(), 0, 0},
               "cannot read MJCF file");
    return nullptr;
  }
  const std::string inner = WorldbodyInner(*head);
  std::string text = *cell;
  const std::string marker = "<!--STITCHSIM:HEAD-->";
  const auto at = text.find(marker);
  if (inner.empty() || at == std::string::npos) {
    sink.Error(code, {head_mjcf.string(), 0, 0},
               "head MJCF has no <worldbody> content or the cell lacks the head marker");
    return nullptr;
  }
  // Tag the head's bodies so its geoms can be told apart after compilation.
  text.replace(at, marker.size(),
               "<body name=\"stitchsim_head_root\">" + head_root_extra + inner + "</body>");
  if (strip_geoms) text = WithoutGeoms(text);
  auto vfs = std::make_unique<mjVFS>();  // megabytes: keep it off the stack
  mj_defaultVFS(vfs.get());
  const char* name = "stitchsim_collision.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(text.size())) != 0) {
    sink.Error(code, {cell_mjcf.string(), 0, 0}, "MuJoCo VFS is full");
    return nullptr;
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], text.data(), text.size());
  char error[1024] = {0};
  MjModelPtr m(mj_loadXML(name, vfs.get(), error, sizeof(error)));
  mj_deleteVFS(vfs.get());
  if (!m) {
    sink.Error(code, {cell_mjcf.string(), 0, 0},
               std::string("MuJoCo could not compile the cell + head model: ") + error);
  }
  return m;
}

namespace {

std::string BodyName(const mjModel& m, int b) {
  const char* n = mj_id2name(&m, mjOBJ_BODY, b);
  return std::string(n != nullptr ? n : "");
}

// Geom `g`'s name, bodies and pose in the frame of the nearest body that is a URDF link.
MjcfGeom PlacedGeom(const mjModel& m, int g, const std::vector<std::string>& link_names) {
  auto is_link = [&](const std::string& n) {
    return std::find(link_names.begin(), link_names.end(), n) != link_names.end();
  };
  MjcfGeom geom;
  const char* gname = mj_id2name(&m, mjOBJ_GEOM, g);
  geom.name = gname != nullptr ? gname : "geom_" + std::to_string(g);
  const int body = m.geom_bodyid[g];
  geom.body = BodyName(m, body);
  Eigen::Isometry3d pose = PoseOf(m.geom_pos + 3 * g, m.geom_quat + 4 * g);
  int b = body;
  while (b != 0 && !is_link(BodyName(m, b))) {
    if (BodyName(m, b) == "stitchsim_head_root") geom.in_head = true;
    pose = PoseOf(m.body_pos + 3 * b, m.body_quat + 4 * b) * pose;
    b = m.body_parentid[b];
  }
  geom.link = b == 0 ? "world" : BodyName(m, b);
  for (int t = body; t != 0; t = m.body_parentid[t]) {
    if (m.body_parentid[t] == 0) geom.top_body = BodyName(m, t);
  }
  geom.pose_in_link = pose;
  geom.size = Eigen::Vector3d(m.geom_size[3 * g], m.geom_size[3 * g + 1], m.geom_size[3 * g + 2]);
  return geom;
}

// The collision shape of a MuJoCo geom type; nullopt for a type FCL is not given.
std::optional<MjcfShape> ShapeOf(int mujoco_type) {
  switch (mujoco_type) {
    case mjGEOM_BOX:
      return MjcfShape::kBox;
    case mjGEOM_SPHERE:
      return MjcfShape::kSphere;
    case mjGEOM_CAPSULE:
      return MjcfShape::kCapsule;
    case mjGEOM_CYLINDER:
      return MjcfShape::kCylinder;
    case mjGEOM_PLANE:
      return MjcfShape::kPlane;
    default:
      return std::nullopt;
  }
}

}  // namespace

std::vector<MjcfGeom> LoadMjcfGeoms(const std::filesystem::path& cell_mjcf,
                                    const std::filesystem::path& head_mjcf,
                                    const std::vector<std::string>& link_names,
                                    DiagnosticSink& sink, bool& ok) {
  ok = false;
  std::vector<MjcfGeom> out;
  const MjModelPtr m = CompileCellWithHead(cell_mjcf, head_mjcf, sink);
  if (!m) return out;
  bool good = true;
  for (int g = 0; g < m->ngeom; ++g) {
    MjcfGeom geom = PlacedGeom(*m, g, link_names);
    const std::optional<MjcfShape> shape = ShapeOf(m->geom_type[g]);
    if (!shape) {
      sink.Error("collision-unsupported-geom", {head_mjcf.string(), 0, 0},
                 "geom '" + geom.name + "' has a MuJoCo type (" + std::to_string(m->geom_type[g]) +
                     ") the collision checker does not map to FCL");
      good = false;
      continue;
    }
    geom.shape = *shape;
    if (geom.shape == MjcfShape::kPlane && geom.link != "world") {
      sink.Error("collision-unsupported-geom", {head_mjcf.string(), 0, 0},
                 "geom '" + geom.name + "' is a plane on a body that is not the world");
      good = false;
      continue;
    }
    out.push_back(std::move(geom));
  }
  ok = good;
  if (!good) out.clear();
  return out;
}

}  // namespace stitchsim::sim::detail
