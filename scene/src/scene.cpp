#include "stitchsim/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "cad_surface_reader.h"
#include "laminate_reader.h"
#include "limit_map.h"
#include "ply_reader.h"
#include "scene_bounds.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/geom/stl.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene {
namespace {

class SceneLoader {
 public:
  SceneLoader(const std::filesystem::path& file, DiagnosticSink& sink, const LoadOptions& options)
      : r_(file, sink, "scene"), sink_(sink), options_(options) {
    files_.roots = {file.has_parent_path() ? file.parent_path() : ".", ModelsDir()};
    files_.allow_outside = options.allow_outside_paths;
  }

  std::unique_ptr<Scene> Load() {
    const std::size_t errors_before = sink_.ErrorCount();
    auto root = r_.LoadFile();
    if (!root) return nullptr;
    if (!r_.ExpectMap(*root, "a scene")) return nullptr;
    r_.CheckKeys(*root,
                 {"stitchsim_scene", "name", "description", "units", "head", "cell", "part",
                  "surface", "preform", "mold", "stitch", "constraints", "paths", "limits", "rail",
                  "raster", "plies", "laminates", "materials"},
                 "scene");
    auto scene = std::make_unique<Scene>();
    scene->file = r_.File();
    const auto dir = r_.File().parent_path();
    if (auto n = r_.Child(*root, "name", true)) {
      if (auto s = r_.String(*n, "name")) scene->name = *s;
    }
    if (auto n = r_.Child(*root, "units", true)) {
      if (auto s = r_.String(*n, "units")) {
        if (auto u = ParseLengthUnit(*s)) {
          scene->units = *u;
        } else {
          r_.Error(*n, "bad-unit", "units must be mm, in or m, got '" + *s + "'");
        }
      }
    }
    unit_ = scene->units;
    // Cell model: default is the bundled ISAAC-like cell.
    scene->cell_urdf = DataDir() / "models" / "isaac_cell.urdf";
    scene->cell_mjcf = DataDir() / "models" / "isaac_cell.xml";
    if (auto n = r_.Child(*root, "cell", false); n && r_.ExpectMap(*n, "cell")) {
      r_.CheckKeys(*n, {"urdf", "mjcf", "omit"}, "cell");
      if (auto u = r_.Child(*n, "urdf", false)) {
        if (auto s = r_.String(*u, "cell.urdf")) RequireFile(*u, *s, "cell URDF", scene->cell_urdf);
      }
      if (auto m = r_.Child(*n, "mjcf", false)) {
        if (auto s = r_.String(*m, "cell.mjcf")) RequireFile(*m, *s, "cell MJCF", scene->cell_mjcf);
      }
      if (auto o = r_.Child(*n, "omit", false)) ReadOmit(*o, *scene);
    }
    if (auto n = r_.Child(*root, "head", true)) {
      if (auto s = r_.String(*n, "head")) {
        const auto head_file = ResolveHeadFile(*s, dir);
        std::error_code ec;
        if (!std::filesystem::exists(head_file, ec)) {
          r_.Error(*n, "unknown-head",
                   "unknown head '" + *s + "' (no head spec at " + head_file.string() + ")");
        } else if (std::filesystem::path(*s).has_extension() &&
                   !r_.ReferencedFile(*n, *s, files_, "head spec")) {
          // reported (a bare name is a bundled head, in the models folder)
        } else if (auto h = LoadHeadSpec(head_file, sink_, options_)) {
          scene->head = std::move(*h);
        }
      }
    }
    scene->preform_thickness_mm = scene->head.stitch.preform_thickness_mm;
    scene->nominal_stitch_length_mm = scene->head.stitch.nominal_length_mm;
    scene->limits = scene->head.limits;
    ReadPart(*root, *scene);
    ReadSurface(*root, *scene);
    ReadPreformAndMold(*root, *scene);
    ReadStitch(*root, *scene);
    ReadConstraints(*root, *scene);
    ReadPaths(*root, *scene);
    ReadLimits(*root, *scene);
    ReadRail(*root, *scene);
    ReadRaster(*root, *scene);
    detail::ReadPlies(r_, *root, unit_, *scene);
    detail::ReadLaminates(r_, *root, unit_, *scene);
    if (sink_.ErrorCount() > errors_before) return nullptr;
    return scene;
  }

