#pragma once
// The G-code dialect as data: which letter carries which axis, the Euler order of A B C, how
// many decimals the writer prints, and which G/M/T codes mean what. The built-in default
// equals models/dialect/default.yaml; docs/program-format.md describes both.

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"

namespace stitchsim::program {

/// The ten pose/machine axes a block can set, in the writer's word order.
enum class Axis : int {
  kX,           // tool point x in the part frame, length
  kY,           // tool point y, length
  kZ,           // tool point z, length
  kA,           // first Euler angle of the head orientation, degrees
  kB,           // second Euler angle, degrees
  kC,           // third Euler angle, degrees
  kDrive,       // cumulative drive-axis distance (one stitch per stitch length), length
  kPathLength,  // cumulative stitching path length, length
  kRail,        // rail carriage position, length
  kRotator,     // rotator (turntable) angle, degrees
};
inline constexpr std::size_t kAxisCount = 10;

/// True for A, B, C and the rotator (degrees); false for lengths.
constexpr bool IsAngular(Axis axis) {
  return axis == Axis::kA || axis == Axis::kB || axis == Axis::kC || axis == Axis::kRotator;
}

/// Role name used in dialect files: "x", "y", "z", "a", "b", "c", "drive", "path_length",
/// "rail", "rotator".
std::string_view RoleName(Axis axis);

/// What a G code number means in a dialect.
enum class GMeaning {
  kUnknown,
  kRapid,                    // G0: rapid positioning
  kFeed,                     // G1: linear move at the programmed feed
  kInch,                     // G20: lengths in inches from here on
  kMillimetre,               // G21: lengths in millimetres from here on
  kAbsolute,                 // G90: absolute coordinates (the only distance mode)
  kUnsupportedDistanceMode,  // G91 etc.: recognised only to say it is not supported
  kUnsupportedMotion,        // G2/G3 etc.: arcs; the planner writes linear moves only
};

/// What an M code number means in a dialect.
enum class MMeaning {
  kUnknown,
  kToolChange,   // M6: mount the head selected by the last T word
  kStitchOn,     // M10: stitching on
  kStitchOff,    // M11: stitching off
  kHeadRetract,  // M20: retract the head (jump a constraint)
  kHeadLower,    // M21: lower the head back to the work
  kProgramEnd,   // M30: end of programme; no words may follow
  kHeadSection,  // M60 P<n>: the following blocks belong to head n
  kUserMacro,    // M100..M199: user functions, passed through, no kinematic effect
  kTowAdd,       // M62 P<n>: AFP tow n (1-based) restarts here; P0: every tow of the head
  kTowCut,       // M63 P<n>: AFP tow n is cut here; P0: every tow
  kPlyStart,     // M70 P<n>: ply n starts (AFP; docs/program-format.md, "Fibre placement")
  kCourseStart,  // M71 P<n>: course n of the ply starts
  kCourseEnd,    // M72: the course ends
};
/// Number of MMeaning values.
inline constexpr int kMMeaningCount = static_cast<int>(MMeaning::kCourseEnd) + 1;

struct GCodes {
  int rapid = 0;
  int feed = 1;
  int inch = 20;
  int millimetre = 21;
  int absolute = 90;
  std::vector<int> unsupported_distance_modes = {91};
  std::vector<int> unsupported_motions = {2, 3};
  friend bool operator==(const GCodes&, const GCodes&) = default;
};

/// How the controller times the motion (docs/timing.md): the time law sim::TimingSink plans.
struct TrajectorySpec {
  /// Continuous-path blending between consecutive lines (G64-like); false: an exact stop at
  /// every line end (G61-like).
  bool continuous = true;
  double ramp_time_s = 0.25;  ///< time to reach the programmed speed (until an axis caps it)
  int look_ahead_lines = 64;  ///< lines the controller plans ahead
  friend bool operator==(const TrajectorySpec&, const TrajectorySpec&) = default;
};

/// Most AFP tows a programme can address (M62/M63 P1..P64; the modal tow mask is 64 bits).
inline constexpr int kMaxTows = 64;

struct MCodes {
  int tool_change = 6;
  int stitch_on = 10;
  int stitch_off = 11;
  int head_retract = 20;
  int head_lower = 21;
  int program_end = 30;
  int head_section = 60;
  int tow_add = 62;
  int tow_cut = 63;
  int ply_start = 70;
  int course_start = 71;
  int course_end = 72;
  int user_macro_first = 100;  // inclusive
  int user_macro_last = 199;   // inclusive
  friend bool operator==(const MCodes&, const MCodes&) = default;
};

/// One T number and the head it mounts ("rs535", "rs566", "afp").
struct ToolEntry {
  int number = 0;
  std::string head;
  friend bool operator==(const ToolEntry&, const ToolEntry&) = default;
};

/// A dialect: immutable description used by the reader, writer and modal state tracker.
/// Letters are upper case; G and M are fixed by ISO 6983 and not part of the dialect.
struct Dialect {
  std::string name = "default";
  /// Word letter per axis, indexed by Axis.
  std::array<char, kAxisCount> axis_letters = {'X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'E', 'W'};
  char feed_letter = 'F';   // feed, programme length unit per minute
  char block_letter = 'N';  // block (sequence) number
  char tool_letter = 'T';   // head selection, see tools
  char param_letter = 'P';  // integer parameter (head index of M60)
  /// Fixed-axes order of (A, B, C): "XYZ" means R = Rz(C) * Ry(B) * Rx(A).
  std::string euler_order = "XYZ";
  LengthUnit default_units = LengthUnit::kMillimetre;  // in force before any G20/G21
  int length_decimals = 6;                             // writer: digits after the point for lengths
  int angle_decimals = 6;                              // writer: digits after the point for angles
  int feed_decimals = 3;                               // writer: digits after the point for F
  int max_line_length = 1024;                          // characters per line, line ending excluded
  GCodes g;
  MCodes m;
  std::vector<ToolEntry> tools = {{1, "rs535"}, {2, "rs566"}, {3, "afp"}};
  TrajectorySpec trajectory;

  /// The built-in dialect, equal to models/dialect/default.yaml.
  static const Dialect& Default();

  GMeaning MeaningOfG(int code) const;
  MMeaning MeaningOfM(int code) const;
  /// The tool with this T number, or nullptr.
  const ToolEntry* FindTool(int number) const;
  /// Digits after the point the writer uses for `axis`.
  int DecimalsFor(Axis axis) const { return IsAngular(axis) ? angle_decimals : length_decimals; }

  friend bool operator==(const Dialect&, const Dialect&) = default;
};

/// Checks letters (distinct, A-Z, not G/M), Euler order, decimals, line limit and codes
/// (distinct, non-negative). Reports "dialect-*" diagnostics against `file_name`.
bool ValidateDialect(const Dialect& dialect, const std::string& file_name, DiagnosticSink& sink);

/// Reads a dialect YAML file; keys left out keep their Dialect::Default() value. Returns
/// nullopt (with diagnostics) if the file is missing, malformed or invalid.
std::optional<Dialect> LoadDialect(const std::filesystem::path& path, DiagnosticSink& sink);

/// As LoadDialect, from YAML text; `file_name` is used in diagnostics.
std::optional<Dialect> LoadDialectFromString(std::string_view yaml, const std::string& file_name,
                                             DiagnosticSink& sink);

}  // namespace stitchsim::program
