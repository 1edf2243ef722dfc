#pragma once
// An AFP programme read back into its plies and courses (docs/program-format.md, "Fibre
// placement"; docs/sequence.md): per course the approach, the lay-up and the retract, from
// the codes M70 (ply), M71 (course), M72 (course end) and the tow codes M62/M63 in the modal
// state. The off-part sequencer (`stitchsim sequence`) reads a programme with it, reorders or
// reverses the courses and writes the programme again; the lay-up lines of a course laid in
// its written direction are copied verbatim.
//
// A course's parts, in written order:
// - approach: from its M71 up to (not including) the block that first adds a tow;
// - lay-up: from that block to the block that cuts the last tow laying (the mask returns to
//   0 for the last time before M72), inclusive; everything between is kept as written;
// - retract: the rest up to M72.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::program {

/// One station of a lay-up: a position the head stands at (the start of the lay-up, then the
/// end of each move in it), and the state in force when it leaves it (after that station's
/// codes). Part frame, mm and the tool pose (ToolPoseOf).
struct LayupStation {
  int source_line = 0;  ///< the block that moved here (the first station: the first tow block)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::uint64_t tows = 0;         ///< tows laying on the move that leaves this station
  bool head_retracted = false;    ///< M20 in force on that move
  Motion motion = Motion::kFeed;  ///< G0/G1 of that move (the last station: the mode in force)
  double feed_mm_per_min = 0.0;   ///< F in force on that move (0 if none yet)
};

/// The modal state a course's lay-up starts from in the original programme: a verbatim copy of
/// its lines needs the same state in force (the sequencer's approach restores it).
struct LayupEntry {
  LengthUnit units = LengthUnit::kMillimetre;
  Motion motion = Motion::kFeed;
  std::optional<double> feed_mm_per_min;
  bool head_retracted = false;
  std::optional<double> rail_mm;      ///< E in force, if set
  std::optional<double> rotator_deg;  ///< W in force, if set
};

struct AfpCourse {
  int ply = 0;               ///< P of the M70 in force (the scene's `plies:` position, 1-based)
  int number = 0;            ///< P of its M71
  int begin_line = 0;        ///< the M71 line
  int end_line = 0;          ///< the M72 line
  int layup_first_line = 0;  ///< first and last source line of the lay-up, inclusive
  int layup_last_line = 0;
  LayupEntry entry;
  std::vector<LayupStation> stations;  ///< >= 2; stations.front() / back(): lay-up start / end
  double layup_length_mm = 0.0;        ///< tool-point path length of the lay-up
};

struct AfpPly {
  int number = 0;       ///< P of its M70
  int line = 0;         ///< its first M70 line
  std::string comment;  ///< that line's comment (e.g. "PLY name=skin_0 angle=0")
  /// Its courses (indices into AfpProgram::courses), programme order. A sequenced programme
  /// may enter a ply several times (plies of one precedence set interleave): still one AfpPly.
  std::vector<int> courses;
};

/// The tool point after one block that moves (part frame, mm): the programme's path, every
/// move in written order (its off-part stretches are the lines outside every lay-up).
struct ToolPathPoint {
  int line = 0;  ///< the block's source line
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

struct AfpProgram {
  std::string file_name;
  ProgramHeader header;
  /// The source text, and where each line starts (line n is text[line_start[n-1]..]),
  /// without its newline. Kept so that lay-up lines are copied byte for byte.
  std::string text;
  std::vector<std::size_t> line_start;
  int prologue_last_line = 0;      ///< lines before the first M70 (setup: units, tool change)
  std::vector<AfpPly> plies;       ///< in programme order
  std::vector<AfpCourse> courses;  ///< in programme order
  /// The first tool pose the programme commands (the default home of the sequencer).
  std::optional<Eigen::Isometry3d> first_pose;
  /// Off-part tool-point path length of the programme as written: every move outside the
  /// lay-ups (approaches, retracts, moves between courses), mm.
  double offpart_length_mm = 0.0;
  /// Every block that sets the tool point (X, Y, Z all known), in order: the path whose
  /// length less the lay-ups' is offpart_length_mm.
  std::vector<ToolPathPoint> tool_path;

