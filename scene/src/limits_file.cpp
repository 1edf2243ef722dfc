#include "stitchsim/scene/limits_file.h"

#include "limit_map.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene {
namespace detail {

void ReadLimitMap(YamlReader& r, const YAML::Node& limits, RuleLimits& out) {
  if (!r.ExpectMap(limits, "limits")) return;
  for (const auto& rule : limits) {
    const std::string id = rule.first.Scalar();
    if (!r.ExpectMap(rule.second, "limits of " + id)) continue;
    for (const auto& kv : rule.second) {
      if (auto v = r.Number(kv.second, id + "." + kv.first.Scalar())) {
        out[id][kv.first.Scalar()] = *v;
      }
    }
  }
}

}  // namespace detail

bool ApplyLimitsFile(const std::filesystem::path& file, Scene& scene, DiagnosticSink& sink) {
  const std::size_t errors_before = sink.ErrorCount();
  detail::YamlReader r(file, sink, "limits");
  const std::optional<YAML::Node> root = r.LoadFile();
  if (!root || !r.ExpectMap(*root, "limits file")) return false;
  r.CheckKeys(*root, {"limits"}, "limits file");
  RuleLimits limits = scene.limits;
  if (auto lim = r.Child(*root, "limits", true)) detail::ReadLimitMap(r, *lim, limits);
  if (sink.ErrorCount() > errors_before) return false;
  scene.limits = std::move(limits);
  return true;
}

}  // namespace stitchsim::scene