 private:
  // The file `name` at `n` into `out` when it may be read (ReferencedFile); else reported.
  void RequireFile(const YAML::Node& n, const std::string& name, std::string_view what,
                   std::filesystem::path& out) {
    if (auto p = r_.ReferencedFile(n, name, files_, what)) out = *p;
  }

  std::optional<double> LengthKey(const YAML::Node& map, std::string_view key, bool required,
                                  bool positive) {
    auto n = r_.Child(map, key, required);
    if (!n) return std::nullopt;
    auto v = r_.Length(*n, unit_, key);
    if (v && positive && !r_.Positive(*n, *v, key)) return std::nullopt;
    return v;
  }

  std::optional<double> NumberKey(const YAML::Node& map, std::string_view key, bool required) {
    auto n = r_.Child(map, key, required);
    if (!n) return std::nullopt;
    return r_.Number(*n, key);
  }

  std::optional<Eigen::Vector2d> Point2(const YAML::Node& map, std::string_view key,
                                        bool required) {
    auto n = r_.Child(map, key, required);
    if (!n) return std::nullopt;
    auto v = r_.Vector(*n, 2, key, unit_);
    if (!v) return std::nullopt;
    return Eigen::Vector2d((*v)[0], (*v)[1]);
  }

  void ReadPart(const YAML::Node& root, Scene& scene) {
    auto part = r_.Child(root, "part", true);
    if (!part || !r_.ExpectMap(*part, "part")) return;
    r_.CheckKeys(*part, {"mount", "position", "rotation_deg"}, "part");
    if (auto n = r_.Child(*part, "mount", true)) {
      if (auto s = r_.String(*n, "part.mount")) {
        if (*s == "table") {
          scene.mount = Mount::kTable;
        } else if (*s == "rotator") {
          scene.mount = Mount::kRotator;
        } else {
          r_.Error(*n, "bad-value", "part.mount must be table or rotator, got '" + *s + "'");
        }
      }
    }
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();
    Eigen::Vector3d rot = Eigen::Vector3d::Zero();
    if (auto n = r_.Child(*part, "position", false)) {
      if (auto v = r_.Vector(*n, 3, "part.position", unit_)) pos = *v;
    }
    if (auto n = r_.Child(*part, "rotation_deg", false)) {
      if (auto v = r_.Vector(*n, 3, "part.rotation_deg")) rot = *v;
    }
    scene.mount_to_part_m.setIdentity();
    scene.mount_to_part_m.translation() = pos / 1000.0;
    scene.mount_to_part_m.linear() = geom::RotationFromEuler(geom::EulerOrder{}, rot * kDeg);
  }

