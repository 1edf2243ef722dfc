#pragma once
// Constraint-aware raster stitching of a large preform (seed 001, docs/raster.md): straight
// rows along u at a row spacing, stitches at a pitch, constraint footprints (stringers,
// intercostals, spar caps) either jumped (retract, traverse, lower) or avoided by filling the
// bays between them serpentine-wise; regions split among working heads; user code blocks at
// events. PlanRaster makes the plan (pure data: regions, head sections, passes and the
// transits between them); WriteRasterProgram turns a plan into programme text, streaming.

#include <Eigen/Geometry>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/code_library.h"
#include "stitchsim/planner/plan_progress.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/footprint.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

enum class RasterStrategy { kJump, kSerpentine };
std::optional<RasterStrategy> ParseRasterStrategy(std::string_view text);
std::string_view ToString(RasterStrategy strategy);

struct RasterOptions {
  RasterStrategy strategy = RasterStrategy::kJump;
  double pitch_mm = 2.54;        ///< stitch length along a row (0.1 in: 10 stitches/in)
  double row_spacing_mm = 5.08;  ///< distance between rows (0.2 in)
  /// Kept clear around each constraint footprint beyond the head's keep-out (the larger of
  /// the needle spread and the head spec's envelope radius).
  double margin_mm = 12.7;
  /// A retracted head flies this much above the tallest constraint (mm).
  double lift_clearance_mm = 20.0;
  double edge_margin_mm = 0.0;      ///< kept clear inside the surface domain edges
  int heads = 1;                    ///< heads the regions are split among
  std::vector<int> out_of_service;  ///< 1-based head numbers that get nothing
  /// Stitch only this (u, v) window (mm); default the whole surface domain.
  std::optional<Eigen::AlignedBox2d> region;
  UserCodeLibrary library;
  /// (rows so far, rows): the plan's row pieces, each counted 0.1 when its stitches are
  /// counted, 0.1 when its passes are built (PlanRaster) and 0.8 when it is written
  /// (WriteRasterProgram), about the shares of the run's time they take. Null: not called.
  PlanProgress progress;
};

/// The defaults with the scene's `raster:` values (pitch, row spacing, margin) where it gives
/// them.
RasterOptions RasterOptionsFor(const scene::Scene& scene);

/// A piece of one row to stitch: the row's v and the u-range of clear surface (mm).
struct RasterRowPiece {
  long row = 0;  ///< global row index
  double v_mm = 0.0;
  double u_begin_mm = 0.0;
  double u_end_mm = 0.0;
};

/// A region handed to one head: one row (jump) or one bay (serpentine).
struct RasterRegion {
  std::vector<RasterRowPiece> pieces;  ///< by row, then by u
  long stitches = 0;                   ///< stitches of its pieces counted along +u
};

/// How the head gets from the last stitch of one pass to the first point of the next, the
/// needles out. The turn comes first when the head turns by more than 90 deg.
struct RasterTransit {
  bool jump = false;          ///< retract, fly up the normals, across and down, lower
  double lift_mm = 0.0;       ///< jump: flight height above both ends, along their normals
  bool quarter_turn = false;  ///< a quarter turn about the tool z axis first (unwinds the wrist)
  double turn_sign = 1.0;     ///< sense of that quarter turn
};

/// One row piece stitched in one direction.
struct RasterPass {
  RasterRowPiece piece;
  double direction = 1.0;  ///< +1: from u_begin along +u; -1: from u_end along -u
  long stitches = 0;       ///< whole stitches of one pitch (3D chord) from the start end, > 0
  bool row_start = false;  ///< the first pass of its row (user row_start codes)
  /// From the pass before; nullopt for the programme's first pass (a plain rapid to it).
  std::optional<RasterTransit> transit;
};

/// The work of one working head, in order.
struct RasterSection {
  int head = 0;             ///< 1-based head number
  std::size_t regions = 0;  ///< regions handed to it
  std::vector<RasterPass> passes;
};

/// A raster plan: pure data, written as text by WriteRasterProgram.
struct RasterPlan {
  RasterStrategy strategy = RasterStrategy::kJump;
  double pitch_mm = 0.0;
  double row_spacing_mm = 0.0;
  int heads = 1;
  bool head_sections = false;  ///< each section opens with M60 P<head> (more than one head)
  std::vector<scene::Footprint> footprints;  ///< grown by the margin and the head's keep-out
  double flight_clearance_mm = 0.0;  ///< jumps fly this high at least: tallest constraint + lift
  std::vector<RasterRegion> regions;
  long row_pieces = 0;                  ///< pieces over all regions (the progress's rows)
  std::vector<RasterSection> sections;  ///< working heads that got regions, in head order
  long stitches = 0;                    ///< the header's total: the regions' stitches
  UserCodeLibrary library;
};

/// Plans the raster of `scene`. Diagnostics "plan-raster-..." for a bad option or surface;
/// nullopt then.
std::optional<RasterPlan> PlanRaster(const scene::Scene& scene, const RasterOptions& options,
                                     DiagnosticSink& sink);

/// What WriteRasterProgram wrote.
struct RasterSummary {
  long stitches = 0;
  long rows = 0;   ///< row pieces stitched (a row split by a jump counts once per piece)
  long jumps = 0;  ///< retract - traverse - lower sequences
  long bays = 0;   ///< regions (serpentine: bays; jump: rows)
  long turns = 0;  ///< direction changes without retracting (serpentine inside a bay)
  long user_blocks = 0;
  long motion_lines = 0;
  std::vector<long> head_stitches;  ///< per head (1-based index - 1), out of service = 0
  double stitching_s = 0.0;
  double traverse_s = 0.0;
  double TotalS() const { return stitching_s + traverse_s; }
};

/// Writes `plan` (made for `scene`) as a programme (mm, G90, one coupled G1 per stitch)
/// through the dialect's writer, streaming: memory does not grow with the stitches.
/// `progress` as RasterOptions::progress (from where PlanRaster left it).
RasterSummary WriteRasterProgram(const RasterPlan& plan, const scene::Scene& scene,
                                 const program::Dialect& dialect, std::ostream& out,
                                 const PlanProgress& progress = nullptr);

/// PlanRaster, then WriteRasterProgram.
std::optional<RasterSummary> WriteRasterProgram(const scene::Scene& scene,
                                                const RasterOptions& options,
                                                const program::Dialect& dialect, std::ostream& out,
                                                DiagnosticSink& sink);

}  // namespace stitchsim::planner
