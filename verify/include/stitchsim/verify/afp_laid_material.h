#pragma once
// What an AFP programme laid, kept for the pictures and the HTML report (issue 30;
// docs/report-format.md, "Laid material"): every laying line's tows as a strip of stations,
// each station the head's tow boundaries across the roller (process::TowsAt, the model every
// afp.* rule reads through the verifier's one sampler, verify/src/afp_laid.h), thinned along
// the line to at most `spacing_mm` apart; the tow adds and cuts; per line and tow the figures
// the rules measured there. Owner: verify::Verifier (Laid()), filled only when it keeps
// stitch marks (verify --snapshots / --html) and the head is AFP. Values only: run/ draws
// them. Part frame, mm; (u, v): the surface's parameters, mm.
//
// Memory: stations are stored once, flat: a strip that continues the previous strip of its
// course (its line starts where the previous one ended) shares that strip's last station.
// A station costs sizeof(LaidStation) + (k + 1) * 20 bytes (k = 16: 372 bytes); a strip
// sizeof(LaidStrip) + 8 k bytes (k = 16: 168). BytesUsed() sums them.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace stitchsim::verify {

/// One station along a laying line: where the tool was. Its k + 1 tow boundaries are in
/// LaidMaterial::boundary / boundary_uv (Boundary(), BoundaryUv()).
struct LaidStation {
  Eigen::Vector3f tool = Eigen::Vector3f::Zero();     ///< tool point, part frame, mm
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< unit surface normal under the roller
  /// The roller was on the surface here (process::TowCross::ok); false: the boundaries are NaN.
  bool on_surface = true;
};

/// One laying line (a feed move of a course with the head down and some tow set).
struct LaidStrip {
  int line = 0;            ///< the programme line (1-based)
  int ply = 0;             ///< M70 P<n>
  int course = 0;          ///< the course number the programme gives (M71 P<n>)
  std::uint64_t tows = 0;  ///< bit t - 1: head tow t laid on this line
  float feed_mm_s = 0.0F;  ///< the line's programmed feed, mm/s
  /// Its stations: LaidMaterial::stations[first_station .. first_station + station_count),
  /// in order along the line: the line's two ends always (station_count >= 2), between them
  /// evenly at most LaidMaterial::spacing_mm apart (measured along the tool's line).
  std::uint32_t first_station = 0;
  std::uint32_t station_count = 0;
};

/// A tow added (the first line of a run that lays it) or cut (the last) within a course.
struct TowEvent {
  enum class Kind : std::uint8_t { kAdd, kCut };
  Kind kind = Kind::kAdd;
  int line = 0;                      ///< the line that starts (add) or ends (cut) laying the tow
  int ply = 0, course = 0, tow = 0;  ///< tow: head number, 1-based
  std::uint32_t strip = 0;           ///< index into LaidMaterial::strips
  Eigen::Vector3f point = Eigen::Vector3f::Zero();  ///< the tow's centre there, part frame, mm
  Eigen::Vector2f uv = Eigen::Vector2f::Zero();     ///< the same point in (u, v), mm
};

struct LaidMaterial {
  static constexpr float kNotMeasured = std::numeric_limits<float>::quiet_NaN();

  int tows = 0;               ///< k, the head's tows
  double tow_width_mm = 0.0;  ///< w, mm
  double spacing_mm = 0.0;    ///< the most a strip's stations lie apart along its line, mm
  std::vector<LaidStation> stations;
  /// stations.size() * (k + 1) boundaries, station by station, left to right across the
  /// roller: boundary b (0 .. k) is the left edge of head tow b + 1 (b = k: the right edge of
  /// tow k). On the surface, part frame, mm; the same points in (u, v), mm. Boundaries of
  /// tows a line does not lay are kept too.
  std::vector<Eigen::Vector3f> boundary;
  std::vector<Eigen::Vector2f> boundary_uv;
  std::vector<LaidStrip> strips;  ///< programme order
  /// strips.size() * k, strip by strip (index t - 1 for head tow t): the smallest steering
  /// radius afp.steering_radius measured at a vertex on the strip's line, mm (infinity: the
  /// tow ran straight), and the largest fibre-angle deviation afp.fiber_angle measured along
  /// it, deg; kNotMeasured (NaN) for a tow not laid there or not measured.
  std::vector<float> steering_radius_mm;
  std::vector<float> fiber_angle_deg;
  std::vector<TowEvent> events;  ///< programme order (a cut is listed when its run ends)

  bool Empty() const { return strips.empty(); }
  const Eigen::Vector3f& Boundary(std::size_t station, int b) const {
    return boundary[station * static_cast<std::size_t>(tows + 1) + static_cast<std::size_t>(b)];
  }
  const Eigen::Vector2f& BoundaryUv(std::size_t station, int b) const {
    return boundary_uv[station * static_cast<std::size_t>(tows + 1) + static_cast<std::size_t>(b)];
  }
  /// Strip `strip`'s figure for head tow `tow` (1-based).
  float SteeringRadiusMm(std::size_t strip, int tow) const {
    return steering_radius_mm[strip * static_cast<std::size_t>(tows) +
                              static_cast<std::size_t>(tow - 1)];
  }
  float FiberAngleDeg(std::size_t strip, int tow) const {
    return fiber_angle_deg[strip * static_cast<std::size_t>(tows) +
                           static_cast<std::size_t>(tow - 1)];
  }
  /// The bytes one station and one strip take (payload), and the total held (capacity).
  std::size_t BytesPerStation() const {
    return sizeof(LaidStation) +
           static_cast<std::size_t>(tows + 1) * (sizeof(Eigen::Vector3f) + sizeof(Eigen::Vector2f));
  }
  std::size_t BytesPerStrip() const {
    return sizeof(LaidStrip) + 2 * static_cast<std::size_t>(tows) * sizeof(float);
  }
  std::size_t BytesUsed() const {
    return stations.capacity() * sizeof(LaidStation) +
           boundary.capacity() * sizeof(Eigen::Vector3f) +
           boundary_uv.capacity() * sizeof(Eigen::Vector2f) +
           strips.capacity() * sizeof(LaidStrip) +
           (steering_radius_mm.capacity() + fiber_angle_deg.capacity()) * sizeof(float) +
           events.capacity() * sizeof(TowEvent);
  }
};

}  // namespace stitchsim::verify
