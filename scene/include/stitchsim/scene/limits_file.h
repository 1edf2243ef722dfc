#pragma once
// Rule-limit overrides from a file of their own (`stitchsim recheck --limits L.yaml`): the
// same `limits:` map a scene or head spec holds (docs/scene-format.md), applied on top of a
// loaded scene's limits.

#include <filesystem>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::scene {

/// Reads `file` (a YAML map with the one key `limits`) and overrides `scene`'s limits with
/// it, validated against the limit table as a scene's are. Every problem is a diagnostic with
/// file:line:col (codes "limits-...", e.g. "limits-unknown-rule", "limits-limit-unit");
/// returns false, leaving `scene` unchanged, if any error was reported.
bool ApplyLimitsFile(const std::filesystem::path& file, Scene& scene, DiagnosticSink& sink);

}  // namespace stitchsim::scene
