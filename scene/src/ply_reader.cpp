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

bool SceneNameOk(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

namespace {

std::optional<Eigen::Vector3d> ReferenceVec3(YamlReader& r, const YAML::Node& map,
                                             std::string_view key, std::optional<LengthUnit> unit) {
  auto n = r.Child(map, key, true);
  if (!n) return std::nullopt;
  auto v = r.Vector(*n, 3, key, unit);
  if (!v) return std::nullopt;
  return Eigen::Vector3d(*v);
}

class PlyReader {
 public:
  PlyReader(YamlReader& r, LengthUnit unit, const Scene& scene, const InlinePly* inline_ply)
      : r_(r), unit_(unit), scene_(scene), inline_(inline_ply) {}

  std::optional<PlySpec> Read(const YAML::Node& item, std::set<std::string>& names) {
    if (!r_.ExpectMap(item, "a ply")) return std::nullopt;
    if (inline_ != nullptr) {  // a laminate's stack entry: no name; its material and thickness
      r_.CheckKeys(item,
                   {"angle_deg", "reference", "boundary_uv", "boundary", "rule", "method",
                    "coverage", "tows", "material", "thickness"},
                   "laminate stack ply");
    } else {
      r_.CheckKeys(item,
                   {"name", "angle_deg", "reference", "boundary_uv", "boundary", "rule", "method",
                    "coverage", "tows", "material"},
                   "ply");
    }
    PlySpec ply;
    ply.where = r_.At(item);
    const std::size_t errors = r_.Sink().ErrorCount();
    if (inline_ != nullptr) {
      ply.name = inline_->name;
    } else if (auto n = r_.Child(item, "name", true)) {
      if (auto s = r_.String(*n, "ply name")) {
        ply.name = *s;
        if (!SceneNameOk(*s)) Bad(*n, "ply name '" + *s + "' must be letters, digits, '_' or '-'");
        if (!names.insert(*s).second) Bad(*n, "ply '" + *s + "' is defined twice");
      }
    }
    if (auto n = r_.Child(item, "angle_deg", false)) {
      if (auto v = r_.Number(*n, "angle_deg")) ply.angle_rad = *v * kDeg;
    }
    ReadEnums(item, ply);
    ReadTows(item, ply);
    if (inline_ == nullptr) ReadMaterial(item, ply);  // a stack entry's is the laminate's
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

  bool ReadReference(const YAML::Node& item, PlySpec& ply) {
    std::optional<YAML::Node> ref = r_.Child(item, "reference", inline_ == nullptr);
    if (!ref) {  // an inline ply without a reference of its own: the laminate's rosette
      if (inline_ == nullptr || scene_.surface == nullptr) return false;
      ply.origin_mm = inline_->rosette.origin_mm;
      ply.direction = inline_->rosette.direction;
      ply.projection = inline_->rosette.projection;
      return true;
    }
    if (!r_.ExpectMap(*ref, "reference")) return false;
    r_.CheckKeys(*ref, {"origin", "direction", "projection", "path"}, "ply reference");
    Choice<ReferencePath>(*ref, "path",
                          {{"projected", ReferencePath::kProjected},
                           {"geodesic", ReferencePath::kGeodesic},
                           {"constant_angle", ReferencePath::kConstantAngle}},
                          ply.reference_path);
    if (scene_.surface == nullptr) return false;
    auto axes = ReadReferenceAxes(r_, *ref, unit_, *scene_.surface, "bad-ply");
    if (!axes) return false;
    ply.origin_mm = axes->origin_mm;
    ply.direction = axes->direction;
    ply.projection = axes->projection;
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
  const InlinePly* inline_;  ///< set for a laminate's inline ply
};

}  // namespace

std::optional<ReferenceAxes> ReadReferenceAxes(YamlReader& r, const YAML::Node& ref,
                                               LengthUnit unit, const geom::Surface& surface,
                                               std::string_view code) {
  auto origin = ReferenceVec3(r, ref, "origin", unit);
  auto direction = ReferenceVec3(r, ref, "direction", std::nullopt);
  if (!origin || !direction) return std::nullopt;
  const auto bad = [&](std::string_view key, std::string message) {
    r.Error(*r.Child(ref, key, true), code, std::move(message));
    return std::nullopt;
  };
  if (direction->norm() < 1e-12) return bad("direction", "reference direction must not be zero");
  ReferenceAxes axes;
  axes.origin_mm = *origin;
  axes.direction = direction->normalized();
  const geom::SurfaceProjection foot = surface.Project(*origin);
  if (!foot.inside_domain) {
    return bad("origin", "reference origin does not project onto the surface");
  }
  axes.projection = -foot.normal;
  if (r.Child(ref, "projection", false)) {
    auto p = ReferenceVec3(r, ref, "projection", std::nullopt);
    if (!p) return std::nullopt;
    if (p->norm() < 1e-12) return bad("projection", "reference projection must not be zero");
    axes.projection = p->normalized();
  }
  if (std::abs(axes.direction.dot(foot.normal)) > 1.0 - 1e-9) {
    return bad("direction", "reference direction runs along the surface normal");
  }
  if (std::abs(axes.direction.dot(axes.projection)) > 1.0 - 1e-9) {
    return bad("direction", "reference direction runs along the projection");
  }
  return axes;
}

std::optional<PlySpec> ReadInlinePly(YamlReader& r, const YAML::Node& item, LengthUnit unit,
                                     const Scene& scene, const InlinePly& inline_ply) {
  std::set<std::string> names;
  return PlyReader(r, unit, scene, &inline_ply).Read(item, names);
}

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
        if (!SceneNameOk(*s)) {
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

std::optional<YAML::Node> SceneList(YamlReader& r, const YAML::Node& root, std::string_view key,
                                    std::string_view code, std::size_t most) {
  auto list = r.Child(root, key, false);
  if (!list) return std::nullopt;
  if (!list->IsSequence() || list->size() == 0) {
    r.Error(*list, code, std::string(key) + " must be a non-empty list");
    return std::nullopt;
  }
  if (list->size() > most) {
    r.Error(*list, code, "a scene has at most " + std::to_string(most) + " " + std::string(key));
    return std::nullopt;
  }
  return list;
}

void ReadPlies(YamlReader& r, const YAML::Node& root, LengthUnit unit, Scene& scene) {
  ReadMaterials(r, root, unit, scene);
  auto list = SceneList(r, root, "plies", "bad-ply", 1000);
  if (!list) return;
  PlyReader reader(r, unit, scene, nullptr);
  std::set<std::string> names;
  for (const auto& item : *list) {
    if (auto ply = reader.Read(item, names)) scene.plies.push_back(std::move(*ply));
  }
}

}  // namespace stitchsim::scene::detail
