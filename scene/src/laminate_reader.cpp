#include "laminate_reader.h"

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "ply_reader.h"

namespace stitchsim::scene::detail {
namespace {

class LaminateReader {
 public:
  LaminateReader(YamlReader& r, LengthUnit unit, Scene& scene)
      : r_(r), unit_(unit), scene_(scene) {}

  std::optional<LaminateSpec> Read(const YAML::Node& item, std::set<std::string>& names) {
    if (!r_.ExpectMap(item, "a laminate")) return std::nullopt;
    r_.CheckKeys(item, {"name", "rosette", "stagger", "stack"}, "laminate");
    LaminateSpec lam;
    lam.where = r_.At(item);
    const std::size_t errors = r_.Sink().ErrorCount();
    if (auto n = r_.Child(item, "name", true)) {
      if (auto s = r_.String(*n, "laminate name")) {
        lam.name = *s;
        if (!SceneNameOk(*s)) {
          Bad(*n, "laminate name '" + *s + "' must be letters, digits, '_' or '-'");
        }
        if (!names.insert(*s).second) Bad(*n, "laminate '" + *s + "' is defined twice");
      }
    }
    if (scene_.head.kind != HeadKind::kAfp) {
      Bad(item, "laminate '" + lam.name + "' needs an AFP head; head '" + scene_.head.name +
                    "' places no tows");
      return std::nullopt;
    }
    const bool rosette_ok = ReadRosette(item, lam);
    ReadStagger(item, lam);
    if (rosette_ok) ReadStack(item, lam);
    if (r_.Sink().ErrorCount() > errors) return std::nullopt;
    return lam;
  }

 private:
  void Bad(const YAML::Node& n, std::string message) {
    r_.Error(n, "bad-laminate", std::move(message));
  }

  bool ReadRosette(const YAML::Node& item, LaminateSpec& lam) {
    auto n = r_.Child(item, "rosette", true);
    if (!n || !r_.ExpectMap(*n, "rosette") || scene_.surface == nullptr) return false;
    r_.CheckKeys(*n, {"origin", "direction", "projection"}, "laminate rosette");
    auto axes = ReadReferenceAxes(r_, *n, unit_, *scene_.surface, "bad-laminate");
    if (!axes) return false;
    lam.rosette.origin_mm = axes->origin_mm;
    lam.rosette.direction = axes->direction;
    lam.rosette.projection = axes->projection;
    return true;
  }

  void ReadStagger(const YAML::Node& item, LaminateSpec& lam) {
    auto n = r_.Child(item, "stagger", true);
    if (!n || !r_.ExpectMap(*n, "stagger")) return;
    r_.CheckKeys(*n, {"offset", "plies_before_repeat"}, "laminate stagger");
    if (auto o = r_.Child(*n, "offset", true)) {
      if (auto v = r_.Length(*o, unit_, "stagger.offset")) {
        const double course_mm = scene_.head.afp.tows * scene_.head.afp.tow_width_mm;
        if (*v < 0.0 || *v > course_mm) {
          Bad(*o, "stagger offset " + std::to_string(*v) +
                      " mm must lie from 0 to a course's width, " + std::to_string(course_mm) +
                      " mm (the head's " + std::to_string(scene_.head.afp.tows) + " tows)");
        } else {
          lam.stagger_offset_mm = *v;
        }
      }
    }
    if (auto p = r_.Child(*n, "plies_before_repeat", true)) {
      if (auto v = r_.Number(*p, "stagger.plies_before_repeat")) {
        if (*v != std::floor(*v) || *v < 1 || *v > 1000) {
          Bad(*p, "stagger plies_before_repeat must be a whole number from 1 to 1000");
        } else {
          lam.stagger_plies_before_repeat = static_cast<int>(*v);
        }
      }
    }
  }

