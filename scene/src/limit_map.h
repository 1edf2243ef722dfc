#pragma once
// Private: the `limits:` map of a head spec, a scene or a limits file.

#include <yaml-cpp/yaml.h>

#include "stitchsim/scene/rule_limits.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene::detail {

/// Reads `limits` (rule id -> key -> value) into `out`, over what it holds, validated against
/// the limit table (LimitTable()): unknown rule ids and keys, values in the wrong unit and
/// negative values where none may be are reported through `r` ("<prefix>-unknown-rule",
/// "-unknown-limit", "-limit-unit", "-out-of-range") and left out.
void ReadLimitMap(YamlReader& r, const YAML::Node& limits, RuleLimits& out);

}  // namespace stitchsim::scene::detail
