#pragma once
// Private to verify: doubles in a verifier partial (Verifier::SavePartial). JSON numbers
// round-trip a finite double exactly (shortest round-trip form); infinities and NaN, which
// JSON has no number for, are written as the strings "inf", "-inf" and "nan".

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace stitchsim::verify::detail {

inline nlohmann::json DoubleToJson(double v) {
  if (std::isfinite(v)) return v;
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

/// Throws nlohmann::json::exception (type_error) for anything but a number or those strings.
inline double DoubleFromJson(const nlohmann::json& j) {
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  }
  return j.get<double>();
}

/// An optional double: null when empty.
inline nlohmann::json OptionalToJson(const std::optional<double>& v) {
  return v ? DoubleToJson(*v) : nlohmann::json(nullptr);
}

inline std::optional<double> OptionalFromJson(const nlohmann::json& j) {
  if (j.is_null()) return std::nullopt;
  return DoubleFromJson(j);
}

/// Bit-exact equality of optional doubles (a NaN limit equals itself).
inline bool SameOptional(const std::optional<double>& a, const std::optional<double>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return *a == *b || (std::isnan(*a) && std::isnan(*b));
}

}  // namespace stitchsim::verify::detail
