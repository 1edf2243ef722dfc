#pragma once
// The precedence network of an AFP programme (seed 004, section 3.1; docs/sequence.md): which
// courses may be laid in any order among themselves. Consecutive plies whose courses do not
// overlap on the surface join one precedence set; sets keep the programme's order. Overlap is
// tested on the tow footprints the programme lays (process/afp_tows.h at the lay-up poses),
// not on bounding boxes. Optionally (off by default) a course moves into an earlier set when
// nothing it overlaps is laid between (the seed's further work, course-level precedence).
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/geom/surface.h"
#include "stitchsim/process/afp_tows.h"
#include "stitchsim/program/afp_program.h"

namespace stitchsim::planner {

/// What one course lays: convex quads of tow strip between consecutive lay-up stations, in
/// the surface's (u, v) and in mm^2 of surface, plus its (u, v) bounding box.
struct CourseFootprint {
  struct Quad {
    Eigen::Vector2d uv[4];  ///< counter-clockwise in (u, v)
  };
  std::vector<Quad> quads;
  Eigen::Vector2d uv_min = Eigen::Vector2d::Zero();
  Eigen::Vector2d uv_max = Eigen::Vector2d::Zero();
  double area_mm2 = 0.0;  ///< laid area (surface area, by the area element)
  bool ok = true;         ///< false when a tow walk left the surface (reported by the caller)
};

/// The footprint of every course of `program` (same order), laid as written.
std::vector<CourseFootprint> CourseFootprints(const geom::Surface& surface,
                                              const process::TowLayout& layout,
                                              const program::AfpProgram& program);

/// Surface area (mm^2) two footprints share; 0 when they only touch.
double OverlapAreaMm2(const geom::Surface& surface, const CourseFootprint& a,
                      const CourseFootprint& b);

struct PrecedenceOptions {
  /// Two courses overlap when they share more than this area (mm^2): neighbouring courses of
  /// a ply that meet edge to edge share ~0; a tow lying on another shares its width per mm.
  double min_overlap_mm2 = 1.0;
  bool course_level = false;  ///< let a course move into an earlier set (off by default)
};

struct PrecedenceSet {
  std::vector<int> courses;  ///< indices into AfpProgram::courses, programme order
  std::vector<int> plies;    ///< indices into AfpProgram::plies whose courses it holds
};

struct PrecedenceNetwork {
  std::vector<PrecedenceSet> sets;  ///< in laying order
  /// For every course, the set it is in, and (report, tests) the first earlier course of
  /// another ply it overlaps, -1 if none.
  std::vector<int> set_of_course;
  std::vector<int> blocker_of_course;
};

/// Builds the network (seed's ply-level rule; course-level when asked).
PrecedenceNetwork BuildPrecedence(const geom::Surface& surface, const program::AfpProgram& program,
                                  const std::vector<CourseFootprint>& footprints,
                                  const PrecedenceOptions& options);

/// True when `order` (a permutation of all courses) lays no course before one it overlaps and
/// that precedes it in the programme (the part is the same part); tests and the CLI's --order.
bool RespectsPrecedence(const geom::Surface& surface, const program::AfpProgram& program,
                        const std::vector<CourseFootprint>& footprints,
                        const std::vector<program::CourseVisit>& order, double min_overlap_mm2,
                        int* first_violation = nullptr);

}  // namespace stitchsim::planner
