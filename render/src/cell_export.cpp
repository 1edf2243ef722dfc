#include "stitchsim/render/cell_export.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "stitchsim/common/base64.h"
#include "stitchsim/render/scene_model.h"

namespace stitchsim::render {
namespace {

using nlohmann::json;

json Vec(const mjtNum* v, int n) {
  json a = json::array();
  for (int i = 0; i < n; ++i) a.push_back(v[i]);
  return a;
}

json Rgba(const mjModel& m, int g) {
  const float* c = m.geom_matid[g] >= 0 ? m.mat_rgba + 4 * m.geom_matid[g] : m.geom_rgba + 4 * g;
  // MuJoCo's default geom colour applies when neither geom nor material sets one.
  return json::array({c[0], c[1], c[2], c[3]});
}

const char* GeomType(int type) {
  switch (type) {
    case mjGEOM_PLANE:
      return "plane";
    case mjGEOM_SPHERE:
      return "sphere";
    case mjGEOM_CAPSULE:
      return "capsule";
    case mjGEOM_ELLIPSOID:
      return "ellipsoid";
    case mjGEOM_CYLINDER:
      return "cylinder";
    case mjGEOM_BOX:
      return "box";
    case mjGEOM_MESH:
      return "mesh";
    default:
      return nullptr;  // height fields: not drawn
  }
}

std::string Name(const mjModel& m, int type, int id) {
  const char* n = mj_id2name(&m, type, id);
  return n == nullptr ? "" : n;
}

json Joint(const mjModel& m, int body, const CellExportOptions& o) {
  if (m.body_jntnum[body] == 0) return nullptr;
  const int j = m.body_jntadr[body];
  const std::string name = Name(m, mjOBJ_JOINT, j);
  const auto it = std::find(o.joints.begin(), o.joints.end(), name);
  const int type = m.jnt_type[j];
  if (it == o.joints.end() || (type != mjJNT_HINGE && type != mjJNT_SLIDE)) return nullptr;
  return json{{"name", name},
              {"type", type == mjJNT_HINGE ? "hinge" : "slide"},
              {"axis", Vec(m.jnt_axis + 3 * j, 3)},
              {"pos", Vec(m.jnt_pos + 3 * j, 3)},
              {"index", it - o.joints.begin()},
              {"ref", m.qpos0[m.jnt_qposadr[j]]}};
}

}  // namespace

ThinnedMesh ThinMesh(const float* vertices, int vertex_count, const int* faces, int face_count,
                     std::size_t max_faces) {
  ThinnedMesh out;
  out.vertices.assign(vertices, vertices + 3 * vertex_count);
  out.faces.assign(faces, faces + 3 * face_count);
  if (static_cast<std::size_t>(face_count) <= max_faces || vertex_count == 0) return out;
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = vertices[a];
  for (int v = 0; v < vertex_count; ++v) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], vertices[3 * v + a]);
      hi[a] = std::max(hi[a], vertices[3 * v + a]);
    }
  }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-9f});
  for (double step = extent / 4096.0; step < 2.0 * extent; step *= 2.0) {
    std::unordered_map<long long, std::uint32_t> cell_of;
    std::vector<double> sum;
    std::vector<int> count;
    std::vector<std::uint32_t> remap(static_cast<std::size_t>(vertex_count));
    for (int v = 0; v < vertex_count; ++v) {
      long long key = 0;
      for (int a = 0; a < 3; ++a) {
        key = key * 8192 + static_cast<long long>((vertices[3 * v + a] - lo[a]) / step);
      }
      auto [it, fresh] = cell_of.try_emplace(key, static_cast<std::uint32_t>(count.size()));
      if (fresh) {
        sum.insert(sum.end(), 3, 0.0);
        count.push_back(0);
      }
      const std::uint32_t c = it->second;
      for (int a = 0; a < 3; ++a) sum[3 * c + a] += vertices[3 * v + a];
      ++count[c];
      remap[static_cast<std::size_t>(v)] = c;
    }
    std::vector<std::uint32_t> kept;
    for (int f = 0; f < face_count; ++f) {
      const std::uint32_t i = remap[static_cast<std::size_t>(faces[3 * f])];
      const std::uint32_t j = remap[static_cast<std::size_t>(faces[3 * f + 1])];
      const std::uint32_t k = remap[static_cast<std::size_t>(faces[3 * f + 2])];
      if (i != j && j != k && i != k) kept.insert(kept.end(), {i, j, k});
    }
    if (kept.size() / 3 > max_faces) continue;
    out.vertices.resize(3 * count.size());
    for (std::size_t c = 0; c < count.size(); ++c) {
      for (std::size_t a = 0; a < 3; ++a) {
        out.vertices[3 * c + a] = static_cast<float>(sum[3 * c + a] / count[c]);
      }
    }
    out.faces = std::move(kept);
    return out;
  }
  out.faces.clear();  // unreachable for a finite mesh: one cell holds everything
  return out;
}