  void ReadSurface(const YAML::Node& root, Scene& scene) {
    auto s = r_.Child(root, "surface", true);
    if (!s || !r_.ExpectMap(*s, "surface")) return;
    auto type_node = r_.Child(*s, "type", true);
    if (!type_node) return;
    auto type = r_.String(*type_node, "surface.type");
    if (!type) return;
    if (*type == "plane") {
      r_.CheckKeys(*s, {"type", "size"}, "plane surface");
      auto n = r_.Child(*s, "size", true);
      if (!n) return;
      auto v = r_.Vector(*n, 2, "surface.size", unit_);
      if (v && r_.Positive(*n, v->minCoeff(), "surface.size")) {
        scene.surface = geom::MakePlane((*v)[0], (*v)[1]);
      }
    } else if (*type == "cylinder") {
      r_.CheckKeys(*s, {"type", "radius", "side", "length", "arc_length"}, "cylinder surface");
      auto radius = LengthKey(*s, "radius", true, true);
      auto length = LengthKey(*s, "length", true, true);
      auto arc = LengthKey(*s, "arc_length", true, true);
      bool outside = true;
      if (auto n = r_.Child(*s, "side", true)) {
        if (auto side = r_.String(*n, "side")) {
          if (*side == "inside") {
            outside = false;
          } else if (*side != "outside") {
            r_.Error(*n, "bad-value", "side must be outside or inside, got '" + *side + "'");
            return;
          }
        }
      }
      if (radius && length && arc) {
        if (*arc >= 2 * kPi * *radius) {
          r_.Error(*s, "out-of-range", "arc_length must be less than the full circumference");
          return;
        }
        scene.surface = geom::MakeCylinder(*radius, outside, *length, *arc);
      }
    } else if (*type == "polynomial") {
      r_.CheckKeys(*s, {"type", "size", "coefficients"}, "polynomial surface");
      auto size_node = r_.Child(*s, "size", true);
      auto coeff_node = r_.Child(*s, "coefficients", true);
      if (!size_node || !coeff_node) return;
      auto size = r_.Vector(*size_node, 2, "surface.size", unit_);
      if (!size || !r_.Positive(*size_node, size->minCoeff(), "surface.size")) return;
      // z = sum c_ij x^i y^j in scene units; convert to mm: c_ij * u^(1-i-j).
      if (!coeff_node->IsSequence() || coeff_node->size() != 4) {
        r_.Error(*coeff_node, "type", "coefficients must be a 4x4 list (c[i][j] of x^i y^j)");
        return;
      }
      Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
      const double u = MmPer(unit_);
      for (int i = 0; i < 4; ++i) {
        auto row = r_.Vector((*coeff_node)[static_cast<std::size_t>(i)], 4, "coefficients row");
        if (!row) return;
        for (int j = 0; j < 4; ++j) c(i, j) = (*row)[j] * std::pow(u, 1 - i - j);
      }
      geom::Domain2 d;
      d.min = -Eigen::Vector2d((*size)[0], (*size)[1]) / 2;
      d.max = -d.min;
      scene.surface = geom::MakePolynomialHeightField(c, d);
    } else if (*type == "mesh") {
      r_.CheckKeys(*s, {"type", "file"}, "mesh surface");
      auto n = r_.Child(*s, "file", true);
      if (!n) return;
      auto f = r_.String(*n, "surface.file");
      if (!f) return;
      geom::TriangleMesh mesh;
      std::string err;
      const auto path = r_.ReferencedFile(*n, *f, files_, "STL file");
      if (!path) return;
      if (!geom::ReadStl(*path, MmPer(unit_), mesh, err)) {
        r_.Error(*n, "bad-mesh", err);
        return;
      }
      if (!detail::CheckMeshExtent(r_, *n, *path, mesh)) return;
      scene.surface = geom::MakeMeshSurface(std::move(mesh));
    } else if (detail::IsCadSurfaceType(*type)) {
      scene.surface = detail::ReadCadSurface(r_, *s, *type, unit_, files_);
    } else {
      r_.Error(
          *type_node, "bad-value",
          "surface.type must be plane, cylinder, polynomial, mesh, bspline, step, iges or wing, "
          "got '" +
              *type + "'");
    }
  }

  void ReadPreformAndMold(const YAML::Node& root, Scene& scene) {
    if (auto p = r_.Child(root, "preform", false); p && r_.ExpectMap(*p, "preform")) {
      r_.CheckKeys(*p, {"thickness"}, "preform");
      if (auto t = LengthKey(*p, "thickness", true, true)) scene.preform_thickness_mm = *t;
    }
    if (auto m = r_.Child(root, "mold", false); m && r_.ExpectMap(*m, "mold")) {
      r_.CheckKeys(*m, {"depth"}, "mold");
      if (auto t = LengthKey(*m, "depth", true, true)) scene.mold_depth_mm = *t;
    }
  }

  void ReadStitch(const YAML::Node& root, Scene& scene) {
    if (auto st = r_.Child(root, "stitch", false); st && r_.ExpectMap(*st, "stitch")) {
      r_.CheckKeys(*st, {"nominal_length"}, "stitch");
      if (auto l = LengthKey(*st, "nominal_length", true, true)) {
        scene.nominal_stitch_length_mm = *l;
      }
    }
  }

