#include "stitchsim/render/scene_model.h"

#include <Eigen/Geometry>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>

#include "stitchsim/common/files.h"

namespace stitchsim::render {
namespace {

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}

std::string Vec(const Eigen::Vector3d& v) {
  return Num(v.x()) + " " + Num(v.y()) + " " + Num(v.z());
}

std::string Quat(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  return Num(q.w()) + " " + Num(q.x()) + " " + Num(q.y()) + " " + Num(q.z());
}

// Worldbody contents of a stand-alone MJCF fragment (a head file).
std::string WorldbodyInner(const std::string& xml) {
  const auto b = xml.find("<worldbody>");
  const auto e = xml.rfind("</worldbody>");
  if (b == std::string::npos || e == std::string::npos || e < b) return {};
  return xml.substr(b + std::strlen("<worldbody>"), e - b - std::strlen("<worldbody>"));
}

void AppendMesh(std::ostringstream& assets, const std::string& name,
                const geom::TriangleMesh& mesh_mm) {
  assets << "    <mesh name=\"" << name << "\" vertex=\"";
  for (const auto& v : mesh_mm.vertices) assets << Vec(v / 1000.0) << ' ';
  assets << "\" face=\"";
  for (const auto& t : mesh_mm.triangles) assets << t[0] << ' ' << t[1] << ' ' << t[2] << ' ';
  assets << "\"/>\n";
}

bool Replace(std::string& text, const std::string& marker, const std::string& with) {
  const auto pos = text.find(marker);
  if (pos == std::string::npos) return false;
  text.replace(pos, marker.size(), with);
  return true;
}

}  // namespace

std::string ComposeSceneMjcf(const scene::Scene& scene, DiagnosticSink& sink) {
  auto cell = ReadFile(scene.cell_mjcf);
  if (!cell) {
    sink.Error("model-missing-file", {scene.cell_mjcf.string(), 0, 0},
               "cannot read cell MJCF " + scene.cell_mjcf.string());
    return {};
  }
  auto head = ReadFile(scene.head.mjcf);
  if (!head) {
    sink.Error("model-missing-file", {scene.head.mjcf.string(), 0, 0},
               "cannot read head MJCF " + scene.head.mjcf.string());
    return {};
  }
  const std::string head_inner = WorldbodyInner(*head);
  if (head_inner.empty()) {
    sink.Error("model-bad-head", {scene.head.mjcf.string(), 0, 0},
               "head MJCF has no <worldbody> content");
    return {};
  }
  std::ostringstream assets;
  std::ostringstream part;
  assets << "    <material name=\"mold\" rgba=\"0.36 0.44 0.55 1\" specular=\"0.3\"/>\n"
         << "    <material name=\"preform\" rgba=\"0.86 0.78 0.58 1\" specular=\"0.1\"/>\n"
         << "    <material name=\"constraint\" rgba=\"0.72 0.22 0.2 1\" specular=\"0.2\"/>\n";
  const geom::Surface& s = *scene.surface;
  const geom::Domain2 dom = s.Domain();
  AppendMesh(assets, "mold_mesh", geom::TessellateSlab(s, dom, -scene.mold_depth_mm, 0.0, 0.5));
  // The preform sits on the surface, a little inset so the mold edge stays visible.
  geom::Domain2 inset = dom;
  const Eigen::Vector2d margin = (dom.max - dom.min) * 0.04;
  inset.min += margin;
  inset.max -= margin;
  AppendMesh(assets, "preform_mesh",
             geom::TessellateSlab(s, inset, 0.0, scene.preform_thickness_mm, 0.5));
  part
      << "<body name=\"part\" pos=\"" << Vec(scene.mount_to_part_m.translation()) << "\" quat=\""
      << Quat(scene.mount_to_part_m.linear()) << "\">\n"
      << "  <geom name=\"" << kMoldGeom
      << "\" type=\"mesh\" mesh=\"mold_mesh\" material=\"mold\" contype=\"0\" conaffinity=\"0\"/>\n"
      << "  <geom name=\"" << kPreformGeom
      << "\" type=\"mesh\" mesh=\"preform_mesh\" material=\"preform\" contype=\"0\" "
         "conaffinity=\"0\"/>\n";
  int mesh_id = 0;
  for (const auto& c : scene.constraints) {
    const std::string gname = kConstraintGeomPrefix + c.name;
    if (c.shape == scene::Constraint::Shape::kBox) {
      part << "  <geom name=\"" << gname << "\" type=\"box\" pos=\""
           << Vec(c.pose_mm.translation() / 1000.0) << "\" quat=\"" << Quat(c.pose_mm.linear())
           << "\" size=\"" << Vec(c.size_mm / 2000.0)
           << "\" material=\"constraint\" contype=\"0\" conaffinity=\"0\"/>\n";
    } else {
      const std::string mname = "constraint_mesh_" + std::to_string(mesh_id++);
      AppendMesh(assets, mname, c.mesh);
      part << "  <geom name=\"" << gname << "\" type=\"mesh\" mesh=\"" << mname
           << "\" material=\"constraint\" contype=\"0\" conaffinity=\"0\"/>\n";
    }
  }
  part << "</body>\n";
  std::string text = *cell;
  bool ok = Replace(text, "<!--STITCHSIM:ASSETS-->", assets.str());
  ok = Replace(text, "<!--STITCHSIM:HEAD-->", head_inner) && ok;
  ok = Replace(text,
               scene.mount == scene::Mount::kTable ? "<!--STITCHSIM:PART_TABLE-->"
                                                   : "<!--STITCHSIM:PART_ROTATOR-->",
               part.str()) &&
       ok;
  if (!ok) {
    sink.Error("model-missing-marker", {scene.cell_mjcf.string(), 0, 0},
               "cell MJCF lacks a <!--STITCHSIM:...--> insertion marker");
    return {};
  }
  return text;
}

