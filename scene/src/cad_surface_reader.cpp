#include "cad_surface_reader.h"

#include <cmath>
#include <initializer_list>
#include <vector>

#include "stitchsim/geom/cad_surface.h"
#include "stitchsim/geom/naca.h"
#include "stitchsim/geom/wing_surface.h"

namespace stitchsim::scene::detail {
namespace {

// A list of numbers of any length >= 1 (knots, multiplicities, a weights row).
std::optional<std::vector<double>> Numbers(YamlReader& r, const YAML::Node& n,
                                           std::string_view what) {
  if (!n.IsSequence() || n.size() == 0) {
    r.Error(n, "type", std::string(what) + " must be a non-empty list of numbers");
    return std::nullopt;
  }
  auto v = r.Vector(n, static_cast<int>(n.size()), what);
  if (!v) return std::nullopt;
  return std::vector<double>(v->data(), v->data() + v->size());
}

// Optional knots_<d> with multiplicities_<d>: both or neither.
bool ReadKnots(YamlReader& r, const YAML::Node& s, const std::string& d, std::vector<double>& knots,
               std::vector<int>& mults) {
  auto kn = r.Child(s, "knots_" + d, false);
  auto mn = r.Child(s, "multiplicities_" + d, false);
  if (!kn && !mn) return true;
  if (!kn || !mn) {
    r.Error(kn ? *kn : *mn, "missing-key",
            "knots_" + d + " and multiplicities_" + d + " go together");
    return false;
  }
  auto k = Numbers(r, *kn, "knots_" + d);
  if (!k) return false;
  knots = *k;
  if (!mn->IsSequence() || mn->size() == 0) {
    r.Error(*mn, "type", "multiplicities_" + d + " must be a non-empty list of whole numbers");
    return false;
  }
  for (const auto& m : *mn) {
    auto i = r.Integer(m, "multiplicities_" + d, 1, 10);
    if (!i) return false;
    mults.push_back(static_cast<int>(*i));
  }
  return true;
}

bool ReadNet(YamlReader& r, const YAML::Node& s, LengthUnit unit, geom::BSplineSpec& spec) {
  auto pn = r.Child(s, "poles", true);
  if (!pn) return false;
  if (!pn->IsSequence() || pn->size() == 0) {
    r.Error(*pn, "type", "poles must be a list of rows, each a list of [x, y, z] points");
    return false;
  }
  for (const auto& row : *pn) {
    if (!row.IsSequence() || row.size() == 0) {
      r.Error(row, "type", "a poles row must be a list of [x, y, z] points");
      return false;
    }
    spec.poles.emplace_back();
    for (const auto& q : row) {
      auto v = r.Vector(q, 3, "pole", unit);
      if (!v) return false;
      spec.poles.back().push_back(*v);
    }
  }
  if (auto wn = r.Child(s, "weights", false)) {
    if (!wn->IsSequence() || wn->size() != spec.poles.size()) {
      r.Error(*wn, "type", "weights must have one row per poles row");
      return false;
    }
    for (const auto& row : *wn) {
      auto w = Numbers(r, row, "weights row");
      if (!w) return false;
      spec.weights.push_back(*w);
    }
  }
  return true;
}

std::unique_ptr<geom::Surface> ReadBSpline(YamlReader& r, const YAML::Node& s, LengthUnit unit) {
  r.CheckKeys(s,
              {"type", "degree", "poles", "weights", "knots_u", "multiplicities_u", "knots_v",
               "multiplicities_v", "flip_normal"},
              "bspline surface");
  geom::BSplineSpec spec;
  auto dn = r.Child(s, "degree", true);
  if (!dn) return nullptr;
  auto deg = r.Vector(*dn, 2, "degree");
  if (!deg) return nullptr;
  for (int i = 0; i < 2; ++i) {
    if ((*deg)[i] != static_cast<int>((*deg)[i]) || (*deg)[i] < 1 || (*deg)[i] > 9) {
      r.Error(*dn, "out-of-range", "degree must be two whole numbers in 1..9 (u, v)");
      return nullptr;
    }
  }
  spec.degree_u = static_cast<int>((*deg)[0]);
  spec.degree_v = static_cast<int>((*deg)[1]);
  if (!ReadNet(r, s, unit, spec) || !ReadKnots(r, s, "u", spec.knots_u, spec.mults_u) ||
      !ReadKnots(r, s, "v", spec.knots_v, spec.mults_v)) {
    return nullptr;
  }
  if (auto f = r.Child(s, "flip_normal", false)) {
    auto b = r.Bool(*f, "flip_normal");
    if (!b) return nullptr;
    spec.flip_normal = *b;
  }
  std::string err;
  auto out = geom::MakeBSplineSurface(spec, err);
  if (!out) r.Error(s, "bad-bspline", "bspline surface: " + err);
  return out;
}

std::unique_ptr<geom::Surface> ReadPartFace(YamlReader& r, const YAML::Node& s,
                                            const std::string& type, const FileRefPolicy& files) {
  r.CheckKeys(s, {"type", "file", "face", "flip_normal"}, type + " surface");
  auto fn = r.Child(s, "file", true);
  auto facen = r.Child(s, "face", true);
  if (!fn || !facen) return nullptr;
  auto f = r.String(*fn, "surface.file");
  if (!f) return nullptr;
  geom::CadFaceRef ref;
  // A plain (unquoted) number is an index; anything else, "3" quoted too, a face name.
  const std::string text = facen->IsScalar() ? facen->Scalar() : "";
  const bool number = facen->IsScalar() && facen->Tag() == "?" && !text.empty() &&
                      text.find_first_not_of("-+0123456789.eE") == std::string::npos;
  if (number) {
    auto index = r.Integer(*facen, "face", 0, 1000000);
    if (!index) return nullptr;
    ref.index = static_cast<int>(*index);
  } else if (auto name = r.String(*facen, "face")) {
    if (name->empty()) {
      r.Error(*facen, "bad-value", "face must be an index (from 0) or a face name");
      return nullptr;
    }
    ref.name = *name;
  } else {
    return nullptr;
  }
  if (auto fl = r.Child(s, "flip_normal", false)) {
    auto b = r.Bool(*fl, "flip_normal");
    if (!b) return nullptr;
    ref.flip_normal = *b;
  }
  const auto path = r.ReferencedFile(*fn, *f, files, type == "step" ? "STEP file" : "IGES file");
  if (!path) return nullptr;
  std::string err;
  auto out = geom::ReadCadFace(
      *path, type == "step" ? geom::CadFormat::kStep : geom::CadFormat::kIges, ref, err);
  if (!out) {
    const bool about_face = err.find("out of range") != std::string::npos ||
                            err.find("no face named") != std::string::npos;
    r.Error(about_face ? *facen : *fn, "bad-cad-file", err);
  }
  return out;
}

// A wing section map {naca: "23014", chord: ...}: its code and chord (mm) into `code`, `chord`.
bool ReadSection(YamlReader& r, const YAML::Node& s, const char* key, LengthUnit unit,
                 std::string& code, double& chord_mm) {
  auto n = r.Child(s, key, true);
  if (!n || !r.ExpectMap(*n, key)) return false;
  r.CheckKeys(*n, {"naca", "chord"}, std::string("wing ") + key);
  auto cn = r.Child(*n, "naca", true);
  auto ln = r.Child(*n, "chord", true);
  if (!cn || !ln) return false;
  auto text = r.String(*cn, "naca");
  if (!text) return false;
  std::string error;
  if (!geom::ParseNaca(*text, error)) {
    r.Error(*cn, "bad-value", std::string("wing ") + key + " section: " + error);
    return false;
  }
  code = *text;
  auto chord = r.Length(*ln, unit, "chord");
  if (!chord || !r.Positive(*ln, *chord, std::string(key) + ".chord")) return false;
  chord_mm = *chord;
  return true;
}

// An optional angle in degrees, strictly inside (-90, 90), into radians.
bool ReadAngle(YamlReader& r, const YAML::Node& s, const char* key, double& rad) {
  auto n = r.Child(s, key, false);
  if (!n) return true;
  auto deg = r.Number(*n, key);
  if (!deg) return false;
  if (!(std::abs(*deg) < 90.0)) {
    r.Error(*n, "out-of-range", std::string(key) + " must lie strictly between -90 and 90");
    return false;
  }
  rad = DegToRad(*deg);
  return true;
}

// One of `names` at optional `key` (the first is the default); its index, or -1 reported.
int ReadChoice(YamlReader& r, const YAML::Node& s, const char* key,
               std::initializer_list<const char*> names) {
  auto n = r.Child(s, key, false);
  if (!n) return 0;
  auto text = r.String(*n, key);
  if (!text) return -1;
  int i = 0;
  std::string list;
  for (const char* name : names) {
    if (*text == name) return i;
    list += (i++ ? ", " : "") + std::string(name);
  }
  r.Error(*n, "bad-value", std::string(key) + " must be one of " + list + ", got '" + *text + "'");
  return -1;
}

std::unique_ptr<geom::Surface> ReadWing(YamlReader& r, const YAML::Node& s, LengthUnit unit) {
  r.CheckKeys(s,
              {"type", "root", "tip", "span", "sweep_deg", "dihedral_deg", "twist_deg",
               "trailing_edge", "skin"},
              "wing surface");
  geom::WingSpec spec;
  bool ok = ReadSection(r, s, "root", unit, spec.root_code, spec.root_chord_mm);
  ok = ReadSection(r, s, "tip", unit, spec.tip_code, spec.tip_chord_mm) && ok;
  if (auto n = r.Child(s, "span", true)) {
    auto span = r.Length(*n, unit, "span");
    ok = span && r.Positive(*n, *span, "span") && ok;
    if (span) spec.span_mm = *span;
  } else {
    ok = false;
  }
  ok = ReadAngle(r, s, "sweep_deg", spec.sweep_rad) && ok;
  ok = ReadAngle(r, s, "dihedral_deg", spec.dihedral_rad) && ok;
  ok = ReadAngle(r, s, "twist_deg", spec.washout_rad) && ok;
  const int edge = ReadChoice(r, s, "trailing_edge", {"closed", "open"});
  const int skin = ReadChoice(r, s, "skin", {"full", "upper", "lower"});
  if (!ok || edge < 0 || skin < 0) return nullptr;
  spec.trailing_edge = edge == 0 ? geom::TrailingEdge::kClosed : geom::TrailingEdge::kOpen;
  const geom::WingSkin skins[] = {geom::WingSkin::kFull, geom::WingSkin::kUpper,
                                  geom::WingSkin::kLower};
  std::string err;
  geom::WingSurface w = geom::MakeWingSurface(spec, skins[skin], err);
  if (!w.surface) r.Error(s, "bad-wing", "wing surface: " + err);
  return std::move(w.surface);
}

}  // namespace

bool IsCadSurfaceType(const std::string& type) {
  return type == "bspline" || type == "step" || type == "iges" || type == "wing";
}

std::unique_ptr<geom::Surface> ReadCadSurface(YamlReader& r, const YAML::Node& s,
                                              const std::string& type, LengthUnit unit,
                                              const FileRefPolicy& files) {
  if (type == "bspline") return ReadBSpline(r, s, unit);
  if (type == "wing") return ReadWing(r, s, unit);
  return ReadPartFace(r, s, type, files);
}

}  // namespace stitchsim::scene::detail
