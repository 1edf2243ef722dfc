#include "stitchsim/scene/head_spec.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "limit_map.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/inertia.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene {
namespace {

// The required number `map[key]`, > 0 (>= 0 with allow_zero), into `out`; a missing or bad
// value is reported (and the spec then fails to load).
bool ReadPositive(detail::YamlReader& r, const YAML::Node& map, std::string_view key, double& out,
                  bool allow_zero = false) {
  if (auto n = r.Child(map, key, true)) {
    if (auto v = r.Number(*n, key); v && r.Positive(*n, *v, key, allow_zero)) {
      out = *v;
      return true;
    }
  }
  return false;
}

// A whole number in [lo, hi] into `out`; anything else (a fraction, 1e300) is reported, never
// converted (a double beyond int's range is undefined behaviour to convert).
void ReadCount(detail::YamlReader& r, const YAML::Node& node, double value, std::string_view key,
               int lo, int hi, int& out) {
  if (value >= lo && value <= hi && value == std::floor(value)) {
    out = static_cast<int>(value);
    return;
  }
  r.Error(node, "out-of-range",
          std::string(key) + " must be a whole number from " + std::to_string(lo) + " to " +
              std::to_string(hi) + ", got " + node.Scalar());
}

// name, description, kind, tool_number and the MJCF file.
void ReadIdentity(detail::YamlReader& r, const YAML::Node& root, const LoadOptions& options,
                  HeadSpec& h) {
  if (auto n = r.Child(root, "name", true)) {
    if (auto s = r.String(*n, "name")) h.name = *s;
  }
  if (auto n = r.Child(root, "description", false)) {
    if (auto s = r.String(*n, "description")) h.description = *s;
  }
  if (auto n = r.Child(root, "kind", true)) {
    if (auto s = r.String(*n, "kind")) {
      if (*s == "single_sided_stitch") {
        h.kind = HeadKind::kSingleSidedStitch;
      } else if (*s == "double_sided_stitch") {
        h.kind = HeadKind::kDoubleSidedStitch;
      } else if (*s == "afp") {
        h.kind = HeadKind::kAfp;
      } else {
        r.Error(*n, "bad-value",
                "kind must be single_sided_stitch, double_sided_stitch or afp, got '" + *s + "'");
      }
    }
  }
  if (auto n = r.Child(root, "tool_number", true)) {
    if (auto v = r.Number(*n, "tool_number"))
      ReadCount(r, *n, *v, "tool_number", 0, 999, h.tool_number);
  }
  if (auto n = r.Child(root, "mjcf", true)) {
    if (auto s = r.String(*n, "mjcf")) {
      detail::FileRefPolicy policy;
      policy.roots = {h.file.has_parent_path() ? h.file.parent_path() : ".", ModelsDir()};
      policy.allow_outside = options.allow_outside_paths;
      if (auto p = r.ReferencedFile(*n, *s, policy, "head MJCF")) h.mjcf = *p;
    }
  }
}

// tool_frame: flange -> tool point, mm and degrees in the file.
void ReadToolFrame(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  if (auto tf = r.Child(root, "tool_frame", true); tf && r.ExpectMap(*tf, "tool_frame")) {
    r.CheckKeys(*tf, {"position_mm", "rotation_deg"}, "tool_frame");
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();
    Eigen::Vector3d rot = Eigen::Vector3d::Zero();
    if (auto n = r.Child(*tf, "position_mm", true)) {
      if (auto v = r.Vector(*n, 3, "tool_frame.position_mm")) pos = *v;
    }
    if (auto n = r.Child(*tf, "rotation_deg", true)) {
      if (auto v = r.Vector(*n, 3, "tool_frame.rotation_deg")) rot = *v;
    }
    h.flange_to_tool_m.setIdentity();
    h.flange_to_tool_m.translation() = pos / 1000.0;
    h.flange_to_tool_m.linear() = geom::RotationFromEuler(geom::EulerOrder{}, rot * (kPi / 180.0));
  }
}

void ReadNeedles(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  if (auto nd = r.Child(root, "needles", true)) {
    if (!nd->IsSequence()) {
      r.Error(*nd, "type", "needles must be a list");
    } else {
      for (const auto& item : *nd) {
        if (!r.ExpectMap(item, "a needle")) continue;
        r.CheckKeys(item, {"name", "through_mm", "direction"}, "needle");
        NeedleSpec ns;
        if (auto n = r.Child(item, "name", true)) {
          if (auto s = r.String(*n, "needle name")) ns.name = *s;
        }
        if (auto n = r.Child(item, "through_mm", true)) {
          if (auto v = r.Vector(*n, 3, "needle through_mm")) ns.through_mm = *v;
        }
        if (auto n = r.Child(item, "direction", true)) {
          if (auto v = r.Vector(*n, 3, "needle direction")) {
            if (v->norm() < 1e-9 || (*v)[2] >= 0) {
              r.Error(*n, "out-of-range",
                      "needle direction must be non-zero and point into the "
                      "preform (negative z)");
            } else {
              ns.direction = v->normalized();
            }
          }
        }
        h.needles.push_back(ns);
      }
    }
  }
}

// stitch: the stitch-cycle parameters (required for a stitching head).
void ReadStitchProcess(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  if (auto st = r.Child(root, "stitch", h.kind != HeadKind::kAfp);
      st && r.ExpectMap(*st, "stitch")) {
    r.CheckKeys(*st,
                {"nominal_length_mm", "width_mm", "needle_in_phase", "walk_capacity_mm",
                 "preform_thickness_mm", "stitch_rate_per_min", "rotation_speed_deg_s",
                 "settle_time_s", "rapid_speed_mm_s"},
                "stitch");
    auto& s = h.stitch;
    auto num = [&](std::string_view key, double& out, bool allow_zero) {
      ReadPositive(r, *st, key, out, allow_zero);
    };
    num("nominal_length_mm", s.nominal_length_mm, false);
    num("width_mm", s.width_mm, true);
    num("walk_capacity_mm", s.walk_capacity_mm, true);
    num("preform_thickness_mm", s.preform_thickness_mm, false);
    num("stitch_rate_per_min", s.stitch_rate_per_min, false);
    num("rotation_speed_deg_s", s.rotation_speed_deg_s, false);
    num("settle_time_s", s.settle_time_s, true);
    num("rapid_speed_mm_s", s.rapid_speed_mm_s, false);
    if (auto n = r.Child(*st, "needle_in_phase", true)) {
      if (auto v = r.Vector(*n, 2, "needle_in_phase")) {
        if ((*v)[0] < 0 || (*v)[1] > 1 || (*v)[0] >= (*v)[1]) {
          r.Error(*n, "out-of-range", "needle_in_phase must be [in, out] with 0 <= in < out <= 1");
        } else {
          s.phase_in = (*v)[0];
          s.phase_out = (*v)[1];
        }
      }
    }
  }
}

// afp: the tow and layup parameters (required for an AFP head).
void ReadAfp(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  if (auto af = r.Child(root, "afp", h.kind == HeadKind::kAfp); af && r.ExpectMap(*af, "afp")) {
    r.CheckKeys(*af,
                {"tows", "tow_width_mm", "roller_radius_mm", "min_steering_radius_mm",
                 "layup_speed_mm_s", "rapid_speed_mm_s", "cut_to_roller_mm", "min_restart_mm",
                 "cut_add_feed_mm_s", "cut_add_zone_mm"},
                "afp");
    auto num = [&](std::string_view key, double& out) { ReadPositive(r, *af, key, out); };
    if (auto n = r.Child(*af, "tows", true)) {
      if (auto v = r.Number(*n, "tows")) ReadCount(r, *n, *v, "tows", 1, 64, h.afp.tows);
    }
    num("tow_width_mm", h.afp.tow_width_mm);
    num("roller_radius_mm", h.afp.roller_radius_mm);
    num("min_steering_radius_mm", h.afp.min_steering_radius_mm);
    num("layup_speed_mm_s", h.afp.layup_speed_mm_s);
    num("rapid_speed_mm_s", h.afp.rapid_speed_mm_s);
    // Optional: absent leaves the parameter not given.
    auto optional_num = [&](std::string_view key, std::optional<double>& out) {
      if (!r.Child(*af, key, false)) return;
      double v = 0.0;
      if (ReadPositive(r, *af, key, v)) out = v;
    };
    optional_num("cut_to_roller_mm", h.afp.cut_to_roller_mm);
    optional_num("min_restart_mm", h.afp.min_restart_mm);
    const auto feed = r.Child(*af, "cut_add_feed_mm_s", false);
    const auto zone = r.Child(*af, "cut_add_zone_mm", false);
    if (feed.has_value() != zone.has_value()) {  // at the one given
      r.Error(feed ? *feed : *zone, "missing-key",
              "cut_add_feed_mm_s and cut_add_zone_mm go together (the feed within the zone)");
    } else if (feed) {
      num("cut_add_feed_mm_s", h.afp.cut_add_feed_mm_s);
      num("cut_add_zone_mm", h.afp.cut_add_zone_mm);
    }
  }
}

// sequence: off-part sequencing parameters (optional; docs/sequence.md).
void ReadSequence(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  auto sq = r.Child(root, "sequence", false);
  if (!sq || !r.ExpectMap(*sq, "sequence")) return;
  r.CheckKeys(*sq, {"retract_mm", "clearance_mm", "min_overlap_mm2", "axis_weights"}, "sequence");
  auto num = [&](std::string_view key, double& out) {
    if (r.Child(*sq, key, false)) ReadPositive(r, *sq, key, out);
  };
  num("retract_mm", h.sequence.retract_mm);
  num("clearance_mm", h.sequence.clearance_mm);
  num("min_overlap_mm2", h.sequence.min_overlap_mm2);
  auto w = r.Child(*sq, "axis_weights", false);
  if (!w || !r.ExpectMap(*w, "sequence.axis_weights")) return;
  for (const auto& kv : *w) {
    SequenceSpec::AxisWeight a;
    a.joint = kv.first.as<std::string>();
    a.where = r.At(kv.first);
    if (auto v = r.Number(kv.second, "axis weight");
        v && r.Positive(kv.second, *v, "axis weight", true)) {
      a.weight = *v;
      h.sequence.axis_weights.push_back(a);
    }
  }
}

void ReadEnvelope(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  if (auto env = r.Child(root, "envelope", false); env && r.ExpectMap(*env, "envelope")) {
    r.CheckKeys(*env, {"height_mm", "radius_mm"}, "envelope");
    HeadEnvelope e;
    ReadPositive(r, *env, "height_mm", e.height_mm);
    ReadPositive(r, *env, "radius_mm", e.radius_mm);
    h.envelope = e;
  }
}

// `with:` of an allowed contact: preform, mold, or a list of them.
void ReadContactSlabs(detail::YamlReader& r, const YAML::Node& node, AllowedContact& c) {
  const bool list = node.IsSequence();
  if (list && node.size() == 0) r.Error(node, "bad-value", "allowed_contacts: with is empty");
  for (std::size_t i = 0; i < (list ? node.size() : 1); ++i) {
    const YAML::Node item = list ? node[i] : node;
    const auto s = r.String(item, "allowed_contacts with");
    if (s && *s == "preform") {
      c.preform = true;
    } else if (s && *s == "mold") {
      c.mold = true;
    } else if (s) {
      r.Error(item, "bad-value",
              "allowed_contacts: with must be preform or mold, got '" + *s + "'");
    }
  }
}

// `allowed_contacts: [{head: <geom pattern>, with: preform | mold | [preform, mold]}, ...]`.
void ReadAllowedContacts(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  const auto list = r.Child(root, "allowed_contacts", false);
  if (!list) return;
  if (!list->IsSequence()) {
    r.Error(*list, "type", "allowed_contacts must be a list");
    return;
  }
  for (const auto& item : *list) {
    if (!r.ExpectMap(item, "an allowed contact")) continue;
    r.CheckKeys(item, {"head", "with"}, "allowed contact");
    AllowedContact c;
    c.where = r.At(item);
    if (auto n = r.Child(item, "head", true)) {
      if (auto s = r.String(*n, "allowed_contacts head")) {
        if (s->empty()) r.Error(*n, "bad-value", "allowed_contacts: head is empty");
        c.head = *s;
      }
    }
    if (auto n = r.Child(item, "with", true)) ReadContactSlabs(r, *n, c);
    h.allowed_contacts.push_back(std::move(c));
  }
}

// One number of the `inertial:` block; every problem with it is reported as head-bad-inertial.
std::optional<double> InertialNumber(detail::YamlReader& r, const YAML::Node& node,
                                     std::string_view what) {
  DiagnosticSink scratch;
  detail::YamlReader quiet(r.File(), scratch, r.Prefix());
  const std::optional<double> value = quiet.Number(node, what);
  for (const Diagnostic& d : scratch.Diagnostics()) {
    r.Sink().Error(r.Prefix() + "-bad-inertial", d.location, d.message);
  }
  return value;
}

// A list of `sizes` numbers of the `inertial:` block (one of the counts given).
std::optional<Eigen::VectorXd> InertialList(detail::YamlReader& r, const YAML::Node& node,
                                            std::initializer_list<int> sizes, std::string_view what,
                                            std::string_view expect) {
  const int n = node.IsSequence() ? static_cast<int>(node.size()) : -1;
  if (std::find(sizes.begin(), sizes.end(), n) == sizes.end()) {
    r.Error(node, "bad-inertial", std::string(what) + " must be a list of " + std::string(expect));
    return std::nullopt;
  }
  Eigen::VectorXd out(n);
  bool ok = true;
  for (int i = 0; i < n; ++i) {
    const std::optional<double> v = InertialNumber(r, node[static_cast<std::size_t>(i)], what);
    ok = ok && v.has_value();
    if (v) out(i) = *v;
  }
  return ok ? std::optional<Eigen::VectorXd>(out) : std::nullopt;
}

// inertial: {mass_kg, com_mm (flange frame), inertia_kg_m2: [ixx, iyy, izz(, ixy, ixz, iyz)]}.
void ReadInertial(detail::YamlReader& r, const YAML::Node& root, HeadSpec& h) {
  const auto in = r.Child(root, "inertial", false);
  if (!in || !r.ExpectMap(*in, "inertial")) return;
  r.CheckKeys(*in, {"mass_kg", "com_mm", "inertia_kg_m2"}, "inertial");
  HeadInertial out;
  bool ok = true;
  if (auto n = r.Child(*in, "mass_kg", true)) {
    const std::optional<double> mass = InertialNumber(r, *n, "inertial.mass_kg");
    if (mass && !(*mass > 0.0)) r.Error(*n, "bad-inertial", "inertial.mass_kg must be > 0");
    ok = ok && mass && *mass > 0.0;
    out.mass_kg = mass.value_or(0.0);
  } else {
    ok = false;
  }
  const auto com = r.Child(*in, "com_mm", true);
  const auto com_mm =
      com ? InertialList(r, *com, {3}, "inertial.com_mm", "3 numbers (mm)") : std::nullopt;
  if (com_mm) out.com_m = com_mm->head<3>() / 1000.0;
  const auto inertia = r.Child(*in, "inertia_kg_m2", true);
  const auto moments = inertia ? InertialList(r, *inertia, {3, 6}, "inertial.inertia_kg_m2",
                                              "3 or 6 numbers [ixx, iyy, izz(, ixy, ixz, iyz)]")
                               : std::nullopt;
  if (moments) {
    const Eigen::VectorXd& m = *moments;
    const double ixy = m.size() == 6 ? m(3) : 0.0;
    const double ixz = m.size() == 6 ? m(4) : 0.0;
    const double iyz = m.size() == 6 ? m(5) : 0.0;
    out.inertia_kg_m2 << m(0), ixy, ixz, ixy, m(1), iyz, ixz, iyz, m(2);
    if (const std::string why = geom::InertiaProblem(out.inertia_kg_m2); !why.empty()) {
      r.Error(*inertia, "bad-inertial", "inertial.inertia_kg_m2: " + why);
      ok = false;
    }
  }
  if (ok && com_mm && moments) h.inertial = out;
}

}  // namespace