  void ReadConstraints(const YAML::Node& root, Scene& scene) {
    auto cs = r_.Child(root, "constraints", false);
    if (!cs) return;
    if (!cs->IsSequence()) {
      r_.Error(*cs, "type", "constraints must be a list");
      return;
    }
    std::set<std::string> names;
    for (const auto& item : *cs) {
      if (!r_.ExpectMap(item, "a constraint")) continue;
      Constraint c;
      c.where = r_.At(item);
      if (auto n = r_.Child(item, "name", true)) {
        if (auto s = r_.String(*n, "constraint name")) {
          c.name = *s;
          if (!names.insert(*s).second) {
            r_.Error(*n, "duplicate-name", "constraint '" + *s + "' is defined twice");
          }
        }
      }
      auto tn = r_.Child(item, "type", true);
      if (!tn) continue;
      auto type = r_.String(*tn, "constraint type");
      if (!type) continue;
      if (*type == "box") {
        r_.CheckKeys(item, {"name", "type", "center", "size", "rotation_deg"}, "box constraint");
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        Eigen::Vector3d rot = Eigen::Vector3d::Zero();
        if (auto n = r_.Child(item, "center", true)) {
          if (auto v = r_.Vector(*n, 3, "center", unit_)) centre = *v;
        }
        if (auto n = r_.Child(item, "size", true)) {
          if (auto v = r_.Vector(*n, 3, "size", unit_);
              v && r_.Positive(*n, v->minCoeff(), "size")) {
            c.size_mm = *v;
          }
        }
        if (auto n = r_.Child(item, "rotation_deg", false)) {
          if (auto v = r_.Vector(*n, 3, "rotation_deg")) rot = *v;
        }
        c.shape = Constraint::Shape::kBox;
        c.pose_mm.setIdentity();
        c.pose_mm.translation() = centre;
        c.pose_mm.linear() = geom::RotationFromEuler(geom::EulerOrder{}, rot * kDeg);
      } else if (*type == "mesh") {
        r_.CheckKeys(item, {"name", "type", "file"}, "mesh constraint");
        auto n = r_.Child(item, "file", true);
        if (!n) continue;
        auto f = r_.String(*n, "file");
        if (!f) continue;
        const auto path = r_.ReferencedFile(*n, *f, files_, "STL file");
        if (!path) continue;
        std::string err;
        if (!geom::ReadStl(*path, MmPer(unit_), c.mesh, err)) {
          r_.Error(*n, "bad-mesh", err);
          continue;
        }
        if (!detail::CheckMeshExtent(r_, *n, *path, c.mesh)) continue;
        c.shape = Constraint::Shape::kMesh;
      } else {
        r_.Error(*tn, "bad-value", "constraint type must be box or mesh, got '" + *type + "'");
        continue;
      }
      scene.constraints.push_back(std::move(c));
    }
  }

  void ReadPaths(const YAML::Node& root, Scene& scene) {
    auto ps = r_.Child(root, "paths", true);
    if (!ps) return;
    if (!ps->IsSequence() || ps->size() == 0) {
      r_.Error(*ps, "type", "paths must be a non-empty list");
      return;
    }
    if (ps->size() > static_cast<std::size_t>(limits::kMaxScenePaths)) {
      r_.Error(*ps, "too-many-paths",
               "the scene has " + std::to_string(ps->size()) + " paths, more than the limit of " +
                   std::to_string(limits::kMaxScenePaths) + " (docs/limits.md)");
      return;
    }
    std::set<std::string> names;
    for (const auto& item : *ps) {
      if (!r_.ExpectMap(item, "a path")) continue;
      PathSpec p;
      p.where = r_.At(item);
      if (auto n = r_.Child(item, "name", true)) {
        if (auto s = r_.String(*n, "path name")) {
          p.name = *s;
          if (!names.insert(*s).second) {
            r_.Error(*n, "duplicate-name", "path '" + *s + "' is defined twice");
          }
        }
      }
      auto tn = r_.Child(item, "type", true);
      if (!tn) continue;
      auto type = r_.String(*tn, "path type");
      if (!type) continue;
      p.type = *type;
      p.curve = std::make_unique<geom::Curve2>();
      if (!BuildCurve(item, *tn, *type, *p.curve)) continue;
      if (scene.surface && CheckInDomain(item, p, *scene.surface)) {
        detail::CheckStitchCount(r_, item, p, *scene.surface, scene.nominal_stitch_length_mm);
      }
      scene.paths.push_back(std::move(p));
    }
  }

  bool BuildCurve(const YAML::Node& item, const YAML::Node& type_node, const std::string& type,
                  geom::Curve2& curve) {
    if (type == "line") return BuildLine(item, curve);
    if (type == "arc" || type == "circle") return BuildArc(item, type, curve);
    if (type == "polyline") return BuildPolyline(item, curve);
    if (type == "slot") return BuildSlot(item, curve);
    r_.Error(type_node, "bad-value",
             "path type must be line, arc, circle, polyline or slot, got '" + type + "'");
    return false;
  }

  bool BuildLine(const YAML::Node& item, geom::Curve2& curve) {
    r_.CheckKeys(item, {"name", "type", "from", "to"}, "line path");
    auto a = Point2(item, "from", true);
    auto b = Point2(item, "to", true);
    if (!a || !b) return false;
    if ((*a - *b).norm() < 1e-9) {
      r_.Error(item, "degenerate-path", "line path has zero length");
      return false;
    }
    curve.Add(geom::MakeLineSegment(*a, *b), "line");
    return true;
  }

