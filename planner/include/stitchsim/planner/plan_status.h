#pragma once
// What the planners ask of a scene before they plan, answered as values: whether its head
// can do the job, which of its paths a name picks. The caller (the app) prints them.

#include <string>

#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

/// Why a plan cannot start from what it was given: a stable code ("plan-...") and a message.
/// For input problems at no place in a file (those are diagnostics).
struct PlanStatus {
  std::string code;     ///< empty: nothing wrong
  std::string message;  ///< what is wrong, a sentence without the file name
  bool Ok() const { return code.empty(); }
};

/// plan-wrong-head when the scene's head does not stitch (plan stitch and plan raster need one
/// that does).
PlanStatus StitchingHeadStatus(const scene::Scene& scene);

/// A scene path picked by name.
struct PathChoice {
  const scene::PathSpec* path = nullptr;  ///< not owned: the scene's; null unless status.Ok()
  PlanStatus status;                      ///< plan-unknown-path, naming the paths there are
};

/// The scene's path named `name`; its first path when `name` is empty.
PathChoice ChoosePath(const scene::Scene& scene, const std::string& name);

}  // namespace stitchsim::planner
