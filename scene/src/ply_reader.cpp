#include "ply_reader.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <set>
#include <string_view>
#include <utility>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/polygon2.h"

namespace stitchsim::scene::detail {
namespace {

bool NameOk(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

class PlyReader {
 public:
  PlyReader(YamlReader& r, LengthUnit unit, const Scene& scene)
      : r_(r), unit_(unit), scene_(scene) {}

  std::optional<PlySpec> Read(const YAML::Node& item, std::set<std::string>& names) {
    if (!r_.ExpectMap(item, "a ply")) return std::nullopt;
    r_.CheckKeys(item,
                 {"name", "angle_deg", "reference", "boundary_uv", "boundary", "rule", "method",
                  "coverage", "tows", "material"},
                 "ply");
    PlySpec ply;
    ply.where = r_.At(item);
    const std::size_t errors = r_.Sink().ErrorCount();
    if (auto n = r_.Child(item, "name", true)) {
      if (auto s = r_.String(*n, "ply name")) {
        ply.name = *s;
        if (!NameOk(*s)) Bad(*n, "ply name '" + *s + "' must be letters, digits, '_' or '-'");
        if (!names.insert(*s).second) Bad(*n, "ply '" + *s + "' is defined twice");
      }
    }
    if (auto n = r_.Child(item, "angle_deg", false)) {
      if (auto v = r_.Number(*n, "angle_deg")) ply.angle_rad = *v * kDeg;
    }
    ReadEnums(item, ply);
    ReadTows(item, ply);
    ReadMaterial(item, ply);
    const bool reference_ok = ReadReference(item, ply);
    if (reference_ok) ReadBoundary(item, ply);
    if (r_.Sink().ErrorCount() > errors) return std::nullopt;
    return ply;
  }

 private:
  void Bad(const YAML::Node& n, std::string message) { r_.Error(n, "bad-ply", std::move(message)); }

  /// The value of `key` among `choices` (name, value), into `out`; else scene-bad-ply.
  template <typename T>
  void Choice(const YAML::Node& item, std::string_view key,
              std::initializer_list<std::pair<std::string_view, T>> choices, T& out) {
    auto n = r_.Child(item, key, false);
    if (!n) return;
    auto s = r_.String(*n, key);
    if (!s) return;
    std::string names;
    for (const auto& [name, value] : choices) {
      if (*s == name) {
        out = value;
        return;
      }
      names += (names.empty() ? "" : " or ") + std::string(name);
    }
    Bad(*n, "ply " + std::string(key) + " must be " + names + ", got '" + *s + "'");
  }

  void ReadEnums(const YAML::Node& item, PlySpec& ply) {
    Choice<PlyRule>(item, "rule",
                    {{"offset", PlyRule::kOffset}, {"laminate_family", PlyRule::kLaminateFamily}},
                    ply.rule);
    Choice<PlyOffsetMethod>(
        item, "method",
        {{"corrected", PlyOffsetMethod::kCorrected}, {"paper", PlyOffsetMethod::kPaper}},
        ply.method);
    if (auto n = r_.Child(item, "coverage", false)) {
      if (auto v = r_.Number(*n, "coverage")) {
        if (*v == 0.0 || *v == 50.0 || *v == 100.0) {
          ply.coverage = *v / 100.0;
        } else {
          Bad(*n, "ply coverage must be 0, 50 or 100 (percent)");
        }
      }
    }
  }

  void ReadTows(const YAML::Node& item, PlySpec& ply) {
    if (scene_.head.kind != HeadKind::kAfp) {
      Bad(item, "ply '" + ply.name + "' needs an AFP head; head '" + scene_.head.name +
                    "' places no tows");
      return;
    }
    ply.tows = scene_.head.afp.tows;
    auto n = r_.Child(item, "tows", false);
    if (!n) return;
    auto v = r_.Number(*n, "tows");
    if (!v) return;
    if (*v != std::floor(*v) || *v < 1 || *v > scene_.head.afp.tows) {
      Bad(*n, "ply tows must be a whole number from 1 to the head's " +
                  std::to_string(scene_.head.afp.tows));
      return;
    }
    ply.tows = static_cast<int>(*v);
  }

  // `material:`: a name among the scene's materials (read before the plies).
  void ReadMaterial(const YAML::Node& item, PlySpec& ply) {
    auto n = r_.Child(item, "material", false);
    if (!n) return;
    auto s = r_.String(*n, "ply material");
    if (!s) return;
    for (const MaterialSpec& m : scene_.materials) {
      if (m.name == *s) {
        ply.material = m.name;
        ply.thickness_mm = m.ply_thickness_mm;
        ply.areal_weight_g_m2 = m.areal_weight_g_m2;
        return;
      }
    }
    Bad(*n, "ply '" + ply.name + "' names material '" + *s + "', not among the scene's materials");
  }

  std::optional<Eigen::Vector3d> Vec3(const YAML::Node& map, std::string_view key, bool length) {
    auto n = r_.Child(map, key, true);
    if (!n) return std::nullopt;
    auto v = length ? r_.Vector(*n, 3, key, unit_) : r_.Vector(*n, 3, key);
    if (!v) return std::nullopt;
    return Eigen::Vector3d(*v);
  }

  bool ReadReference(const YAML::Node& item, PlySpec& ply) {
    auto ref = r_.Child(item, "reference", true);
    if (!ref || !r_.ExpectMap(*ref, "reference")) return false;
    r_.CheckKeys(*ref, {"origin", "direction", "projection", "path"}, "ply reference");
    Choice<bool>(*ref, "path", {{"projected", false}, {"geodesic", true}}, ply.geodesic_reference);
    auto origin = Vec3(*ref, "origin", true);
    auto direction = Vec3(*ref, "direction", false);
    if (!origin || !direction || scene_.surface == nullptr) return false;
    if (direction->norm() < 1e-12) {
      Bad(*r_.Child(*ref, "direction", true), "reference direction must not be zero");
      return false;
    }
    ply.origin_mm = *origin;
    ply.direction = direction->normalized();
    const geom::SurfaceProjection foot = scene_.surface->Project(*origin);
    if (!foot.inside_domain) {
      Bad(*r_.Child(*ref, "origin", true), "reference origin does not project onto the surface");
      return false;
    }
    ply.projection = -foot.normal;
    if (r_.Child(*ref, "projection", false)) {
      auto p = Vec3(*ref, "projection", false);
      if (!p) return false;
      if (p->norm() < 1e-12) {
        Bad(*r_.Child(*ref, "projection", true), "reference projection must not be zero");
        return false;
      }
      ply.projection = p->normalized();
    }
    if (std::abs(ply.direction.dot(foot.normal)) > 1.0 - 1e-9) {
      Bad(*r_.Child(*ref, "direction", true), "reference direction runs along the surface normal");
      return false;
    }
    return true;
  }

  void ReadBoundary(const YAML::Node& item, PlySpec& ply) {
    auto uv_node = r_.Child(item, "boundary_uv", false);
    auto xyz_node = r_.Child(item, "boundary", false);
    if (uv_node.has_value() == xyz_node.has_value()) {
      Bad(item, "a ply needs exactly one of boundary_uv and boundary");
      return;
    }
    const YAML::Node& list = uv_node ? *uv_node : *xyz_node;
    if (!list.IsSequence() || list.size() < 3) {
      Bad(list, "a ply boundary needs at least 3 points");
      return;
    }
    if (list.size() > 100000) {
      Bad(list, "a ply boundary has more than 100000 points");
      return;
    }
    const geom::Surface& s = *scene_.surface;
    const geom::Domain2 domain = s.Domain();
    for (const auto& pt : list) {
      Eigen::Vector2d uv;
      if (uv_node) {
        auto v = r_.Vector(pt, 2, "boundary_uv point", unit_);
        if (!v) return;
        uv = *v;
      } else {
        auto v = r_.Vector(pt, 3, "boundary point", unit_);
        if (!v) return;
        Eigen::Vector3d hit;
        if (!s.IntersectLine(*v, ply.projection, hit)) {
          Bad(pt, "ply boundary point does not project onto the surface along the projection");
          return;
        }
        const geom::SurfaceProjection foot = s.Project(hit);
        if (!foot.inside_domain || (foot.point - hit).norm() > 1e-3) {
          Bad(pt, "ply boundary point does not project onto the surface along the projection");
          return;
        }
        uv = foot.uv;
      }
      if (!domain.Contains(uv, 1e-6)) {
        Bad(pt, "ply boundary point lies off the surface (outside its (u, v) domain)");
        return;
      }
      ply.boundary_uv.push_back(uv);
    }
    const double area = geom::SignedArea(ply.boundary_uv);
    if (std::abs(area) < 1e-6) {
      Bad(list, "ply boundary encloses no area");
      return;
    }
    if (geom::SelfCrossing(ply.boundary_uv)) {
      Bad(list, "ply boundary crosses itself");
      return;
    }
    if (area < 0) std::reverse(ply.boundary_uv.begin(), ply.boundary_uv.end());
  }

  YamlReader& r_;
  LengthUnit unit_;
  const Scene& scene_;
};

}  // namespace

static void ReadMaterials(YamlReader& r, const YAML::Node& root, LengthUnit unit, Scene& scene) {
  auto list = r.Child(root, "materials", false);
  if (!list) return;
  if (!list->IsSequence() || list->size() == 0) {
    r.Error(*list, "bad-material", "materials must be a non-empty list");
    return;
  }
  std::set<std::string> names;
  for (const auto& item : *list) {
    if (!r.ExpectMap(item, "a material")) continue;
    r.CheckKeys(item, {"name", "ply_thickness", "areal_weight_g_m2"}, "material");
    MaterialSpec m;
    m.where = r.At(item);
    const std::size_t errors = r.Sink().ErrorCount();
    if (auto n = r.Child(item, "name", true)) {
      if (auto s = r.String(*n, "material name")) {
        m.name = *s;
        if (!NameOk(*s)) {
          r.Error(*n, "bad-material",
                  "material name '" + *s + "' must be letters, digits, '_' or '-'");
        }
        if (!names.insert(*s).second) {
          r.Error(*n, "bad-material", "material '" + *s + "' is defined twice");
        }
      }
    }
    if (auto n = r.Child(item, "ply_thickness", true)) {
      if (auto v = r.Length(*n, unit, "ply_thickness"); v && r.Positive(*n, *v, "ply_thickness")) {
        m.ply_thickness_mm = *v;
      }
    }
    if (auto n = r.Child(item, "areal_weight_g_m2", true)) {
      if (auto v = r.Number(*n, "areal_weight_g_m2");
          v && r.Positive(*n, *v, "areal_weight_g_m2")) {
        m.areal_weight_g_m2 = *v;
      }
    }
    if (r.Sink().ErrorCount() == errors) scene.materials.push_back(std::move(m));
  }
}

void ReadPlies(YamlReader& r, const YAML::Node& root, LengthUnit unit, Scene& scene) {
  ReadMaterials(r, root, unit, scene);
  auto list = r.Child(root, "plies", false);
  if (!list) return;
  if (!list->IsSequence() || list->size() == 0) {
    r.Error(*list, "bad-ply", "plies must be a non-empty list");
    return;
  }
  if (list->size() > 1000) {
    r.Error(*list, "bad-ply", "a scene has at most 1000 plies");
    return;
  }
  PlyReader reader(r, unit, scene);
  std::set<std::string> names;
  for (const auto& item : *list) {
    if (auto ply = reader.Read(item, names)) scene.plies.push_back(std::move(*ply));
  }
}

}  // namespace stitchsim::scene::detail