  // An arc (start_deg to end_deg) or a full circle (from start_deg, ccw or cw).
  bool BuildArc(const YAML::Node& item, const std::string& type, geom::Curve2& curve) {
    const bool circle = type == "circle";
    if (circle) {
      r_.CheckKeys(item, {"name", "type", "center", "radius", "start_deg", "direction"},
                   "circle path");
    } else {
      r_.CheckKeys(item, {"name", "type", "center", "radius", "start_deg", "end_deg"}, "arc path");
    }
    auto c = Point2(item, "center", true);
    auto radius = LengthKey(item, "radius", true, true);
    double start = 0.0;
    if (auto v = NumberKey(item, "start_deg", !circle)) start = *v;
    double end = start + 360.0;
    if (circle) {
      if (auto n = r_.Child(item, "direction", false)) {
        auto d = r_.String(*n, "direction");
        if (d && *d == "cw") {
          end = start - 360.0;
        } else if (d && *d != "ccw") {
          r_.Error(*n, "bad-value", "direction must be ccw or cw, got '" + *d + "'");
          return false;
        }
      }
    } else if (auto v = NumberKey(item, "end_deg", true)) {
      end = *v;
      if (std::abs(end - start) < 1e-9 || std::abs(end - start) > 360.0) {
        r_.Error(item, "degenerate-path", "arc sweep must be non-zero and at most 360 deg");
        return false;
      }
    } else {
      return false;
    }
    if (!c || !radius) return false;
    curve.Add(geom::MakeEllipticArc(*c, *radius, *radius, 0.0, start * kDeg, end * kDeg), type);
    return true;
  }

  bool BuildPolyline(const YAML::Node& item, geom::Curve2& curve) {
    r_.CheckKeys(item, {"name", "type", "points", "closed"}, "polyline path");
    auto n = r_.Child(item, "points", true);
    if (!n) return false;
    if (!n->IsSequence() || n->size() < 2) {
      r_.Error(*n, "type", "points must be a list of at least two [u, v] points");
      return false;
    }
    std::vector<Eigen::Vector2d> pts;
    for (const auto& pn : *n) {
      auto v = r_.Vector(pn, 2, "point", unit_);
      if (!v) return false;
      pts.emplace_back((*v)[0], (*v)[1]);
    }
    bool closed = false;
    if (auto cn = r_.Child(item, "closed", false)) {
      if (auto b = r_.Bool(*cn, "closed")) closed = *b;
    }
    if (closed) pts.push_back(pts.front());
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      if ((pts[i + 1] - pts[i]).norm() < 1e-9) {
        r_.Error((*n)[std::min(i + 1, n->size() - 1)], "degenerate-path",
                 "polyline has two equal consecutive points");
        return false;
      }
      curve.Add(geom::MakeLineSegment(pts[i], pts[i + 1]), "line");
    }
    return true;
  }

  bool BuildSlot(const YAML::Node& item, geom::Curve2& curve) {
    // Two parallel straights of `length`, `width` apart, joined at each end by a half
    // ellipse whose semi-axis along the slot is `end_radius` (across: width / 2).
    r_.CheckKeys(item, {"name", "type", "center", "length", "width", "end_radius", "angle_deg"},
                 "slot path");
    auto c = Point2(item, "center", true);
    auto length = LengthKey(item, "length", true, true);
    auto width = LengthKey(item, "width", true, true);
    auto end_r = LengthKey(item, "end_radius", true, true);
    double angle = 0.0;
    if (auto v = NumberKey(item, "angle_deg", false)) angle = *v;
    if (!c || !length || !width || !end_r) return false;
    const double th = angle * kDeg;
    const Eigen::Matrix2d rot = Eigen::Rotation2Dd(th).toRotationMatrix();
    const double hl = *length / 2;
    const double hw = *width / 2;
    auto P = [&](double x, double y) -> Eigen::Vector2d {
      return *c + rot * Eigen::Vector2d(x, y);
    };
    // Counter-clockwise: bottom straight (+x), right end, top straight (-x), left end.
    curve.Add(geom::MakeLineSegment(P(-hl, -hw), P(hl, -hw)), "straight");
    curve.Add(geom::MakeEllipticArc(P(hl, 0), *end_r, hw, th, -kPi / 2, kPi / 2), "end");
    curve.Add(geom::MakeLineSegment(P(hl, hw), P(-hl, hw)), "straight");
    curve.Add(geom::MakeEllipticArc(P(-hl, 0), *end_r, hw, th, kPi / 2, 3 * kPi / 2), "end");
    return true;
  }

