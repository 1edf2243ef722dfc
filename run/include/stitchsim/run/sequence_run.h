#pragma once
// `stitchsim sequence` as a library (docs/sequence.md): the inputs loaded and checked, the
// courses of every precedence set ordered, the costs before and after, the off-part moves
// regenerated. Two steps, so that the caller prints the inputs' diagnostics before the run's
// progress: LoadSequenceInputs, then RunSequence. Nothing here prints.
#include <Eigen/Geometry>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/planner/plan_progress.h"
#include "stitchsim/planner/sequence/precedence.h"
#include "stitchsim/program/afp_program.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/sequence_costs.h"

namespace stitchsim::run {

enum class SequenceSolver { kLocal, kSeed, kExact };

/// What a sequence run is asked to do (the CLI's options).
struct SequenceOptions {
  std::string program_file;       ///< AFP programme to reorder (M70/M71/M72 marked)
  std::string scene_file;         ///< its scene: surface, plies, AFP head
  std::string output_file;        ///< where the caller writes the programme (named in the report)
  scene::LoadOptions scene_load;  ///< how the scene's paths resolve
  Measure measure = Measure::kAxes;                ///< the cost minimised (--cost)
  SequenceSolver solver = SequenceSolver::kLocal;  ///< exact: sets over 16 courses use local
  bool bidirectional = false;                      ///< courses may be laid backwards
  bool return_home = false;                        ///< back to home after the last course
  bool course_level = false;   ///< course-level precedence (a course may move to an earlier set)
  bool measure_gap = false;    ///< also solve sets of 13 to 16 courses exactly (the optimum)
  double time_limit_s = 10.0;  ///< the local search's limit per set, s (0: none)
  int jobs = 0;  ///< threads for the local search's starts (0: the cores; same answer on any)
  /// The local search's starts and its stagnation cap (rounds without a cheaper answer that
  /// end a start), per set; 0: the defaults (planner::LocalSearchOptions, the large-run rule).
  int starts = 0;
  std::int64_t stagnation = 0;
  std::string home;  ///< "X,Y,Z,A,B,C", part frame (mm, deg); empty: the programme's first pose
  std::string order_file;  ///< a report's "order" to lay instead of solving; empty: solve
};

/// A problem with no file position: the caller prints "error[code]: message".
struct SequenceError {
  std::string code;     ///< stable, kebab-case ("sequence-bad-home"); empty: no error
  std::string message;  ///< for people
};

/// Everything a run reads, validated (LoadSequenceInputs).
struct SequenceInputs {
  LoadedScene loaded;           ///< owned: the scene and its cell's robot model
  program::AfpProgram program;  ///< the programme as read
  Eigen::Isometry3d home = Eigen::Isometry3d::Identity();  ///< part frame, mm
  std::vector<double> axis_weights;  ///< per joint, model order (head's sequence.axis_weights)
  std::vector<program::CourseVisit> given_order;  ///< the order file's; empty without one
  double load_seconds = 0.0;  ///< wall time loading and checking took, s (counted in the run's)
};

/// Loads and checks the scene (an AFP head), the programme (its plies the scene's, its tows the
/// head's), the head's axis weights, the home pose and the order file. Diagnostics with a file
/// position go to `sink`; nullopt on any error, with `error` set when the problem has none
/// (bad --home, a bad order file).
std::optional<SequenceInputs> LoadSequenceInputs(const SequenceOptions& options,
                                                 DiagnosticSink& sink, SequenceError& error);

/// What one precedence set's run decided.
struct SetOutcome {
  std::vector<int> courses;  ///< indices into program.courses, programme order
  std::vector<int> plies;    ///< ply numbers (M70 P) it holds
  std::string solver;        ///< what chose its order ("local", "seed", "exact", "given")
  planner::SolveStatus status = planner::SolveStatus::kGiven;  ///< how that solver stopped
  double seconds = 0.0;                                        ///< the solver's wall time, s
  std::int64_t iterations = 0;                                 ///< the solver's work count
  bool kept_original = false;               ///< the solver's order cost more than the programme's
  Costs offpart_before{}, offpart_after{};  ///< moves into its courses (and home, last set)
  /// The set's own problem in the chosen measure (from where the previous set ended in the
  /// order laid; home after the last set with return_home): the programme's order (the cost at
  /// which the safeguard keeps it), and the order chosen.
  double original_cost = 0.0, cost = 0.0;
  /// The same problem's optimum (the exact solver: sets of at most kExactByDefaultCourses
  /// courses, or kMaxExactCourses with measure_gap, or the exact solver's own answer).
  std::optional<double> optimum;
  /// A lower bound on the same problem's cost (planner::ComputeLowerBound), how it was found
  /// ("held-karp", "exact", "trivial") and its wall time, s; filled by the run after solving.
  /// Absent only for a given order that interleaves the sets (no per-set problem).
  std::optional<double> bound;
  std::string bound_method;
  double bound_seconds = 0.0;
  /// (cost - best lower) / best lower, the best lower being the optimum when known, else the
  /// bound (a fraction, 0.01 = 1 %); 0 when both are 0; absent when the best lower is 0 and the
  /// cost is not, or without a bound.
  std::optional<double> gap;
};

/// One ply's share of the run's figures: the move into a course counts for that course's ply,
/// the moves after the last course (home) for the last course's ply, as a set's do.
struct PlyOutcome {
  int ply = 0;                              ///< its M70 P (the scene's `plies:` position)
  std::string comment;                      ///< its M70 line's comment ("PLY name=... angle=...")
  int courses = 0;                          ///< how many courses it has
  Costs offpart_before{}, offpart_after{};  ///< every measure (units: MeasureUnit)
  /// Off-part tool path (run/sequence_html.h OffPartStretches), mm: the programme as written
  /// and the sequenced programme as written (read back); and its lay-ups' tool path, mm.
  double flown_before_mm = 0.0, flown_after_mm = 0.0, layup_mm = 0.0;
};

/// Sets of at most this many courses are also solved exactly by every run (instant there), for
/// the optimum and the gap; `measure_gap` raises it to planner::kMaxExactCourses.
inline constexpr int kExactByDefaultCourses = 12;

/// What a run decided, for the report and the summary.
struct SequenceOutcome {
  std::string program_file, scene_file, output_file;  ///< as given in the options
  Measure measure = Measure::kAxes;
  std::string solver;  ///< "local", "seed", "exact" or "given" (--order)
  bool bidirectional = false, return_home = false, course_level = false;
  /// The precedence whose answer was taken: "course" (--course-level) or "ply"; with
  /// --course-level both are solved and the cheaper kept (every ply-level order is allowed).
  std::string precedence = "ply";
  double joined_saving = 0.0;     ///< chosen measure: saved by solving neighbouring sets jointly
  bool kept_programme = false;    ///< the whole answer cost more than the programme: not taken
  std::vector<SetOutcome> sets;   ///< in laying order
  std::vector<PlyOutcome> plies;  ///< programme order (AfpProgram::plies)
  std::vector<program::CourseVisit> before, after;   ///< whole programme: as written, as chosen
  std::vector<int> set_of_course;                    ///< per course (programme order): its set
  Costs offpart_before{}, offpart_after{}, layup{};  ///< whole programme, every measure
  double flown_offpart_before_mm = 0.0;              ///< the programme's own off-part tool path, mm
  double flown_offpart_after_mm = 0.0;               ///< the regenerated off-part tool path, mm
  double seconds = 0.0;  ///< wall time of loading and the run (not writing), s
};

/// A course end (or home) the cell cannot reach: the programme cannot run as written.
struct UnreachableEnd {
  int course = -1;         ///< index into program.courses; -1: the home pose
  bool layup_end = false;  ///< the lay-up's end (else its start)
  std::string reason;      ///< the IK's words
};

enum class SequenceStatus {
  kOk,           ///< ordered; `outcome` and `offpart` filled
  kUnreachable,  ///< course ends the cell cannot reach forwards (`unreachable`)
  kBadOrder,     ///< the given order breaks precedence (`error`)
  kInternal,     ///< a solved order breaks precedence: a bug (`error`)
};

/// A run's result.
struct SequenceRun {
  SequenceStatus status = SequenceStatus::kOk;
  std::vector<UnreachableEnd> unreachable;  ///< with kUnreachable, programme order, home first
  SequenceError error;                      ///< with kBadOrder, kInternal
  SequenceOutcome outcome;
  /// Off-part blocks of every gap of outcome.after: gap i before visit i, the last after it.
  std::vector<std::vector<program::OffPartBlock>> offpart;
  /// The sequenced programme (WriteSequencedProgram) read back: its tool path is the new one
  /// the page draws and the plies' flown_after_mm measure. With kOk only.
  std::optional<program::AfpProgram> sequenced;
  /// Where the head starts, both programmes flown from it (SequenceInputs::home), part frame, mm.
  Eigen::Vector3d start_mm = Eigen::Vector3d::Zero();
};

/// Orders the courses of every precedence set (or lays `inputs.given_order`), from home,
/// each set from where the previous ended; costs before and after; the off-part blocks of the
/// new order. `progress`: courses ordered so far of the programme's (null: none).
SequenceRun RunSequence(const SequenceInputs& inputs, const SequenceOptions& options,
                        const planner::PlanProgress& progress);

/// "file:line: error[sequence-unreachable]: ..." for one unreachable end, as printed on stdout.
std::string UnreachableMessage(const program::AfpProgram& program, const UnreachableEnd& end);

/// Writes the sequenced programme: the lay-ups as written, in the run's order, with its
/// off-part blocks and the header's sequenced / cost / bidirectional entries.
void WriteSequencedProgram(const SequenceInputs& inputs, const SequenceRun& run, std::ostream& out);

}  // namespace stitchsim::run
