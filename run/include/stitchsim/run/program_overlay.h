#pragma once
// A programme's stitch points for drawing (`stitchsim render --program`): the end point of
// every line that advances the drive axis, in the part frame, thinned to what a picture shows.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/run/status.h"

namespace stitchsim::run {

struct ProgramOverlay {
  Status status;                                           ///< not ok: nothing to draw (bad input)
  std::vector<Eigen::Vector3d> stitch_points_part_mm;      ///< part frame, mm; at most 3000
  std::optional<Eigen::Isometry3d> first_tool_in_part_mm;  ///< part frame, mm; the first move's
};

/// Reads `program_file` in the default dialect; the reader's diagnostics go into `sink`
/// (status InSink when one is an error), a missing file or a programme without moves come
/// back as the status's code and message.
ProgramOverlay ProgramStitchOverlay(const std::string& program_file, DiagnosticSink& sink);

}  // namespace stitchsim::run
