// A sequence run: precedence sets ordered, costs, off-part moves (sequence_run.h).
#include "stitchsim/run/sequence_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <ostream>
#include <thread>

#include "stitchsim/planner/sequence/offpart.h"
#include "stitchsim/planner/sequence/solver.h"
#include "stitchsim/process/afp_tows.h"
#include "stitchsim/run/sequence_html.h"
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

planner::PrecedenceNetwork PrecedenceOf(const SequenceInputs& in,
                                        const std::vector<planner::CourseFootprint>& footprints,
                                        bool course_level) {
  const scene::Scene& scene = *in.loaded.scene;
  planner::PrecedenceOptions po;
  po.min_overlap_mm2 = scene.head.sequence.min_overlap_mm2;
  po.course_level = course_level;
  return planner::BuildPrecedence(*scene.surface, in.program, footprints, po);
}

SequenceAnalysis AnalyseForSequence(const SequenceInputs& in, const SequenceOptions& options,
                                    const sim::CellSetup& cell) {
  const scene::Scene& scene = *in.loaded.scene;
  SequenceAnalysis a;
  const process::TowLayout layout = process::TowLayoutOf(scene.head);
  a.footprints = planner::CourseFootprints(*scene.surface, layout, in.program);
  a.network = PrecedenceOf(in, a.footprints, options.course_level);
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

// The cost of laying `visits` from home (and back, with `finish`) in the measure of `spec`.
double TotalCost(const CourseEnds& ends, const std::vector<CourseVisit>& visits,
                 const MeasureSpec& spec, Measure m, bool finish) {
  const std::vector<double> moves = MoveCosts(ends, visits, spec, m, finish);
  return std::accumulate(moves.begin(), moves.end(), 0.0);
}

// The local search's options of a run: its time limit and threads.
// A run of more than kLargeRun courses (many sets) gives each set's search, and each join's,
// kLargeRunStarts starts and a stagnation cap of kLargeRunRounds / courses rounds, at least
// kMinRounds: the whole run's work grows like one large set's, not like the sets' count times
// a small set's (a small set alone gets 8 starts of 5,000 rounds). Rounds, not seconds: the
// answer stays the same on any machine.
constexpr std::size_t kLargeRun = 1000;
constexpr int kLargeRunStarts = 2;
constexpr std::int64_t kLargeRunRounds = 1'000'000;
constexpr std::int64_t kMinRounds = 100;

// `run_courses`: the courses of the whole run.
planner::LocalSearchOptions LocalOptionsOf(const SequenceOptions& options,
                                           std::size_t run_courses) {
  planner::LocalSearchOptions lo;
  lo.time_limit_s = options.time_limit_s;
  lo.jobs = options.jobs > 0 ? options.jobs
                             : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (run_courses > kLargeRun) {
    lo.starts = kLargeRunStarts;
    lo.stagnation = std::max(kMinRounds, kLargeRunRounds / static_cast<std::int64_t>(run_courses));
  }
  if (options.starts > 0) lo.starts = options.starts;
  if (options.stagnation > 0) lo.stagnation = options.stagnation;
  return lo;
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
      sol = planner::SolveLocalSearch(p, LocalOptionsOf(options, o.before.size()));
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
    for (const auto& v : sol.order)
      o.after.push_back({courses[static_cast<std::size_t>(v.course)], v.reversed});
    start = &EndOf(an.ends, o.after.back());
    if (progress) progress(static_cast<double>(o.after.size()), total_courses);
  }
}

// The first position of every set in o.after (and the end, o.after.size()).
std::vector<std::size_t> SetOffsets(const SequenceOutcome& o) {
  std::vector<std::size_t> at{0};
  for (const auto& set : o.sets) at.push_back(at.back() + set.courses.size());
  return at;
}

