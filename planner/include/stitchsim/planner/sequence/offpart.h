#pragma once
// The off-part moves `stitchsim sequence` writes between lay-ups (docs/sequence.md): retract
// along the head axis, travel that keeps the tool point clear of the part, approach along
// the next course's head axis and lower onto its start. Part frame, mm.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/program/afp_program.h"

namespace stitchsim::planner {

struct OffPartOptions {
  double retract_mm = 100.0;    ///< along the tool z after a lay-up and before the next
  double clearance_mm = 100.0;  ///< travel keeps the tool point at least this far off the surface
  double sample_mm = 10.0;      ///< travel checked at most this far apart
  int max_refinements = 10;     ///< via points inserted per travel at most (depth of bisection)
  /// How far the head turns about its own axis (tool z) during the travel, radians, signed:
  /// a head turned round (a course laid backwards) can turn either way, and the wrist's last
  /// axis only has so much travel, so the caller chooses. Unset: the shorter way.
  std::optional<double> turn_about_z_rad;
};

/// `pose` moved `h` mm along its own tool z (up, off the part): where a retract ends and an
/// approach begins.
Eigen::Isometry3d RaisedPose(const Eigen::Isometry3d& pose, double h);

/// Signed angle (radians, in (-pi, pi]) about the tool z from orientation `a` to `b`: the
/// z component of the relative rotation (exact when they differ by a turn about z only).
double TwistAboutZ(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/// Where the head is between lay-ups: a lay-up's end or start (on the surface), or a free pose
/// (home).
struct OffPartEnd {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  bool on_surface = true;  ///< a lay-up end: retract from / approach to it
};

/// The off-part blocks from `from` to `to` (either may be absent: nothing before / after).
/// From a lay-up end: M20 and a rapid `retract_mm` up its tool z. Then rapids to above `to`
/// (its start raised `retract_mm` along its tool z) through via points lifted to
/// `clearance_mm` off the surface wherever the straight line would come closer, orientation
/// turning with the distance travelled. To a lay-up start: lower the head (M21) and feed down
/// onto it at `feed_mm_per_min` (the lay-up's own feed, so its first line means what it meant).
std::vector<program::OffPartBlock> OffPartPath(const geom::Surface& surface,
                                               const std::optional<OffPartEnd>& from,
                                               const std::optional<OffPartEnd>& to,
                                               std::optional<double> feed_mm_per_min,
                                               const OffPartOptions& options);

/// Tool-point path length of `blocks` starting from `from` (mm): the as-flown off-part motion.
double OffPartLength(const Eigen::Vector3d& from, const std::vector<program::OffPartBlock>& blocks);

/// The turn about the head axis (radians) for an off-part move whose shorter turn is
/// `shorter` (in (-pi, pi]), the head having turned `twist` in all since home: a near half turn
/// (a course laid backwards) goes the way that brings the total back towards zero, and so does
/// any turn that would take the total past 3/4 of a turn. The wrist's last axis follows the
/// total; made the shorter way every time, the half turns of a bidirectional programme wind it
/// to its limit (a6: +-350 deg).
double UnwindingTurn(double twist, double shorter);

/// Height of `p` above the surface along the normal at its foot point (negative beneath).
double HeightAboveSurface(const geom::Surface& surface, const Eigen::Vector3d& p);

}  // namespace stitchsim::planner
