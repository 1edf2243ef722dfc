#include "stitchsim/geom/stl.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

#include "stitchsim/common/files.h"
#include "stitchsim/common/limits.h"

namespace stitchsim::geom {
namespace {

// Merges vertices on a grid of `tol` (file units). The grid keys are whole doubles, not
// integers: a coordinate beyond 2^63 grid steps would overflow an integer key and weld
// distant vertices together.
struct Welder {
  double tol;
  double scale;
  std::map<std::tuple<double, double, double>, int> index;
  TriangleMesh* mesh;
  double Step() const { return tol > 0 ? tol : 1e-12; }
  /// False if `p_file` is too large for the grid (a key would be infinite).
  bool Weldable(const Eigen::Vector3d& p_file) const { return (p_file / Step()).allFinite(); }
  int Add(const Eigen::Vector3d& p_file) {
    const Eigen::Vector3d g = p_file / Step();
    const auto key = std::make_tuple(std::round(g.x()), std::round(g.y()), std::round(g.z()));
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const int id = static_cast<int>(mesh->vertices.size());
    mesh->vertices.push_back(p_file * scale);
    index.emplace(key, id);
    return id;
  }
};

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

bool ReadStl(const std::filesystem::path& path, double scale_to_mm, TriangleMesh& mesh,
             std::string& error, double weld_tol) {
  // A regular file within the size cap: a directory, FIFO or /dev/zero is refused up front.
  FileText file = ReadRegularFile(path, limits::kMaxStlFileBytes);
  if (!file.ok()) {
    error = "cannot read STL file: " + file.error;
    return false;
  }
  const std::string& bytes = file.text;
  TriangleMesh out;
  Welder welder{weld_tol, scale_to_mm, {}, &out};
  auto add_triangle = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
    const int ia = welder.Add(a), ib = welder.Add(b), ic = welder.Add(c);
    if (ia != ib && ib != ic && ia != ic) out.triangles.emplace_back(ia, ib, ic);
  };
  const bool looks_binary = [&] {
    if (bytes.size() < 84) return false;
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);
    return bytes.size() == 84 + static_cast<std::size_t>(n) * 50;
  }();
  if (looks_binary) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);
    for (std::uint32_t i = 0; i < n; ++i) {
      const char* rec = bytes.data() + 84 + static_cast<std::size_t>(i) * 50;
      float f[12];
      std::memcpy(f, rec, sizeof(f));
      Eigen::Vector3d v[3];
      for (int k = 0; k < 3; ++k) v[k] = Eigen::Vector3d(f[3 + 3 * k], f[4 + 3 * k], f[5 + 3 * k]);
      if (!Finite(v[0]) || !Finite(v[1]) || !Finite(v[2])) {
        error = "STL triangle " + std::to_string(i + 1) + " has a non-finite coordinate";
        return false;
      }
      if (!welder.Weldable(v[0]) || !welder.Weldable(v[1]) || !welder.Weldable(v[2])) {
        error = "STL triangle " + std::to_string(i + 1) + " has a coordinate too large to weld";
        return false;
      }
      add_triangle(v[0], v[1], v[2]);
    }
  } else {
    std::istringstream ss(bytes);
    std::string word;
    if (!(ss >> word) || word != "solid") {
      error = "not an STL file (neither binary nor ASCII 'solid'): " + path.string();
      return false;
    }
    std::vector<Eigen::Vector3d> facet;
    while (ss >> word) {
      if (word == "vertex") {
        Eigen::Vector3d v;
        if (!(ss >> v.x() >> v.y() >> v.z()) || !Finite(v)) {
          error = "malformed vertex in ASCII STL " + path.string();
          return false;
        }
        if (!welder.Weldable(v)) {
          error = "vertex coordinate too large to weld in ASCII STL " + path.string();
          return false;
        }
        facet.push_back(v);
      } else if (word == "endfacet") {
        if (facet.size() != 3) {
          error = "ASCII STL facet without exactly three vertices in " + path.string();
          return false;
        }
        add_triangle(facet[0], facet[1], facet[2]);
        facet.clear();
      }
    }
  }
  if (out.triangles.empty()) {
    error = "STL file has no triangles: " + path.string();
    return false;
  }
  mesh = std::move(out);
  return true;
}

bool WriteStl(const std::filesystem::path& path, const TriangleMesh& mesh, std::string& error) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    error = "cannot write " + path.string();
    return false;
  }
  char header[80] = "stitchsim binary STL";
  out.write(header, 80);
  const std::uint32_t n = static_cast<std::uint32_t>(mesh.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    Eigen::Vector3d nrm = (b - a).cross(c - a);
    if (nrm.norm() > 0) nrm.normalize();
    float f[12];
    const Eigen::Vector3d* vs[4] = {&nrm, &a, &b, &c};
    for (int k = 0; k < 4; ++k) {
      for (int d = 0; d < 3; ++d) f[3 * k + d] = static_cast<float>((*vs[k])[d]);
    }
    out.write(reinterpret_cast<const char*>(f), sizeof(f));
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
  if (!out) {
    error = "write failed for " + path.string();
    return false;
  }
  return true;
}

}  // namespace stitchsim::geom