std::vector<int> GeomsOfBody(const mjModel& model, int body_id) {
  std::vector<int> out;
  for (int g = 0; g < model.ngeom; ++g) {
    if (model.geom_bodyid[g] == body_id) out.push_back(g);
  }
  return out;
}

std::vector<int> GeomsOfCollisionBody(const mjModel& model, const std::string& body) {
  auto geom = [&](const std::string& name) -> std::vector<int> {
    const int id = mj_name2id(&model, mjOBJ_GEOM, name.c_str());
    if (id < 0) return {};
    return {id};
  };
  if (body.rfind("head:", 0) == 0) return geom(body.substr(5));
  if (body == "mold") return geom(kMoldGeom);
  if (body == "preform") return geom(kPreformGeom);
  if (body.rfind("constraint:", 0) == 0) return geom(kConstraintGeomPrefix + body.substr(11));
  const int id = mj_name2id(&model, mjOBJ_BODY, body.c_str());
  if (id > 0) return GeomsOfBody(model, id);
  return geom(body);
}

MjModelPtr LoadSceneModel(const scene::Scene& scene, DiagnosticSink& sink) {
  const std::string xml = ComposeSceneMjcf(scene, sink);
  if (xml.empty()) return nullptr;
  // mjVFS is megabytes large: keep it off the stack.
  auto vfs_holder = std::make_unique<mjVFS>();
  mjVFS& vfs = *vfs_holder;
  mj_defaultVFS(&vfs);
  const char* name = "stitchsim_scene.xml";
  if (mj_makeEmptyFileVFS(&vfs, name, static_cast<int>(xml.size())) != 0) {
    sink.Error("model-compile", {scene.file.string(), 0, 0}, "MuJoCo VFS is full");
    return nullptr;
  }
  const int idx = mj_findFileVFS(&vfs, name);
  std::memcpy(vfs.filedata[idx], xml.data(), xml.size());
  char error[1024] = {0};
  mjModel* m = mj_loadXML(name, &vfs, error, sizeof(error));
  mj_deleteVFS(&vfs);
  if (m == nullptr) {
    sink.Error("model-compile", {scene.file.string(), 0, 0},
               std::string("MuJoCo could not compile the scene model: ") + error);
    return nullptr;
  }
  // cell.omit: the fixture's geoms go to group 5, which the renderer's default visual
  // options (groups 0 to 2) never draw.
  // The part rides in the mount's body but is never omitted with it.
  const int part = mj_name2id(m, mjOBJ_BODY, "part");
  for (int g = 0; g < m->ngeom; ++g) {
    int top = m->geom_bodyid[g];
    bool in_part = false;
    while (top != 0 && m->body_parentid[top] != 0) {
      in_part = in_part || top == part;
      top = m->body_parentid[top];
    }
    const char* n = top != 0 ? mj_id2name(m, mjOBJ_BODY, top) : nullptr;
    if (!in_part && n != nullptr && scene.OmitsMjcfBody(n)) m->geom_group[g] = kHiddenGeomGroup;
  }
  return MjModelPtr(m);
}

}  // namespace stitchsim::render
