#pragma once
// Private: the `limits:` map of a head spec, a scene or a limits file.

#include <yaml-cpp/yaml.h>

#include "stitchsim/scene/head_spec.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene::detail {

/// Reads `limits` (rule id -> key -> value) into `out`, over what it holds; problems are
/// reported through `r`.
void ReadLimitMap(YamlReader& r, const YAML::Node& limits, RuleLimits& out);

}  // namespace stitchsim::scene::detail
