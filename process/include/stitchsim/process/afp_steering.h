#pragma once
// The steering radius of a laid tow (docs/afp.md, "Steering radius"): one definition for the
// ply planner, which reports it per tow, and afp.steering_radius, which judges the programme.
// A tow's centre line is known at its vertices: the tow centres at the programme's poses (the
// planner's course points; the verifier's line ends, and the points dividing a line longer
// than the half window). At vertex j the radius is that of the circle through the centres at
// j and at the nearest vertices at least kSteeringHalfWindowMm before and after it along the
// line (chord lengths), laid into the tangent plane at j: the geodesic radius of the centre
// line over that window, exact for a tow on a circle of the plane and infinite for a geodesic
// (a helix on a cylinder turns only along the normal). Vertices closer than the half window to
// either end of a laid stretch are not measured. Part frame, mm.

#include <Eigen/Core>
#include <climits>
#include <deque>
#include <vector>

namespace stitchsim::process {

/// Half the arc over which a steering radius is measured (mm). The planner writes poses at
/// most this far apart.
inline constexpr double kSteeringHalfWindowMm = 25.0;

/// Radius of the circle through a, b, c laid into the plane normal to `n` at b (mm);
/// infinity when they are in line.
double TangentPlaneCircleRadius(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c, const Eigen::Vector3d& n);

/// One tow's centre line, vertex by vertex: each vertex is measured once the line has run a
/// half window past it. Start a new stretch (Reset) where the tow is cut.
class SteeringWindow {
 public:
  struct Radius {
    double radius_mm = 0.0;
    int tag = 0;  ///< the measured vertex's tag (the caller's line or point)
    /// The three tow centres the circle passes through: a half window before, the measured
    /// vertex, a half window after (part frame, mm).
    Eigen::Vector3d before = Eigen::Vector3d::Zero(), at = Eigen::Vector3d::Zero(),
                    after = Eigen::Vector3d::Zero();
  };
  /// Adds the next vertex (tow centre on the surface, unit normal there); appends to `out` the
  /// radii of vertices that now have a vertex a half window after them.
  void Add(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, int tag,
           std::vector<Radius>& out);
  void Reset();
  /// The tag of the first vertex not measured yet (INT_MAX: none).
  int PendingTag() const;

 private:
  struct Vertex {
    Eigen::Vector3d centre, normal;
    double s = 0.0;
    int tag = 0;
  };
  std::deque<Vertex> vertices_;  ///< from the last one a half window behind `next_` on
  std::size_t next_ = 0;         ///< index in vertices_ of the next vertex to measure
};

}  // namespace stitchsim::process
