#pragma once
// `stitchsim sequence --html`: one self-contained page (docs/sequence.md, "The page") showing
// per ply the courses on the part, the original and the new off-part paths side by side with
// the course order, and the report's figures; three.js embedded at build time. The page embeds
// the report's JSON (SequenceReportJson) as its figures' only source. Nothing here prints.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/program/afp_program.h"
#include "stitchsim/run/sequence_run.h"

namespace stitchsim::run {

/// One off-part stretch of a programme's tool path: the moves outside every lay-up between
/// one course's lay-up end (or the programme's start) and the next's lay-up start (or the
/// programme's end). Part frame, mm.
struct OffPartStretch {
  int course = -1;  ///< index into program.courses of the course it leads into; -1: after the last
  std::vector<Eigen::Vector3d> points;  ///< >= 2; its first and last moves' ends included
  double length_mm = 0.0;               ///< polyline length
};

/// The off-part stretches of `program.tool_path` (every gap with at least one move), in order,
/// flown from `start` (part frame, mm: the move from it to the path's first point leads the
/// first stretch); their lengths add up to program.offpart_length_mm plus that move.
std::vector<OffPartStretch> OffPartStretches(const program::AfpProgram& program,
                                             const Eigen::Vector3d& start);

/// The sequenced programme written (WriteSequencedProgram) and read back; nullopt if it does
/// not read (a bug).
std::optional<program::AfpProgram> ReadBackSequenced(const SequenceInputs& inputs,
                                                     const SequenceRun& run);

/// Fills each ply's flown_before_mm / flown_after_mm (o.plies, programme order) from the two
/// programmes' stretches: a stretch counts for the ply of the course it leads into, the last
/// (after every course) for the last course's ply. Both flown from `start` (part frame, mm).
void FillPlyFlown(const program::AfpProgram& original, const program::AfpProgram& sequenced,
                  const Eigen::Vector3d& start, SequenceOutcome& o);

/// The page's data: {"report": SequenceReportJson, "courses": per course (programme order) its
/// ply, number and lay-up polyline, "before" / "after": each programme's stretches and visits
/// in laying order (course: index into the original's courses; start: where it lays from)}.
/// Points rounded to 0.01 mm.
nlohmann::json SequencePageData(const SequenceRun& run, const program::AfpProgram& program);

/// The page (run/html/sequence.html with three.js and sequence.js); "" with `error` set when
/// an asset cannot be embedded (a bug).
std::string SequenceHtmlPage(const SequenceRun& run, const program::AfpProgram& program,
                             std::string& error);

}  // namespace stitchsim::run