// The moves between sets optimised with the sets' own (seed 004's further work): every two
// neighbouring sets solved again as one problem, the first's courses before the second's
// (planner groups), from where the set before them ends to where the set after them begins,
// starting from the orders found, so a join is never dearer. Returns the cost saved.
double JoinSets(const SequenceOptions& options, const CourseEnds& ends, const MeasureSpec& spec,
                SequenceOutcome& o) {
  const std::vector<std::size_t> at = SetOffsets(o);
  double saved = 0.0;
  for (std::size_t k = 0; k + 1 < o.sets.size(); ++k) {
    const std::size_t from = at[k], to = at[k + 2];
    std::vector<int> courses;
    for (std::size_t i = from; i < to; ++i) courses.push_back(o.after[i].course);
    const EndPoint& start = from == 0 ? ends.home : EndOf(ends, o.after[from - 1]);
    const EndPoint* finish = to < o.after.size() ? &StartOf(ends, o.after[to])
                             : o.return_home     ? &ends.home
                                                 : nullptr;
    auto p = SetProblem(ends, courses, spec, o.measure, o.bidirectional, start, finish);
    planner::LocalSearchOptions lo = LocalOptionsOf(options, o.before.size());
    for (std::size_t i = from; i < to; ++i) {
      p.group.push_back(i < at[k + 1] ? 0 : 1);
      lo.initial.push_back({static_cast<int>(i - from), o.after[i].reversed});
    }
    const double before = planner::PathCost(p, lo.initial);
    const planner::SequenceSolution sol = planner::SolveLocalSearch(p, lo);
    if (!(sol.cost < before)) continue;
    saved += before - sol.cost;
    o.sets[k].kept_original = o.sets[k + 1].kept_original = false;  // their orders are new
    for (std::size_t i = 0; i < sol.order.size(); ++i) {
      const auto& v = sol.order[i];
      o.after[from + i] = {courses[static_cast<std::size_t>(v.course)], v.reversed};
    }
  }
  return saved;
}

// The gap of `cost` to the best lower bound known (SetOutcome::gap). A relative difference
// below 1e-9 is rounding (the two costs summed in other orders), reported as 0.
std::optional<double> GapTo(double cost, double best_lower) {
  if (best_lower <= 0.0) return cost <= 0.0 ? std::optional<double>(0.0) : std::nullopt;
  const double gap = (cost - best_lower) / best_lower;
  return std::abs(gap) < 1e-9 ? 0.0 : gap;
}

// The order laid of each set (local indices into its courses), from `after`; empty when the
// order interleaves the sets (a given order may, where their courses do not overlap).
std::vector<std::vector<planner::Visit>> SetOrders(const SequenceOutcome& o) {
  std::vector<std::vector<planner::Visit>> orders(o.sets.size());
  std::size_t set = 0;
  for (const CourseVisit& v : o.after) {
    const auto k = static_cast<std::size_t>(o.set_of_course[static_cast<std::size_t>(v.course)]);
    if (k < set) return {};
    set = k;
    const auto& courses = o.sets[k].courses;
    const auto at = std::find(courses.begin(), courses.end(), v.course) - courses.begin();
    orders[k].push_back({static_cast<int>(at), v.reversed});
  }
  return orders;
}

// After the order is laid: for every set, in the problem it was laid in (from where the
// previous set ended), its cost, a lower bound, the optimum where the exact solver is instant
// (or asked for) and the gap. A given order's sets get their costs here too.
void BoundSets(const SequenceOptions& options, const CourseEnds& ends, const MeasureSpec& spec,
               SequenceOutcome& o) {
  const auto orders = SetOrders(o);
  if (orders.empty()) return;
  const EndPoint* start = &ends.home;
  for (std::size_t k = 0; k < o.sets.size(); ++k) {
    SetOutcome& set = o.sets[k];
    const bool last = k + 1 == o.sets.size();
    const auto p = SetProblem(ends, set.courses, spec, o.measure, o.bidirectional, *start,
                              last && o.return_home ? &ends.home : nullptr);
    set.cost = planner::PathCost(p, orders[k]);
    // The programme's order of the same set from the same start: the cost at which the
    // safeguard keeps it (the start is the final order's, so it is priced here).
    std::vector<planner::Visit> programme;
    for (int i = 0; i < p.courses; ++i) programme.push_back({i, false});
    set.original_cost = planner::PathCost(p, programme);
    const bool exact_asked = options.measure_gap || options.solver == SequenceSolver::kExact;
    const int exact_up_to = exact_asked ? planner::kMaxExactCourses : kExactByDefaultCourses;
    if (p.courses <= exact_up_to) set.optimum = planner::SolveExact(p)->cost;
    const planner::LowerBound b = planner::ComputeLowerBound(p);
    set.bound = b.value;
    set.bound_method = b.method;
    set.bound_seconds = b.seconds;
    set.gap = GapTo(set.cost, set.optimum ? *set.optimum : b.value);
    if (!orders[k].empty()) {
      const planner::Visit& v = orders[k].back();
      start = &EndOf(ends, {set.courses[static_cast<std::size_t>(v.course)], v.reversed});
    }
  }
}

