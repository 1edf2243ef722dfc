// A sequence run: precedence sets ordered, costs, off-part moves (sequence_run.h).
#include "stitchsim/run/sequence_run.h"

#include <chrono>
#include <iterator>
#include <ostream>
#include <thread>

#include "stitchsim/planner/sequence/offpart.h"
#include "stitchsim/planner/sequence/solver.h"
#include "stitchsim/process/afp_tows.h"
#include "stitchsim/run/sequence_timed.h"

namespace stitchsim::run {
namespace {

using program::CourseVisit;

// What the analysis of the programme found: footprints, precedence, course ends.
struct SequenceAnalysis {
  std::vector<planner::CourseFootprint> footprints;
  planner::PrecedenceNetwork network;
  CourseEnds ends;
};

SequenceAnalysis AnalyseForSequence(const SequenceInputs& in, const SequenceOptions& options,
                                    const sim::CellSetup& cell) {
  const scene::Scene& scene = *in.loaded.scene;
  SequenceAnalysis a;
  const process::TowLayout layout = process::TowLayoutOf(scene.head);
  a.footprints = planner::CourseFootprints(*scene.surface, layout, in.program);
  planner::PrecedenceOptions po;
  po.min_overlap_mm2 = scene.head.sequence.min_overlap_mm2;
  po.course_level = options.course_level;
  a.network = planner::BuildPrecedence(*scene.surface, in.program, a.footprints, po);
  a.ends = SolveCourseEnds(cell, in.program, in.home, scene.head.sequence.retract_mm);
  return a;
}

// Course ends the cell cannot reach forwards (and home): the programme cannot run as written.
std::vector<UnreachableEnd> UnreachableEnds(const CourseEnds& ends, std::size_t courses) {
  std::vector<UnreachableEnd> out;
  if (!ends.home.ok) out.push_back({-1, false, ends.home.reason});
  for (std::size_t c = 0; c < courses; ++c) {
    for (int k = 0; k < 2; ++k) {
      const EndPoint& e = ends.ends[4 * c + static_cast<std::size_t>(k)];
      if (!e.ok) out.push_back({static_cast<int>(c), k == 1, e.reason});
    }
  }
  return out;
}

// Orders every set in turn, each from where the previous one ended; a set whose solved order
// costs more than the programme's keeps the programme's (seed 004, requirement 4).
// `progress`: courses ordered so far, of the programme's.
void SolveSequenceSets(const SequenceOptions& options, const SequenceAnalysis& an,
                       const MeasureSpec& spec, SequenceOutcome& o,
                       const planner::PlanProgress& progress) {
  const EndPoint* start = &an.ends.home;
  const double total_courses = static_cast<double>(o.before.size());
  for (std::size_t k = 0; k < an.network.sets.size(); ++k) {
    const auto& courses = an.network.sets[k].courses;
    const bool last = k + 1 == an.network.sets.size();
    const auto p = SetProblem(an.ends, courses, spec, o.measure, o.bidirectional, *start,
                              last && o.return_home ? &an.ends.home : nullptr);
    std::vector<planner::Visit> original;
    for (int i = 0; i < p.courses; ++i) original.push_back({i, false});
    const double original_cost = planner::PathCost(p, original);
    planner::SequenceSolution sol;
    std::optional<planner::SequenceSolution> exact;
    if (options.solver == SequenceSolver::kExact) exact = planner::SolveExact(p);
    if (exact) {
      sol = *exact;
    } else if (options.solver == SequenceSolver::kSeed) {
      sol = planner::SolveSeedMethod(p);
    } else {
      planner::LocalSearchOptions lo;
      lo.time_limit_s = options.time_limit_s;
      sol = planner::SolveLocalSearch(p, lo);
    }
    SetOutcome& set = o.sets[k];
    set.solver = sol.solver;
    set.status = sol.status;
    set.seconds = sol.seconds;
    set.iterations = sol.iterations;
    if (sol.cost > original_cost) {
      sol.order = original;
      sol.cost = original_cost;
      set.kept_original = true;
    }
    set.original_cost = original_cost;
    set.cost = sol.cost;
    if (options.measure_gap) {
      if (exact || (exact = planner::SolveExact(p))) set.optimum = exact->cost;
    }
    for (const auto& v : sol.order)
      o.after.push_back({courses[static_cast<std::size_t>(v.course)], v.reversed});
    const auto& lastv = o.after.back();
    start = &an.ends.ends[4 * static_cast<std::size_t>(lastv.course) + (lastv.reversed ? 3 : 1)];
    if (progress) progress(static_cast<double>(o.after.size()), total_courses);
  }
}

// Off-part costs before and after, per set and overall, in every measure.
void SequenceCostsOf(const CourseEnds& ends, const MeasureSpec* specs, SequenceOutcome& o) {
  for (std::size_t mi = 0; mi < std::size(kMeasures); ++mi) {
    const Measure m = kMeasures[mi];
    const auto before = MoveCosts(ends, o.before, specs[mi], m, o.return_home);
    const auto after = MoveCosts(ends, o.after, specs[mi], m, o.return_home);
    auto add = [&](const std::vector<double>& moves, const std::vector<CourseVisit>& visits,
                   bool is_after) {
      double total = 0.0;
      for (std::size_t i = 0; i < moves.size(); ++i) {
        // The move into visit i counts for that visit's set; the move home for the last set.
        const int course = i < visits.size() ? visits[i].course : visits.back().course;
        auto& set =
            o.sets[static_cast<std::size_t>(o.set_of_course[static_cast<std::size_t>(course)])];
        (is_after ? set.offpart_after : set.offpart_before)[mi] += moves[i];
        total += moves[i];
      }
      (is_after ? o.offpart_after : o.offpart_before)[mi] = total;
    };
    add(before, o.before, false);
    add(after, o.after, true);
  }
}

// The off-part blocks of every gap of `visits` (gap i before visit i; the last after the last).
std::vector<std::vector<program::OffPartBlock>> SequenceOffPart(
    const SequenceInputs& in, const std::vector<CourseVisit>& visits, bool return_home,
    double* length_mm) {
  const auto& seq = in.loaded.scene->head.sequence;
  planner::OffPartOptions opt;
  opt.retract_mm = seq.retract_mm;
  opt.clearance_mm = seq.clearance_mm;
  const geom::Surface& surface = *in.loaded.scene->surface;
  std::vector<std::vector<program::OffPartBlock>> gaps;
  std::optional<planner::OffPartEnd> from = planner::OffPartEnd{in.home, false};
  Eigen::Vector3d here = in.home.translation();
  *length_mm = 0.0;
  // How far the head has turned about its axis since home (radians, unwrapped): the wrist's
  // last axis follows it. A course laid backwards turns the head round, either way; the way
  // that brings the total back towards zero is taken, so a6 never winds up to its limit.
  double twist = 0.0;
  for (std::size_t i = 0; i <= visits.size(); ++i) {
    std::optional<planner::OffPartEnd> to;
    std::optional<double> feed;
    const program::AfpCourse* c = nullptr;
    if (i < visits.size()) {
      c = &in.program.courses[static_cast<std::size_t>(visits[i].course)];
      to = planner::OffPartEnd{program::LayupStartPose(*c, visits[i].reversed), true};
      feed = c->entry.feed_mm_per_min;
    } else if (return_home) {
      to = planner::OffPartEnd{in.home, false};
    }
    if (to) {
      opt.turn_about_z_rad = planner::UnwindingTurn(
          twist, planner::TwistAboutZ(from->pose.linear(), to->pose.linear()));
      twist += *opt.turn_about_z_rad;
    }
    gaps.push_back(planner::OffPartPath(surface, from, to, feed, opt));
    *length_mm += planner::OffPartLength(here, gaps.back());
    if (c != nullptr) {
      from = planner::OffPartEnd{program::LayupEndPose(*c, visits[i].reversed), true};
      here = from->pose.translation();
      double layup = 0.0;  // along the stations, small steps: each the shorter way
      for (std::size_t k = 1; k < c->stations.size(); ++k)
        layup +=
            planner::TwistAboutZ(c->stations[k - 1].pose.linear(), c->stations[k].pose.linear());
      twist += visits[i].reversed ? -layup : layup;
    }
  }
  return gaps;
}

// The outcome's settings, sets and programme order, before any solving.
SequenceOutcome SequenceOutcomeOf(const SequenceInputs& in, const SequenceOptions& options,
                                  const planner::PrecedenceNetwork& network) {
  SequenceOutcome o;
  o.program_file = options.program_file;
  o.scene_file = options.scene_file;
  o.output_file = options.output_file;
  o.measure = options.measure;
  o.bidirectional = options.bidirectional;
  o.return_home = options.return_home;
  o.course_level = options.course_level;
  o.solver = !options.order_file.empty()                ? "given"
             : options.solver == SequenceSolver::kExact ? "exact"
             : options.solver == SequenceSolver::kSeed  ? "seed"
                                                        : "local";
  o.set_of_course = network.set_of_course;
  o.sets.resize(network.sets.size());
  for (std::size_t k = 0; k < o.sets.size(); ++k) {
    o.sets[k].courses = network.sets[k].courses;
    for (const int pi : network.sets[k].plies)
      o.sets[k].plies.push_back(in.program.plies[static_cast<std::size_t>(pi)].number);
  }
  for (std::size_t c = 0; c < in.program.courses.size(); ++c)
    o.before.push_back({static_cast<int>(c), false});
  return o;
}

}  // namespace

SequenceRun RunSequence(const SequenceInputs& in, const SequenceOptions& options,
                        const planner::PlanProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const scene::Scene& scene = *in.loaded.scene;
  const sim::CellSetup cell = sim::MakeCellSetup(*in.loaded.robot, scene);
  const SequenceAnalysis an = AnalyseForSequence(in, options, cell);
  SequenceRun run;
  run.unreachable = UnreachableEnds(an.ends, in.program.courses.size());
  if (!run.unreachable.empty()) {
    run.status = SequenceStatus::kUnreachable;
    return run;
  }
  SequenceOutcome& o = run.outcome;
  o = SequenceOutcomeOf(in, options, an.network);
  MeasureSpec specs[std::size(kMeasures)];
  for (std::size_t mi = 0; mi < std::size(kMeasures); ++mi)
    specs[mi] = SpecOf(kMeasures[mi], *in.loaded.robot, in.axis_weights);
  // The timed measure's tables are computed on every core (the same whatever their number).
  auto timed = std::make_shared<TimedModel>(
      TimedModelOf(*in.loaded.robot, scene, program::Dialect::Default()));
  timed->threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  specs[static_cast<std::size_t>(Measure::kTimed)].timed = timed;
  if (options.order_file.empty()) {
    SolveSequenceSets(options, an, specs[static_cast<std::size_t>(o.measure)], o, progress);
  } else {
    o.after = in.given_order;
    for (auto& set : o.sets) set.solver = "given";
  }
  int violation = -1;
  if (!planner::RespectsPrecedence(*scene.surface, in.program, an.footprints, o.after,
                                   scene.head.sequence.min_overlap_mm2, &violation)) {
    const auto& c =
        in.program
            .courses[static_cast<std::size_t>(o.after[static_cast<std::size_t>(violation)].course)];
    const bool given = !options.order_file.empty();
    run.status = given ? SequenceStatus::kBadOrder : SequenceStatus::kInternal;
    run.error = {given ? "sequence-order-precedence" : "sequence-internal",
                 "the order lays course " + std::to_string(c.number) + " of ply " +
                     std::to_string(c.ply) + " (line " + std::to_string(c.begin_line) +
                     ") before a course it overlaps that the programme lays first"};
    return run;
  }
  SequenceCostsOf(an.ends, specs, o);
  o.layup = LayupCosts(cell, in.program, specs[0], *timed);
  o.flown_offpart_before_mm = in.program.offpart_length_mm;
  run.offpart = SequenceOffPart(in, o.after, o.return_home, &o.flown_offpart_after_mm);
  o.seconds = in.load_seconds +
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

std::string UnreachableMessage(const program::AfpProgram& program, const UnreachableEnd& end) {
  if (end.course < 0)
    return program.file_name + ": error[sequence-unreachable]: the cell cannot reach the home " +
           "pose (" + end.reason + ")";
  const auto& course = program.courses[static_cast<std::size_t>(end.course)];
  const int line = end.layup_end ? course.layup_last_line : course.layup_first_line;
  return program.file_name + ":" + std::to_string(line) + ": error[sequence-unreachable]: course " +
         std::to_string(course.number) + " of ply " + std::to_string(course.ply) +
         ": the cell cannot reach its lay-up " + (end.layup_end ? "end" : "start") + " (" +
         end.reason + ")";
}

void WriteSequencedProgram(const SequenceInputs& in, const SequenceRun& run, std::ostream& out) {
  const SequenceOutcome& o = run.outcome;
  program::AfpWriteOptions wo;
  wo.tow_count = in.loaded.scene->head.afp.tows;
  wo.header_extra = {{"sequenced", o.solver},
                     {"cost", MeasureName(o.measure)},
                     {"bidirectional", o.bidirectional ? "1" : "0"}};
  const program::OffPartSource source = [&](std::size_t i) { return run.offpart[i]; };
  program::WriteAfpProgram(out, in.program, program::Dialect::Default(), o.after, source, wo);
}

}  // namespace stitchsim::run
