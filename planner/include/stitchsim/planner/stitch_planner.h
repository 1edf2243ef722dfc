#pragma once
// The 3D stitch-path planner (seed 000 section 3.2.2): stitch count, equal-arc-length stitch
// points on the surface, tool frames (z = surface normal at the stitch start, y = chord),
// and the coupled / decoupled / auto programme. Streams: a million stitches never sit in
// memory at once.

#include <Eigen/Geometry>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/geom/curve.h"
#include "stitchsim/planner/plan_progress.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::planner {

enum class Mode { kCoupled, kDecoupled, kAuto };
std::optional<Mode> ParseMode(std::string_view text);
std::string_view ToString(Mode mode);

struct StitchPlanOptions {
  Mode mode = Mode::kAuto;
  std::optional<double> nominal_stitch_length_mm;  ///< default: the scene's
  /// Evaluate what a coupled line would do for every stitch even when the mode does not
  /// need it (auto mode always does).
  bool evaluate_coupled = false;
  /// After each stitch Next() returns: (stitches so far, stitch count). Null: not called.
  PlanProgress progress;
};

/// One stitch as planned. Poses are tool-point poses in the part frame (translation mm).
struct PlannedStitch {
  int index = 0;                   ///< 1-based
  Eigen::Isometry3d start;         ///< frame of this stitch at its start point
  Eigen::Isometry3d end;           ///< frame of the next stitch at this stitch's end point
  double arc_length_end_mm = 0.0;  ///< = index * stitch length
  std::string segment_label;       ///< 2D segment the stitch's chord midpoint is on
  bool decoupled = false;          ///< translation then rotation (two lines)
  /// What a coupled line would do to the needles (the auto-mode decision input): side force
  /// per needle, rotation in the preform. Computed in auto mode or with evaluate_coupled.
  process::WindowMetrics coupled;
  std::string exceeded_limit;  ///< rule the coupled stitch would break; empty if none
  double rotation_rad = 0.0;   ///< head rotation from start to end frame
};

/// Time estimate (seconds), from the head spec: feed from the stitch rate, rotation lines at
/// the head's rotation speed plus a settle time.
struct CycleTime {
  double stitching_s = 0.0;  ///< translation (needles working) time
  double rotation_s = 0.0;   ///< pure rotation lines, settle included
  double Total() const { return stitching_s + rotation_s; }
};

/// Streams the stitches of one path.
class StitchPathPlanner {
 public:
  /// Validates and sizes the plan; diagnostics ("plan-...") for a path shorter than one
  /// stitch, a bad stitch length, a degenerate frame.
  static std::optional<StitchPathPlanner> Create(const scene::Scene& scene,
                                                 const scene::PathSpec& path,
                                                 const StitchPlanOptions& options,
                                                 DiagnosticSink& sink);

  int StitchCount() const { return count_; }
  double StitchLengthMm() const { return stitch_length_mm_; }
  /// The stitch length asked for (the options', else the scene's); StitchLengthMm() divides
  /// the path in equal stitches near it.
  double NominalStitchLengthMm() const { return nominal_stitch_length_mm_; }
  double PathLengthMm() const { return path_.Length(); }
  bool Closed() const { return path_.Closed(); }
  Mode GetMode() const { return mode_; }
  const process::ProcessModel& Process() const { return process_; }
  /// Tool pose at the path start (frame of stitch 1).
  const Eigen::Isometry3d& StartPose() const { return start_pose_; }
  /// The next stitch; false after the last one.
  bool Next(PlannedStitch& out);

 private:
  StitchPathPlanner(const scene::Scene& scene, const scene::PathSpec& path);
  Eigen::Isometry3d FrameAt(const geom::PathPoint& at, const geom::PathPoint& next) const;
  Eigen::Isometry3d EndFrame() const;

  const scene::Scene* scene_;
  const scene::PathSpec* spec_;
  geom::SurfacePath path_;
  process::ProcessModel process_;
  process::NeedleLimits limits_;
  Mode mode_ = Mode::kAuto;
  bool evaluate_coupled_ = true;
  PlanProgress progress_;
  int count_ = 0;
  double stitch_length_mm_ = 0.0;
  double nominal_stitch_length_mm_ = 0.0;
  int next_index_ = 1;
  geom::PathPoint current_;    // stitch start point
  geom::PathPoint following_;  // its end point
  Eigen::Isometry3d current_frame_;
  Eigen::Isometry3d start_pose_;
};

/// What one planned stitch lays in the programme: one coupled line to `end`, or (decoupled)
/// a pure translation to `translate` (the whole stitch cycle, orientation kept) and then a
/// pure rotation to `end` (needles out). Tool-point poses in the part frame (translation mm).
struct StitchMoves {
  bool decoupled = false;
  Eigen::Isometry3d translate;  ///< decoupled: the stitch's start frame at its end point
  Eigen::Isometry3d end;        ///< frame of the next stitch at this stitch's end point
  double drive_mm = 0.0;        ///< drive (U) and path length (V) after the stitch, mm
  double rotation_rad = 0.0;    ///< head rotation from start to end frame
  int Lines() const { return decoupled ? 2 : 1; }  ///< motion lines it takes
};

/// The moves of `stitch`, planned at `stitch_length_mm`.
StitchMoves MovesOf(const PlannedStitch& stitch, double stitch_length_mm);

/// The head spec's rates the time estimate uses.
struct StitchTiming {
  double stitch_time_s = 0.0;         ///< one stitch cycle: 60 / stitch rate per minute
  double rotation_speed_rad_s = 0.0;  ///< head rotation speed, rad/s
  double settle_time_s = 0.0;         ///< after each pure rotation line, s
};
StitchTiming StitchTimingOf(const scene::StitchProcessSpec& spec);

/// Adds the time of `moves` to `time`: decoupled, a stitch cycle of stitching and its rotation
/// at the rotation speed plus the settle time; coupled, the longer of the two as stitching.
void AddStitchTime(const StitchMoves& moves, const StitchTiming& timing, CycleTime& time);

/// What WriteStitchProgram wrote.
struct ProgramSummary {
  int stitches = 0;
  int decoupled = 0;
  double stitch_length_mm = 0.0;          ///< as planned (the path split in equal stitches)
  double nominal_stitch_length_mm = 0.0;  ///< asked for: the option's, else the scene's
  double path_length_mm = 0.0;
  long motion_lines = 0;
  CycleTime time;
  Mode mode = Mode::kAuto;
};

/// Writes the programme of one planned path (mm, G90) through the dialect's writer,
/// streaming: per stitch, its moves (MovesOf), their time (AddStitchTime), their text.
ProgramSummary WriteStitchProgram(StitchPathPlanner& planner, const scene::Scene& scene,
                                  const std::string& path_name, const program::Dialect& dialect,
                                  std::ostream& out);

/// All stitches of a path in memory (tests, small paths).
std::vector<PlannedStitch> CollectStitches(StitchPathPlanner& planner);

}  // namespace stitchsim::planner