// Solves every set and joins them; with the safeguard on the whole: an order dearer
// than the programme's (in the chosen measure) is not taken.
void SolveAndJoin(const SequenceOptions& options, const SequenceAnalysis& an,
                  const MeasureSpec& spec, SequenceOutcome& o,
                  const planner::PlanProgress& progress) {
  SolveSequenceSets(options, an, spec, o, progress);
  if (options.solver == SequenceSolver::kLocal)
    o.joined_saving = JoinSets(options, an.ends, spec, o);
  const double before = TotalCost(an.ends, o.before, spec, o.measure, o.return_home);
  const double after = TotalCost(an.ends, o.after, spec, o.measure, o.return_home);
  if (after > before) {
    o.after = o.before;
    o.kept_programme = true;
    for (auto& set : o.sets) set.kept_original = true;
  }
}

// Off-part costs before and after, per set and overall, in every measure.
// Per ply too (o.plies in programme order, one per AfpPly).
void SequenceCostsOf(const CourseEnds& ends, const MeasureSpec* specs,
                     const program::AfpProgram& program, SequenceOutcome& o) {
  std::vector<std::size_t> ply_of_course(program.courses.size(), 0);
  for (std::size_t p = 0; p < program.plies.size(); ++p)
    for (const int c : program.plies[p].courses) ply_of_course[static_cast<std::size_t>(c)] = p;
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
        PlyOutcome& ply = o.plies[ply_of_course[static_cast<std::size_t>(course)]];
        (is_after ? ply.offpart_after : ply.offpart_before)[mi] += moves[i];
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
  o.precedence = options.course_level ? "course" : "ply";
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
  for (const program::AfpPly& p : in.program.plies) {
    PlyOutcome ply{
        .ply = p.number, .comment = p.comment, .courses = static_cast<int>(p.courses.size())};
    for (const int c : p.courses)
      ply.layup_mm += in.program.courses[static_cast<std::size_t>(c)].layup_length_mm;
    o.plies.push_back(std::move(ply));
  }
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
  // The timed measure's tables are computed on --jobs threads (the same whatever their number).
  auto timed = std::make_shared<TimedModel>(
      TimedModelOf(*in.loaded.robot, scene, program::Dialect::Default()));
  timed->threads = LocalOptionsOf(options, 0).jobs;
  specs[static_cast<std::size_t>(Measure::kTimed)].timed = timed;
  const MeasureSpec& spec = specs[static_cast<std::size_t>(o.measure)];
  if (options.order_file.empty()) {
    SolveAndJoin(options, an, spec, o, progress);
    if (options.course_level) {
      // Dominance: every ply-level order is a course-level one; the cheaper answer is taken.
      SequenceAnalysis ply{an.footprints, PrecedenceOf(in, an.footprints, false), an.ends};
      SequenceOutcome alt = SequenceOutcomeOf(in, options, ply.network);
      SolveAndJoin(options, ply, spec, alt, nullptr);
      const double mine = TotalCost(an.ends, o.after, spec, o.measure, o.return_home);
      if (TotalCost(an.ends, alt.after, spec, o.measure, o.return_home) < mine) {
        o = std::move(alt);
        o.precedence = "ply";
      }
    }
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
  BoundSets(options, an.ends, specs[static_cast<std::size_t>(o.measure)], o);
  SequenceCostsOf(an.ends, specs, in.program, o);
  o.layup = LayupCosts(cell, in.program, specs[0], *timed);
  // Both flown from home: the original from its first point when home is that (the default).
  run.start_mm = in.home.translation();
  o.flown_offpart_before_mm =
      in.program.offpart_length_mm +
      (in.program.tool_path.empty() ? 0.0
                                    : (in.program.tool_path.front().point - run.start_mm).norm());
  run.offpart = SequenceOffPart(in, o.after, o.return_home, &o.flown_offpart_after_mm);
  run.sequenced = ReadBackSequenced(in, run);
  if (!run.sequenced) {
    run.status = SequenceStatus::kInternal;
    run.error = {"sequence-internal", "the sequenced programme does not read back"};
    return run;
  }
  FillPlyFlown(in.program, *run.sequenced, run.start_mm, o);
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
