#pragma once
// The scene render behind `stitchsim render` and the overview snapshot: a PNG of the cell,
// the part and its paths (or point sets), the robot posed, framed for the view asked, and
// optionally the pixel coverage of each class of thing (robot, head, mold, ...) as JSON.

#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/render/renderer.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/status.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::run {

struct RenderRequest {
  std::string output;             ///< the PNG written
  int width = 1280;               ///< pixels
  int height = 960;               ///< pixels
  std::string view = "overview";  ///< overview | head | part (the stitches, from above)
  std::string coverage_json;      ///< if set, write per-class pixel counts here
  sim::JointVector joints = sim::JointVector::Zero();  ///< the robot's pose, model order, rad
  Eigen::Isometry3d tool_world_m = Eigen::Isometry3d::Identity();  ///< world, m (head view)
  /// Points to draw instead of the scene's paths (stitches).
  struct PointSet {
    std::string label;                                     ///< coverage class, e.g. "stitch"
    std::vector<Eigen::Vector3d> points_part_mm;           ///< part frame, mm
    std::array<float, 4> rgba = {0.1f, 0.9f, 0.2f, 1.0f};  ///< RGBA in [0, 1]
    double radius_scale = 1.0;                             ///< times the view's point radius
    bool polyline = false;  ///< connect the points (else one sphere each)
    /// Polyline only, one per point when given (part frame, unit): drawn as a flat ribbon
    /// lying on that normal (render::Overlay::normals), radius_mm wide each side.
    std::vector<Eigen::Vector3d> normals_part;
    double radius_mm = 0.0;  ///< > 0: this half width (mm), not the view's point radius
  };
  std::vector<PointSet> point_sets;
  /// Applied to the picture before it is written (snapshots: title bar and legend).
  std::function<void(render::Image&)> decorate;
};

/// Renders `req` and writes its PNG (and coverage JSON). The scene model's diagnostics go into
/// `sink` (Status::InSink when one is an error); a missing joint, a renderer that cannot be
/// made or a file that cannot be written come back as the Status's code and message.
Status RenderScene(const LoadedScene& ls, const RenderRequest& req, DiagnosticSink& sink);

}  // namespace stitchsim::run
