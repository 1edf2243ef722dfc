#include "cad_surface_reader.h"

#include <vector>

#include "stitchsim/geom/cad_surface.h"

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

}  // namespace

bool IsCadSurfaceType(const std::string& type) {
  return type == "bspline" || type == "step" || type == "iges";
}

std::unique_ptr<geom::Surface> ReadCadSurface(YamlReader& r, const YAML::Node& s,
                                              const std::string& type, LengthUnit unit,
                                              const FileRefPolicy& files) {
  if (type == "bspline") return ReadBSpline(r, s, unit);
  return ReadPartFace(r, s, type, files);
}

}  // namespace stitchsim::scene::detail