  bool CheckInDomain(const YAML::Node& item, const PathSpec& p, const geom::Surface& surface) {
    const geom::Domain2 d = surface.Domain();
    for (std::size_t s = 0; s < p.curve->SegmentCount(); ++s) {
      for (int k = 0; k <= 32; ++k) {
        const Eigen::Vector2d uv = p.curve->Segment(s).At(k / 32.0);
        if (!d.Contains(uv, 1e-6)) {
          r_.Error(item, "path-off-surface",
                   "path '" + p.name + "' leaves the surface domain near (" +
                       std::to_string(uv.x() / MmPer(unit_)) + ", " +
                       std::to_string(uv.y() / MmPer(unit_)) + ") " + std::string(UnitName(unit_)));
          return false;
        }
      }
    }
    return true;
  }

  void ReadLimits(const YAML::Node& root, Scene& scene) {
    if (auto lim = r_.Child(root, "limits", false)) detail::ReadLimitMap(r_, *lim, scene.limits);
  }

  void ReadOmit(const YAML::Node& node, Scene& scene) {
    if (!node.IsSequence()) {
      r_.Error(node, "type", "cell.omit must be a list of fixtures (table, rotator)");
      return;
    }
    for (const auto& item : node) {
      auto s = r_.String(item, "cell.omit item");
      if (!s) continue;
      bool known = false;
      for (const auto& f : kCellFixtures) known = known || *s == f.name;
      if (!known) {
        r_.Error(item, "bad-value", "cell.omit: unknown fixture '" + *s + "' (table, rotator)");
      } else if (std::find(scene.omitted_fixtures.begin(), scene.omitted_fixtures.end(), *s) !=
                 scene.omitted_fixtures.end()) {
        r_.Error(item, "duplicate-name", "cell.omit names '" + *s + "' twice");
      } else {
        scene.omitted_fixtures.push_back(*s);
      }
    }
  }

  void ReadRaster(const YAML::Node& root, Scene& scene) {
    auto n = r_.Child(root, "raster", false);
    if (!n || !r_.ExpectMap(*n, "raster")) return;
    r_.CheckKeys(*n, {"pitch", "row_spacing", "margin"}, "raster");
    scene.raster.pitch_mm = LengthKey(*n, "pitch", false, true);
    scene.raster.row_spacing_mm = LengthKey(*n, "row_spacing", false, true);
    if (auto m = r_.Child(*n, "margin", false)) {
      auto v = r_.Length(*m, unit_, "raster.margin");
      if (v && r_.Positive(*m, *v, "raster.margin", /*allow_zero=*/true))
        scene.raster.margin_mm = v;
    }
  }

  void ReadRail(const YAML::Node& root, Scene& scene) {
    auto rail = r_.Child(root, "rail", false);
    if (!rail || !r_.ExpectMap(*rail, "rail")) return;
    r_.CheckKeys(*rail, {"offset"}, "rail");
    if (auto v = LengthKey(*rail, "offset", true, false)) scene.rail_offset_mm = *v;
  }

  detail::YamlReader r_;
  DiagnosticSink& sink_;
  LoadOptions options_;
  detail::FileRefPolicy files_;
  LengthUnit unit_ = LengthUnit::kMillimetre;
};

}  // namespace

bool Scene::OmitsMjcfBody(const std::string& body) const {
  for (const auto& f : kCellFixtures) {
    if (body == f.mjcf_body && std::find(omitted_fixtures.begin(), omitted_fixtures.end(),
                                         f.name) != omitted_fixtures.end()) {
      return true;
    }
  }
  return false;
}

const PathSpec* Scene::FindPath(const std::string& path_name) const {
  for (const auto& p : paths) {
    if (p.name == path_name) return &p;
  }
  return nullptr;
}

const PlySpec* Scene::FindPly(const std::string& ply_name) const {
  for (const PlySpec& ply : plies) {
    if (ply.name == ply_name) return &ply;
  }
  return nullptr;
}

std::unique_ptr<Scene> LoadScene(const std::filesystem::path& file, DiagnosticSink& sink,
                                 const LoadOptions& options) {
  return SceneLoader(file, sink, options).Load();
}

}  // namespace stitchsim::scene
