#include "stitchsim/planner/plan_status.h"

namespace stitchsim::planner {

PlanStatus StitchingHeadStatus(const scene::Scene& scene) {
  if (scene.head.IsStitching()) return {};
  return {"plan-wrong-head", "head '" + scene.head.name +
                                 "' does not stitch; use `stitchsim plan afp` for fiber placement"};
}

PathChoice ChoosePath(const scene::Scene& scene, const std::string& name) {
  PathChoice choice;
  if (name.empty() && !scene.paths.empty()) {
    choice.path = &scene.paths.front();
  } else if (!name.empty()) {
    choice.path = scene.FindPath(name);
  }
  if (choice.path == nullptr) {
    std::string names;
    for (const auto& p : scene.paths) names += (names.empty() ? "" : ", ") + p.name;
    choice.status = {"plan-unknown-path", "no path named '" + name + "' (paths: " + names + ")"};
  }
  return choice;
}

}  // namespace stitchsim::planner