json ExportCell(const mjModel& m, const CellExportOptions& o, std::string& error) {
  for (const std::string& name : o.joints) {
    if (mj_name2id(&m, mjOBJ_JOINT, name.c_str()) < 0) {
      error = "the MuJoCo model has no joint " + name;
      return nullptr;
    }
  }
  long total_faces = 0;
  for (int k = 0; k < m.nmesh; ++k) total_faces += m.mesh_facenum[k];
  json meshes = json::array();
  for (int k = 0; k < m.nmesh; ++k) {
    // Each mesh's share of the budget in proportion to its size.
    const auto share = static_cast<std::size_t>(std::max(
        64.0, static_cast<double>(o.max_faces) * m.mesh_facenum[k] / std::max(1L, total_faces)));
    const ThinnedMesh t = ThinMesh(m.mesh_vert + 3 * m.mesh_vertadr[k], m.mesh_vertnum[k],
                                   m.mesh_face + 3 * m.mesh_faceadr[k], m.mesh_facenum[k], share);
    meshes.push_back(json{{"vertices", Base64Of(t.vertices)}, {"faces", Base64Of(t.faces)}});
  }
  json bodies = json::array();
  for (int b = 1; b < m.nbody; ++b) {  // body 0 is the world
    json geoms = json::array();
    for (int g = m.body_geomadr[b]; g >= 0 && g < m.body_geomadr[b] + m.body_geomnum[b]; ++g) {
      const char* type = GeomType(m.geom_type[g]);
      if (type == nullptr || m.geom_group[g] == kHiddenGeomGroup || m.geom_group[g] > 2) continue;
      geoms.push_back(
          json{{"name", Name(m, mjOBJ_GEOM, g)},
               {"type", type},
               {"size", Vec(m.geom_size + 3 * g, 3)},
               {"pos", Vec(m.geom_pos + 3 * g, 3)},
               {"quat", Vec(m.geom_quat + 4 * g, 4)},
               {"rgba", Rgba(m, g)},
               {"mesh", m.geom_type[g] == mjGEOM_MESH ? json(m.geom_dataid[g]) : json(nullptr)}});
    }
    bodies.push_back(json{{"name", Name(m, mjOBJ_BODY, b)},
                          {"parent", m.body_parentid[b] - 1},
                          {"pos", Vec(m.body_pos + 3 * b, 3)},
                          {"quat", Vec(m.body_quat + 4 * b, 4)},
                          {"joint", Joint(m, b, o)},
                          {"geoms", std::move(geoms)}});
  }
  json joints = json::array(), home = json::array();
  for (const std::string& name : o.joints) {
    joints.push_back(name);
    home.push_back(m.qpos0[m.jnt_qposadr[mj_name2id(&m, mjOBJ_JOINT, name.c_str())]]);
  }
  return json{{"joints", std::move(joints)},
              {"home", std::move(home)},
              {"bodies", std::move(bodies)},
              {"meshes", std::move(meshes)},
              {"part_body", mj_name2id(&m, mjOBJ_BODY, "part") - 1}};
}

}  // namespace stitchsim::render
