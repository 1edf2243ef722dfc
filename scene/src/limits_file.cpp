#include "stitchsim/scene/limits_file.h"

#include "limit_map.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene {

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