  void ReadStack(const YAML::Node& item, LaminateSpec& lam) {
    auto list = r_.Child(item, "stack", true);
    if (!list) return;
    if (!list->IsSequence() || list->size() == 0) {
      Bad(*list, "laminate '" + lam.name + "' needs a non-empty stack (a list of plies)");
      return;
    }
    if (list->size() > 1000) {
      Bad(*list, "a laminate stack has at most 1000 plies");
      return;
    }
    for (std::size_t i = 0; i < list->size(); ++i) {
      const YAML::Node entry = (*list)[i];
      LaminateStackEntry e;
      e.where = r_.At(entry);
      if (entry.IsScalar()) {
        if (auto ply = NamedPly(entry, lam.name)) {
          e.ply = *ply;
          if (ApplyEntryData(entry, e)) lam.stack.push_back(std::move(e));
        }
        continue;
      }
      if (!r_.ExpectMap(entry, "a laminate stack entry")) continue;
      if (!ReadEntryData(entry, e)) continue;
      if (auto named = r_.Child(entry, "ply", false)) {
        r_.CheckKeys(entry, {"ply", "material", "thickness"}, "laminate stack entry");
        auto ply = NamedPly(*named, lam.name);
        if (!ply) continue;
        e.ply = *ply;
      } else {
        const InlinePly how{lam.name + "/" + std::to_string(i + 1),
                            {lam.rosette.origin_mm, lam.rosette.direction, lam.rosette.projection}};
        auto ply = ReadInlinePly(r_, entry, unit_, scene_, how);
        if (!ply) continue;
        e.ply = scene_.plies.size();
        e.inline_ply = true;
        scene_.plies.push_back(std::move(*ply));
      }
      if (!ApplyEntryData(entry, e)) continue;
      lam.stack.push_back(std::move(e));
    }
  }

  // The index in Scene::plies of the `plies:` entry named at `n`; else reported.
  std::optional<std::size_t> NamedPly(const YAML::Node& n, const std::string& laminate) {
    auto s = r_.String(n, "stack ply name");
    if (!s) return std::nullopt;
    for (std::size_t i = 0; i < named_plies_; ++i) {
      if (scene_.plies[i].name == *s) return i;
    }
    Bad(n, "laminate '" + laminate + "' stacks unknown ply '" + *s + "' (not in plies:)");
    return std::nullopt;
  }

  // The entry's `material` and `thickness` into `e`; false when one is bad (reported).
  bool ReadEntryData(const YAML::Node& entry, LaminateStackEntry& e) {
    bool ok = true;
    if (auto m = r_.Child(entry, "material", false)) {
      if (auto s = r_.String(*m, "material")) {
        e.material = *s;
        if (!SceneNameOk(*s)) {
          Bad(*m, "material name '" + *s + "' must be letters, digits, '_' or '-'");
          ok = false;
        }
      } else {
        ok = false;
      }
    }
    if (auto t = r_.Child(entry, "thickness", false)) {
      auto v = r_.Length(*t, unit_, "thickness");
      if (!v) return false;
      if (*v <= 0.0) {
        Bad(*t, "ply thickness must be greater than 0, got " + std::to_string(*v) + " mm");
        return false;
      }
      e.thickness_mm = *v;
    }
    return ok;
  }

  // The entry's material and thickness onto its ply in Scene::plies (a material's data, then
  // the entry's own thickness over it): every reader of a ply's thickness reads the ply. False
  // (reported) for an unknown material, or a named ply stacked with two thicknesses.
  bool ApplyEntryData(const YAML::Node& entry, const LaminateStackEntry& e) {
    PlySpec& ply = scene_.plies[e.ply];
    if (!e.material.empty()) {
      const MaterialSpec* found = nullptr;
      for (const MaterialSpec& m : scene_.materials) {
        if (m.name == e.material) found = &m;
      }
      if (found == nullptr) {
        Bad(entry["material"], "laminate stack entry names material '" + e.material +
                                   "', not among the scene's materials");
        return false;
      }
      ply.material = found->name;
      ply.thickness_mm = found->ply_thickness_mm;
      ply.areal_weight_g_m2 = found->areal_weight_g_m2;
    }
    if (e.thickness_mm) ply.thickness_mm = *e.thickness_mm;
    const auto [it, first] = stacked_thickness_.try_emplace(e.ply, ply.thickness_mm);
    if (!first && std::abs(it->second - ply.thickness_mm) > 1e-12) {
      Bad(entry, "ply '" + ply.name + "' is stacked with two thicknesses (" +
                     std::to_string(it->second) + " and " + std::to_string(ply.thickness_mm) +
                     " mm)");
      return false;
    }
    return true;
  }

  YamlReader& r_;
  LengthUnit unit_;
  /// The thickness each stacked ply was given (a named ply may be stacked more than once).
  std::map<std::size_t, double> stacked_thickness_;
  Scene& scene_;
  /// The `plies:` entries (read before the laminates); a stack may name only these.
  const std::size_t named_plies_ = scene_.plies.size();
};

}  // namespace

void ReadLaminates(YamlReader& r, const YAML::Node& root, LengthUnit unit, Scene& scene) {
  auto list = SceneList(r, root, "laminates", "bad-laminate", 100);
  if (!list) return;
  LaminateReader reader(r, unit, scene);
  std::set<std::string> names;
  for (const auto& item : *list) {
    if (auto lam = reader.Read(item, names)) scene.laminates.push_back(std::move(*lam));
  }
}

}  // namespace stitchsim::scene::detail
