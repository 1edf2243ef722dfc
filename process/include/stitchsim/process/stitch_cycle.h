#pragma once
// The stitch-cycle process model (domain.md sections 2 and 5): needle phases from the drive
// axis, the needle walk, the side-force proxy and the rotation accumulated while the needles
// are in the preform, and where the needles pierce the stitching surface. MuJoCo-free: the
// planner uses it to decide where to decouple, the verifier uses it to judge.
// Lengths in millimetres, angles in radians, poses are tool-point poses in the part frame.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/scene/head_spec.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::process {

/// Immutable description of the head's needles and stitch cycle for one scene.
struct ProcessModel {
  std::vector<scene::NeedleSpec> needles;  ///< tool frame
  double phase_in = 0.15;                  ///< cycle fraction: needles enter the preform
  double phase_out = 0.85;                 ///< cycle fraction: needles leave it
  double walk_capacity_mm = 4.0;
  double preform_thickness_mm = 12.0;  ///< preform occupies tool z in [0, thickness]
  double stitch_length_mm = 5.0;       ///< the drive advance of one stitch cycle
  double nominal_width_mm = 17.0;      ///< insertion-catcher spacing (0: one needle)
  /// Heights (tool z, mm) of the shaft points followed through the preform.
  std::vector<double> shaft_heights_mm;
};

/// Model of `scene`'s head with `stitch_length_mm` as the drive advance per stitch.
ProcessModel MakeProcessModel(const scene::Scene& scene, double stitch_length_mm);

/// Cycle phase in [0, 1) at drive-axis distance `drive_mm`.
double CyclePhase(double drive_mm, double stitch_length_mm);

/// Whether the needles are in the preform at `phase` on a line that advances the drive.
bool NeedlesIn(const ProcessModel& model, double phase);

/// What happened while the needles were in the preform (one needle window).
struct WindowMetrics {
  /// Side-force proxy per needle (model.needles order): the largest drift, across the needle
  /// axis, of the shaft points inside the preform from where they entered, after the walk.
  std::vector<double> side_force_mm;
  double walk_demand_mm = 0.0;  ///< largest walk the motion asked for
  /// Largest |rotation| since entry about tool x, y, z (entry frame) and in total.
  Eigen::Vector3d rotation_rad = Eigen::Vector3d::Zero();
  double rotation_total_rad = 0.0;
  double MaxSideForceMm() const;
};

/// Accumulates one needle window from tool poses sampled while the needles are in.
class NeedleWindow {
 public:
  explicit NeedleWindow(const ProcessModel& model);
  /// The needles enter the preform with the tool at `tool`. `walk_reference`: the commanded
  /// tool pose, which the walk mechanism follows (it runs with the drive, matched to the
  /// programmed travel), when the arm is not exactly on it (a dynamic run); null: the tool.
  void Enter(const Eigen::Isometry3d& tool, const Eigen::Isometry3d* walk_reference = nullptr);
  /// A later pose while the needles are still in (`walk_reference` as for Enter).
  void Update(const Eigen::Isometry3d& tool, const Eigen::Isometry3d* walk_reference = nullptr);
  bool Active() const { return active_; }
  const WindowMetrics& Metrics() const { return metrics_; }
  /// The tool pose the needles entered with (part frame, mm).
  const Eigen::Isometry3d& Entry() const { return entry_; }

 private:
  const ProcessModel* model_;
  bool active_ = false;
  Eigen::Isometry3d entry_ = Eigen::Isometry3d::Identity();
  Eigen::Vector3d entry_reference_ = Eigen::Vector3d::Zero();  ///< walk reference at entry
  std::vector<std::vector<Eigen::Vector3d>> entry_points_;     // per needle, per shaft point
  WindowMetrics metrics_;
};

/// Tool pose on the straight line + slerp from `from` to `to` at fraction `s` in [0, 1].
Eigen::Isometry3d InterpolatePose(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
                                  double s);

/// Metrics of one stitch made in a single (coupled) line from `from` to `to`: translation and
/// rotation together while the drive advances one stitch. `samples` poses inside the window.
WindowMetrics EvaluateCoupledStitch(const ProcessModel& model, const Eigen::Isometry3d& from,
                                    const Eigen::Isometry3d& to, int samples = 24);

/// Limits the planner's auto mode and the verifier share (radians / millimetres).
struct NeedleLimits {
  double side_force_error_mm = 0.10;
  double rotation_error_rad[3] = {1e9, 1e9, 1e9};  ///< about tool x, y, z
  double rotation_total_error_rad = 1e9;
};
NeedleLimits NeedleLimitsFrom(const scene::RuleLimits& limits);

/// Which limit a window breaks first, or empty when it is within all of them.
std::string FirstExceededLimit(const WindowMetrics& m, const NeedleLimits& limits);

/// Where each needle's axis pierces the stitching surface with the tool at `tool`; nullopt
/// for a needle that misses the surface.
std::vector<std::optional<Eigen::Vector3d>> PenetrationPoints(const ProcessModel& model,
                                                              const geom::Surface& surface,
                                                              const Eigen::Isometry3d& tool);

}  // namespace stitchsim::process
