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

/// The k + 1 tow boundaries across the roller at one pose, left to right: boundary b is the
/// left edge of tow b + 1 (b = k: the right edge of tow k), walked along the surface from the
/// tool point's foot. `ok` false if the tool point's foot or a walk leaves the surface.
struct TowCross {
  bool ok = false;
  Eigen::Vector2d centre_uv = Eigen::Vector2d::Zero();  ///< foot of the tool point
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2d> boundary_uv;  ///< k + 1
  std::vector<Eigen::Vector3d> boundary;     ///< k + 1, on the surface
};

/// The tow boundaries at `tool_part` (tool pose, part frame, mm). The tool point's foot is its
/// global closest point (geom::Surface::ProjectFrom); `uv_hint` (the previous pose's foot, or
/// nullptr) only speeds that search. A foot whose normal faces away from the head, on the far
/// side of a thin or closed part, is looked for again among grid points that face it.
/// `max_substep_mm` bounds the walk's steps (geom::WalkOnSurface); 0: half a tow width (the
/// walk's arc is exact on a circle: on the seed's wing a 1 mm step moves no boundary by more
/// than 3e-5 mm, and planner and verifier both use the default).
TowCross TowsAt(const geom::Surface& surface, const Eigen::Isometry3d& tool_part,
                const TowLayout& layout, const Eigen::Vector2d* uv_hint,
                double max_substep_mm = 0.0);

}  // namespace stitchsim::process
