#pragma once
// Where an AFP head's tows lie on the surface (docs/afp.md, "Tows"): one model for the ply
// planner, which places them, and the afp.* rules, which judge what a programme lays. The
// compaction roller's tool frame: origin at the middle of the roller's contact line, z along
// the head axis (away from the surface), y along the travel, x = y cross z (to the right
// looking along the travel with the head above). Tow 1 is the leftmost (most negative x), tow
// k the rightmost; their centres are (i - (k + 1) / 2) w from the tool point, measured along
// the surface in the direction of tool x laid into the tangent plane. Part frame, mm.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "stitchsim/geom/surface.h"
#include "stitchsim/scene/head_spec.h"

namespace stitchsim::process {

struct TowLayout {
  int tows = 16;
  double width_mm = 6.35;
};

/// The head's tows (the `afp:` block of its spec).
TowLayout TowLayoutOf(const scene::HeadSpec& head);

/// Lateral offset of tow `tow`'s (1-based) centre from the tool point along tool x, mm.
double TowCentreOffset(const TowLayout& layout, int tow);

/// Bit mask of the layout's tows (bit i = tow i + 1).
std::uint64_t AllTows(const TowLayout& layout);

/// Which of the head's tows a programme of a ply laying `count` tows uses, numbered as the head
/// numbers them (docs/program-format.md, "Tows"): the `count` adjacent tows in the middle of the
/// head, first = (k - count) / 2 + 1 rounded down. When k - count is odd the one spare tow more
/// is on the right, and the band's centre lies w / 2 to the left (-x) of the tool point; the
/// planner lays the band there and the verifier, which places the head's tows by their
/// numbers, finds it there. Nothing but the tow numbers in M62 carries the band.
struct TowBand {
  int first = 1;   ///< head number of the band's leftmost tow
  int count = 16;  ///< tows in the band
  int Last() const { return first + count - 1; }
};

/// The band of `count` tows (1 .. k) on the head `head`.
TowBand PlyTowBand(const TowLayout& head, int count);

/// Every tow of the head.
inline TowBand WholeHead(const TowLayout& head) { return TowBand{1, head.tows}; }

/// Lateral offset of the band's centre from the tool point along tool x, mm (0, or -w / 2 for
/// PlyTowBand with k - count odd).
double BandCentreOffset(const TowLayout& head, const TowBand& band);

/// Bit mask of the band's tows as the head numbers them (bit t - 1 = head tow t).
std::uint64_t BandTows(const TowBand& band);

/// The k + 1 tow boundaries across the roller at one pose, left to right: boundary b is the
/// left edge of tow b + 1 (b = k: the right edge of tow k), walked along the surface from the
/// tool point's foot. `ok` false if the tool point's foot or a walk leaves the surface.
struct TowCross {
  bool ok = false;
  Eigen::Vector2d centre_uv = Eigen::Vector2d::Zero();  ///< foot of the tool point
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2d> boundary_uv;  ///< k + 1
  std::vector<Eigen::Vector3d> boundary;     ///< k + 1, on the surface
  /// k + 1 unit tangents at the boundaries: the direction of tool x at the foot carried along
  /// the walk (across the course, left to right; the normal to a boundary's line on the
  /// surface where the walk crosses it at a right angle).
  std::vector<Eigen::Vector3d> across;
};

/// The tow boundaries at `tool_part` (tool pose, part frame, mm). The tool point's foot is its
/// global closest point (geom::Surface::ProjectFrom); `uv_hint` (the previous pose's foot, or
/// nullptr) only speeds that search. A foot whose normal faces away from the head, on the far
/// side of a thin or closed part, is looked for again among grid points that face it.
/// `max_substep_mm` bounds the walk's chords (geom::WalkOnSurface); 0: half a tow width (the
/// walk is exact on a cylinder and a sphere, second order in the chord elsewhere; planner and
/// verifier both use the default).
TowCross TowsAt(const geom::Surface& surface, const Eigen::Isometry3d& tool_part,
                const TowLayout& layout, const Eigen::Vector2d* uv_hint,
                double max_substep_mm = 0.0);

/// The boundaries of `band`'s tows only: band.count + 1, boundary j the left edge of head tow
/// band.first + j (the same points as the whole head's boundaries band.first - 1 ..
/// band.Last(); tows outside the band may leave the surface).
TowCross TowsAt(const geom::Surface& surface, const Eigen::Isometry3d& tool_part,
                const TowLayout& layout, const TowBand& band, const Eigen::Vector2d* uv_hint,
                double max_substep_mm = 0.0);

}  // namespace stitchsim::process