  std::string_view Line(int line) const;  ///< 1-based source line, without its newline
};

/// Reads a whole programme. Errors (exit 2 in the CLI), each at its file:line, code in
/// parentheses: every reader and modal-state diagnostic; no M71 in the programme
/// (`sequence-no-courses`); a course that adds no tow on a feed move with the head lowered
/// (`sequence-empty-course`); tows still laying at M72 (`sequence-open-tows`); a course before
/// any M70, a course number repeated within its ply, or M70 P0 (`sequence-marks-order`); a move
/// with unknown axes in a lay-up (`sequence-incomplete-pose`). nullopt when any error was reported.
std::optional<AfpProgram> ReadAfpProgram(std::istream& in, const Dialect& dialect,
                                         std::string file_name, DiagnosticSink& sink);

/// A course in the order to lay it: its index in AfpProgram::courses and whether it is laid
/// backwards (head turned 180 deg about the tool z, tows mirrored, stations in reverse).
struct CourseVisit {
  int course = 0;
  bool reversed = false;
  friend bool operator==(const CourseVisit&, const CourseVisit&) = default;
};

/// The lay-up start or end pose of a course laid in `reversed` direction (a reversed
/// course starts at the forward end, tool frame turned 180 deg about its z).
Eigen::Isometry3d LayupStartPose(const AfpCourse& course, bool reversed);
Eigen::Isometry3d LayupEndPose(const AfpCourse& course, bool reversed);

/// Tow `tow` (1-based) of `tow_count` seen from a head turned 180 deg: tow_count + 1 - tow;
/// and a whole mask mirrored the same way.
int MirrorTow(int tow, int tow_count);
std::uint64_t MirrorTows(std::uint64_t tows, int tow_count);

/// The stations of `course` laid backwards: stations in reverse order, poses turned 180 deg
/// about the tool z, and on each move the mirror of the forward mask on that move.
std::vector<LayupStation> ReversedStations(const AfpCourse& course, int tow_count);

/// One off-part block the sequencer writes between lay-ups (and before the first, after the
/// last): a move to `pose` with `motion`, the head state, optional feed, and a comment.
struct OffPartBlock {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Motion motion = Motion::kRapid;
  bool head_retracted = true;
  std::optional<double> feed_mm_per_min;
  std::string comment;
};

/// The off-part blocks before visit `index` of the order (index 0: from home), and after the
/// last (index == order size: to home or nothing). The writer calls it once per gap.
using OffPartSource = std::function<std::vector<OffPartBlock>(std::size_t index)>;

struct AfpWriteOptions {
  int tow_count = 16;  ///< for mirroring reversed courses (the head's tows)
  /// Header entries added to the programme's own (e.g. sequenced=...); a key the programme's
  /// header already has takes the new value (a programme sequenced twice stays readable).
  std::vector<std::pair<std::string, std::string>> header_extra;
};

/// Writes the programme with its courses in `order` (every course exactly once; plies' M70
/// written whenever the ply changes, with the original comment): the prologue as written, then
/// per visit M71 P<n> (same number and comment), the off-part blocks (the last of them must
/// leave the head at the lay-up start with the lay-up's entry state, which the writer then
/// restores word by word: units, mode, feed, head, E, W), the lay-up (verbatim when forward;
/// regenerated from ReversedStations when reversed: every move written with its full pose, tow
/// codes from the mask changes, M20/M21 from head changes, F when it changes), M72; then the
/// blocks after the last visit and M30. Angles written in the dialect's Euler order.
void WriteAfpProgram(std::ostream& out, const AfpProgram& program, const Dialect& dialect,
                     std::span<const CourseVisit> order, const OffPartSource& offpart,
                     const AfpWriteOptions& options);

}  // namespace stitchsim::program
