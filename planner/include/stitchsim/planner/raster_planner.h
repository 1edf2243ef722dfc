#pragma once
// Constraint-aware raster stitching of a large preform (seed 001, docs/raster.md): straight
// rows along u at a row spacing, stitches at a pitch, constraint footprints (stringers,
// intercostals, spar caps) either jumped (retract, traverse, lower) or avoided by filling the
// bays between them serpentine-wise; regions split among working heads; user code blocks at
// events. The programme streams out as it is generated.

#include <Eigen/Geometry>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

enum class RasterStrategy { kJump, kSerpentine };
std::optional<RasterStrategy> ParseRasterStrategy(std::string_view text);
std::string_view ToString(RasterStrategy strategy);

/// A named block of user codes inserted at an event (e.g. needle cooling M110).
struct UserCodeBlock {
  enum class Event { kEveryStitches, kRowStart, kBeforeJump };
  std::string name;
  Event event = Event::kEveryStitches;
  long every_stitches = 0;   ///< kEveryStitches: after every this many stitches (per programme)
  std::vector<int> m_codes;  ///< user macros, inside the dialect's user range
  std::optional<int> param;  ///< P word, if any
};

struct UserCodeLibrary {
  std::vector<UserCodeBlock> blocks;
};

/// Parses a code library (YAML, docs/raster.md); diagnostics "library-..." with line:col.
std::optional<UserCodeLibrary> ParseUserCodeLibrary(std::string_view yaml,
                                                    const std::string& file_name,
                                                    const program::Dialect& dialect,
                                                    DiagnosticSink& sink);
std::optional<UserCodeLibrary> LoadUserCodeLibrary(const std::filesystem::path& file,
                                                   const program::Dialect& dialect,
                                                   DiagnosticSink& sink);

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
};

/// The defaults with the scene's `raster:` values (pitch, row spacing, margin) where it gives
/// them.
RasterOptions RasterOptionsFor(const scene::Scene& scene);

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

/// Plans and writes the raster programme (mm, G90, one coupled G1 per stitch) through the
/// dialect's writer, streaming: memory grows with the number of regions, not of stitches.
/// Diagnostics "plan-raster-..." for a bad option or surface; nullopt then.
std::optional<RasterSummary> WriteRasterProgram(const scene::Scene& scene,
                                                const RasterOptions& options,
                                                const program::Dialect& dialect, std::ostream& out,
                                                DiagnosticSink& sink);

}  // namespace stitchsim::planner
