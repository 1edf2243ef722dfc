#pragma once
// Private pieces of the JSON writers (the report and the diff's report).

#include <cmath>
#include <nlohmann/json.hpp>

#include "stitchsim/verify/report.h"

namespace stitchsim::verify::detail {

/// NaN and infinity have no JSON spelling: they become null rather than invalid text.
inline nlohmann::ordered_json Number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

/// "error" / "warning".
inline const char* SeverityName(FindingSeverity severity) {
  return severity == FindingSeverity::kError ? "error" : "warning";
}

}  // namespace stitchsim::verify::detail
