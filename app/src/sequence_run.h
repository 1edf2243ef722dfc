#pragma once
// `stitchsim sequence` (docs/sequence.md): what a run decided, shared by the command
// (sequence_cmd.cpp) and its report (sequence_report.cpp).
#include <array>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "sequence_costs.h"
#include "stitchsim/planner/sequence_precedence.h"
#include "stitchsim/program/afp_program.h"

namespace stitchsim::app {

/// Per measure (kMeasures order): axes, time s, tool mm.
using Costs = std::array<double, 3>;

struct SetOutcome {
  std::vector<int> courses;  ///< indices into program.courses, programme order
  std::vector<int> plies;    ///< ply numbers (M70 P) it holds
  std::string solver;        ///< what chose its order ("local", "seed", "given", "original")
  double seconds = 0.0;
  std::int64_t iterations = 0;
  bool kept_original = false;               ///< the solver's order cost more than the programme's
  Costs offpart_before{}, offpart_after{};  ///< moves into its courses (and home, last set)
  /// The set's own problem in the chosen measure (from where the previous set ended): the
  /// programme's order, the order chosen, and (--measure-gap, sets the exact solver takes)
  /// the optimum.
  double original_cost = 0.0, cost = 0.0;
  std::optional<double> optimum;
};

struct SequenceOutcome {
  std::string program_file, scene_file, output_file;
  Measure measure = Measure::kAxes;
  std::string solver;
  bool bidirectional = false, return_home = false, course_level = false;
  std::vector<SetOutcome> sets;
  std::vector<program::CourseVisit> before, after;  ///< whole programme
  std::vector<int> set_of_course;
  Costs offpart_before{}, offpart_after{}, layup{};
  double flown_offpart_before_mm = 0.0, flown_offpart_after_mm = 0.0;
  double seconds = 0.0;
};

/// The JSON report (docs/sequence.md, "Report").
void WriteSequenceJson(const SequenceOutcome& o, const program::AfpProgram& program,
                       std::ostream& out);
/// The text summary on stdout.
void PrintSequenceSummary(const SequenceOutcome& o);

/// Reads an order (a report's "order" array: ply, course, reversed) from a JSON file and maps
/// it onto `program`'s courses; false with an error printed (file, entry) when malformed, when
/// a course is unknown, missing or repeated.
bool ReadOrderFile(const std::string& file, const program::AfpProgram& program,
                   std::vector<program::CourseVisit>& order);

}  // namespace stitchsim::app