bool AllowedContact::Matches(const std::string& geom_name) const {
  // Glob with `*` only: p / n walk the pattern and the name; star / mark the last `*` and the
  // name position it was tried at, to backtrack to.
  std::size_t p = 0, n = 0, star = std::string::npos, mark = 0;
  while (n < geom_name.size()) {
    if (p < head.size() && head[p] == '*') {
      star = p++;
      mark = n;
    } else if (p < head.size() && head[p] == geom_name[n]) {
      ++p;
      ++n;
    } else if (star != std::string::npos) {
      p = star + 1;
      n = ++mark;
    } else {
      return false;
    }
  }
  while (p < head.size() && head[p] == '*') ++p;
  return p == head.size();
}

std::filesystem::path ResolveHeadFile(const std::string& name_or_path,
                                      const std::filesystem::path& relative_to) {
  const std::filesystem::path p(name_or_path);
  if (p.has_extension()) return p.is_absolute() ? p : relative_to / p;
  return DataDir() / "models" / "heads" / (name_or_path + ".yaml");
}

std::optional<HeadSpec> LoadHeadSpec(const std::filesystem::path& file, DiagnosticSink& sink,
                                     const LoadOptions& options) {
  detail::YamlReader r(file, sink, "head");
  const std::size_t errors_before = sink.ErrorCount();
  auto root = r.LoadFile();
  if (!root) return std::nullopt;
  if (!r.ExpectMap(*root, "a head spec")) return std::nullopt;
  r.CheckKeys(*root,
              {"stitchsim_head", "name", "description", "kind", "tool_number", "mjcf", "tool_frame",
               "needles", "stitch", "afp", "sequence", "envelope", "limits", "allowed_contacts",
               "inertial"},
              "head spec");
  HeadSpec h;
  h.file = file;
  ReadIdentity(r, *root, options, h);
  ReadToolFrame(r, *root, h);
  ReadNeedles(r, *root, h);
  ReadStitchProcess(r, *root, h);
  ReadAfp(r, *root, h);
  ReadSequence(r, *root, h);
  ReadEnvelope(r, *root, h);
  ReadAllowedContacts(r, *root, h);
  ReadInertial(r, *root, h);
  if (auto lim = r.Child(*root, "limits", false)) detail::ReadLimitMap(r, *lim, h.limits);
  if (sink.ErrorCount() > errors_before) return std::nullopt;
  return h;
}

std::optional<double> MinTowLengthMm(const Scene& scene) {
  const std::optional<double> given = scene.limits.Get(LimitKey::kAfpMinTowLengthMm);
  return given ? given : scene.head.afp.cut_to_roller_mm;
}

std::optional<double> MinRestartMm(const Scene& scene) {
  const std::optional<double> given = scene.limits.Get(LimitKey::kAfpRestartDistanceMm);
  return given ? given : scene.head.afp.min_restart_mm;
}

}  // namespace stitchsim::scene
