#include "detail/urdf_dynamics.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "stitchsim/geom/inertia.h"

namespace stitchsim::sim::detail {
namespace {

std::string Num(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// The whole of `text` as a number; nullopt when it is not one (surrounding blanks allowed).
std::optional<double> ParseNumber(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) {
    return std::nullopt;
  }
  return value;
}

Eigen::Matrix3d ToRotation(const urdf::Rotation& r) {
  return Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
}

}  // namespace

void CollectUrdfExtensions(const TiXmlElement& element, UrdfExtensions& out) {
  if (element.ValueStr() == "payload_rating") {
    UrdfExtensions::PayloadElement payload;
    payload.line = element.Row();
    for (const TiXmlAttribute* a = element.FirstAttribute(); a != nullptr; a = a->Next()) {
      payload.attributes.emplace(a->Name(), a->Value());
    }
    out.payload.push_back(std::move(payload));
    return;
  }
  const char* name = element.Attribute("name");
  if (element.ValueStr() != "joint" || name == nullptr) return;
  const TiXmlElement* limit = element.FirstChildElement("limit");
  const char* acceleration = limit != nullptr ? limit->Attribute("acceleration") : nullptr;
  if (acceleration != nullptr) out.joint_acceleration.emplace(name, acceleration);
}

std::optional<LinkInertial> ReadLinkInertial(const urdf::Link& link, const SourceLocation& where,
                                             DiagnosticSink& sink) {
  if (!link.inertial) return std::nullopt;
  const urdf::Inertial& in = *link.inertial;
  const auto bad = [&](const std::string& why) {
    sink.Error("urdf-bad-inertial", where, "link '" + link.name + "': " + why);
    return std::nullopt;
  };
  if (!std::isfinite(in.mass) || !(in.mass > 0.0)) {
    return bad("the mass must be positive (got " + Num(in.mass) + " kg)");
  }
  const Eigen::Vector3d com(in.origin.position.x, in.origin.position.y, in.origin.position.z);
  if (!com.allFinite()) return bad("the centre of mass is not finite");
  Eigen::Matrix3d about_com;  // in the <inertial> origin's axes
  about_com << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  if (const std::string why = geom::InertiaProblem(about_com); !why.empty()) return bad(why);
  const Eigen::Matrix3d r = ToRotation(in.origin.rotation);
  LinkInertial out;
  out.mass_kg = in.mass;
  out.com_m = com;
  out.inertia_kg_m2 = r * about_com * r.transpose();
  return out;
}

void ReadJointDynamics(const urdf::Joint& joint, const std::string* acceleration_text,
                       const SourceLocation& where, DiagnosticSink& sink, JointInfo& info) {
  const auto bad = [&](const std::string& what) {
    sink.Error("urdf-bad-limits", where, "joint '" + joint.name + "': " + what);
  };
  if (joint.limits) {
    const double effort = joint.limits->effort;
    if (std::isfinite(effort) && effort >= 0.0) {
      info.effort = effort;
    } else {
      bad("the effort limit must be >= 0 (got " + Num(effort) + ")");
    }
  }
  if (joint.dynamics) {
    const double damping = joint.dynamics->damping;
    if (std::isfinite(damping) && damping >= 0.0) {
      info.damping = damping;
    } else {
      bad("the damping must be >= 0 (got " + Num(damping) + ")");
    }
  }
  if (acceleration_text != nullptr) {
    const std::optional<double> acceleration = ParseNumber(*acceleration_text);
    if (acceleration && std::isfinite(*acceleration) && *acceleration >= 0.0) {
      info.max_acceleration = *acceleration;
    } else {
      bad("the acceleration limit must be a number >= 0 (got '" + *acceleration_text + "')");
    }
  }
}

PayloadRating ReadPayloadRating(const UrdfExtensions& extensions, const std::string& file,
                                DiagnosticSink& sink) {
  PayloadRating out;
  if (extensions.payload.empty()) return out;
  const UrdfExtensions::PayloadElement& element = extensions.payload.front();
  const SourceLocation where{file, element.line, 0};
  if (extensions.payload.size() > 1) {
    sink.Error("urdf-bad-payload", {file, extensions.payload[1].line, 0},
               "only one <payload_rating> is allowed");
  }
  for (const auto& [name, text] : element.attributes) {
    if (name != "mass_kg" && name != "lz_m" && name != "lxy_m") {
      sink.Error("urdf-bad-payload", where,
                 "<payload_rating> has no attribute '" + name + "' (mass_kg, lz_m, lxy_m)");
    }
  }
  PayloadRating read;
  bool ok = true;
  for (const auto& [name, field] :
       {std::pair{"mass_kg", &read.mass_kg}, {"lz_m", &read.lz_m}, {"lxy_m", &read.lxy_m}}) {
    const auto it = element.attributes.find(name);
    const std::optional<double> value =
        it == element.attributes.end() ? std::nullopt : ParseNumber(it->second);
    const bool positive_mass = std::string_view(name) != "mass_kg" || (value && *value > 0.0);
    if (!value || !std::isfinite(*value) || *value < 0.0 || !positive_mass) {
      sink.Error("urdf-bad-payload", where,
                 std::string("<payload_rating> needs ") + name +
                     (std::string_view(name) == "mass_kg" ? " > 0" : " >= 0") + " (got " +
                     (it == element.attributes.end() ? "nothing" : "'" + it->second + "'") + ")");
      ok = false;
      continue;
    }
    *field = *value;
  }
  return ok ? read : out;
}

}  // namespace stitchsim::sim::detail
