// `stitchsim sequence PROG --scene S -o NEW.nc`: reorders the courses of an AFP programme
// within its precedence sets to cut the off-part motion, regenerates the off-part moves and
// writes the programme (and a JSON report) whole or not at all (docs/sequence.md).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "plan_progress.h"
#include "sequence_costs.h"
#include "sequence_run.h"
#include "stitchsim/planner/sequence_offpart.h"
#include "stitchsim/planner/sequence_solver.h"
#include "stitchsim/program/tool_pose.h"
#include "stitchsim/sim/cell.h"

namespace stitchsim::app {
namespace {

struct SequenceArgs {
  std::string program, scene, output, report, cost = "axes", solver = "local", home, order;
  bool bidirectional = false, return_home = false, course_level = false, measure_gap = false;
  bool quiet = false;  // no progress on stderr
  double time_limit_s = 10.0;
};

using program::AfpProgram;
using program::CourseVisit;

// Everything a run reads, validated.
struct Inputs {
  LoadedScene loaded;
  AfpProgram program;
  std::vector<planner::CourseFootprint> footprints;
  planner::PrecedenceNetwork network;
  CourseEnds ends;
  Eigen::Isometry3d home = Eigen::Isometry3d::Identity();
  std::vector<double> axis_weights;  // per joint, model order
};

std::optional<Eigen::Isometry3d> ParseHome(const std::string& text) {
  std::stringstream ss(text);
  program::MachineState st;
  std::string item;
  const program::Axis axes[] = {program::Axis::kX, program::Axis::kY, program::Axis::kZ,
                                program::Axis::kA, program::Axis::kB, program::Axis::kC};
  for (const program::Axis a : axes) {
    if (!std::getline(ss, item, ',')) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !std::isfinite(v)) return std::nullopt;
    st.axes[static_cast<std::size_t>(a)] = v;
  }
  if (std::getline(ss, item, ',')) return std::nullopt;
  return program::ToolPoseOf(st, program::EulerOrderOf(program::Dialect::Default()));
}

// Head weights by joint name onto the model's joints; unknown names are errors at their line.
bool AxisWeights(const scene::HeadSpec& head, const sim::RobotModel& robot, DiagnosticSink& sink,
                 std::vector<double>& out) {
  out.assign(trace::kNumJoints, 0.0);
  for (const auto& w : head.sequence.axis_weights) {
    int found = -1;
    for (int j = 0; j < trace::kNumJoints; ++j)
      if (robot.joint(j).name == w.joint) found = j;
    if (found < 0) {
      sink.Error("head-unknown-joint", w.where,
                 "sequence.axis_weights names '" + w.joint + "', not a joint of the cell");
      continue;
    }
    out[static_cast<std::size_t>(found)] = w.weight;
  }
  return !sink.HasErrors();
}

// Every tow a programme lays must be one of the head's (a course laid backwards mirrors them).
bool TowsOnHead(const AfpProgram& p, const scene::HeadSpec& head, DiagnosticSink& sink) {
  const int k = head.afp.tows;
  const std::uint64_t beyond = k >= 64 ? 0 : ~((std::uint64_t{1} << k) - 1);
  for (const auto& c : p.courses) {
    for (const auto& st : c.stations) {
      // None beyond the head's, or all of them: P0 adds every tow there is.
      const std::uint64_t high = st.tows & beyond;
      if (high == 0 || high == beyond) continue;
      sink.Error(
          "sequence-tow-beyond-head", SourceLocation{p.file_name, st.source_line, 1},
          "a tow beyond the head's " + std::to_string(k) + " lays here (head '" + head.name + "')");
      return false;
    }
  }
  return true;
}

// A programme's plies must name the scene's plies (M70 P<n>, n its position in `plies:`).
bool PliesKnown(const AfpProgram& p, const scene::Scene& scene, DiagnosticSink& sink) {
  for (const auto& ply : p.plies) {
    if (ply.number >= 1 && ply.number <= static_cast<int>(scene.plies.size())) continue;
    sink.Error("sequence-unknown-ply", SourceLocation{p.file_name, ply.line, 1},
               "M70 P" + std::to_string(ply.number) + " names no ply of scene '" + scene.name +
                   "' (it has " + std::to_string(scene.plies.size()) + ")");
  }
  return !sink.HasErrors();
}

std::optional<Inputs> LoadInputs(const SequenceArgs& a) {
  auto loaded = LoadSceneAndRobot(a.scene);
  if (!loaded) return std::nullopt;
  Inputs in;
  in.loaded = std::move(*loaded);
  const scene::Scene& scene = *in.loaded.scene;
  DiagnosticSink sink;
  if (scene.head.kind != scene::HeadKind::kAfp) {
    sink.Error("sequence-not-afp", SourceLocation{a.scene, 1, 1},
               "scene '" + scene.name + "' mounts head '" + scene.head.name +
                   "', not a fibre-placement head");
  }
  std::ifstream file(a.program, std::ios::binary);
  std::optional<AfpProgram> prog;
  if (!sink.HasErrors())
    prog = program::ReadAfpProgram(file, program::Dialect::Default(), a.program, sink);
  if (prog) PliesKnown(*prog, scene, sink);
  if (prog) TowsOnHead(*prog, scene.head, sink);
  AxisWeights(scene.head, *in.loaded.robot, sink, in.axis_weights);
  if (PrintDiagnostics(sink) || !prog) return std::nullopt;
  in.program = std::move(*prog);
  if (!a.home.empty()) {
    auto h = ParseHome(a.home);
    if (!h) {
      PrintError("sequence-bad-home", "--home wants X,Y,Z,A,B,C (mm, deg), got '" + a.home + "'");
      return std::nullopt;
    }
    in.home = *h;
  } else if (in.program.first_pose) {
    in.home = *in.program.first_pose;
  }
  return in;
}

// The cost of each move of `visits` in one measure: entry i is the move into visit i (from
// home or the previous visit's end); one more entry, the move home, when `finish`.
std::vector<double> MoveCosts(const CourseEnds& e, const std::vector<CourseVisit>& visits,
                              const MeasureSpec& spec, Measure m, bool finish) {
  planner::SequenceProblem p;
  p.dim = static_cast<int>(spec.weights.size());
  p.weights = spec.weights;
  p.norm = spec.norm;
  std::vector<double> out;
  std::vector<double> here = PointOf(e.home, m);
  for (const auto& v : visits) {
    const std::size_t k = 4 * static_cast<std::size_t>(v.course) + (v.reversed ? 2 : 0);
    const std::vector<double> start = PointOf(e.ends[k], m);
    out.push_back(planner::MoveCost(p, here.data(), start.data()));
    here = PointOf(e.ends[k + 1], m);
  }
  if (finish) {
    const std::vector<double> home = PointOf(e.home, m);
    out.push_back(planner::MoveCost(p, here.data(), home.data()));
  }
  return out;
}

// Off-part costs before and after, per set and overall, in every measure.
void CostsOf(const Inputs& in, const MeasureSpec* specs, SequenceOutcome& o) {
  for (std::size_t mi = 0; mi < 3; ++mi) {
    const Measure m = kMeasures[mi];
    const auto before = MoveCosts(in.ends, o.before, specs[mi], m, o.return_home);
    const auto after = MoveCosts(in.ends, o.after, specs[mi], m, o.return_home);
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

// Orders every set in turn, each from where the previous one ended; a set whose solved order
// costs more than the programme's keeps the programme's (seed 004, requirement 4).
// `progress`: courses ordered so far, of the programme's.
void SolveSets(const SequenceArgs& a, const Inputs& in, const MeasureSpec& spec, SequenceOutcome& o,
               const planner::PlanProgress& progress) {
  const EndPoint* start = &in.ends.home;
  const double total_courses = static_cast<double>(in.program.courses.size());
  for (std::size_t k = 0; k < in.network.sets.size(); ++k) {
    const auto& courses = in.network.sets[k].courses;
    const bool last = k + 1 == in.network.sets.size();
    const auto p = SetProblem(in.ends, courses, spec, o.measure, o.bidirectional, *start,
                              last && o.return_home ? &in.ends.home : nullptr);
    std::vector<planner::Visit> original;
    for (int i = 0; i < p.courses; ++i) original.push_back({i, false});
    const double original_cost = planner::PathCost(p, original);
    planner::SequenceSolution sol;
    std::optional<planner::SequenceSolution> exact;
    if (a.solver == "exact") exact = planner::SolveExact(p);
    if (exact) {
      sol = *exact;
    } else if (a.solver == "seed") {
      sol = planner::SolveSeedMethod(p);
    } else {
      planner::LocalSearchOptions lo;
      lo.time_limit_s = a.time_limit_s;
      sol = planner::SolveLocalSearch(p, lo);
    }
    SetOutcome& set = o.sets[k];
    set.solver = sol.solver;
    set.seconds = sol.seconds;
    set.iterations = sol.iterations;
    if (sol.cost > original_cost) {
      sol.order = original;
      sol.cost = original_cost;
      set.kept_original = true;
    }
    set.original_cost = original_cost;
    set.cost = sol.cost;
    if (a.measure_gap) {
      if (exact || (exact = planner::SolveExact(p))) set.optimum = exact->cost;
    }
    for (const auto& v : sol.order)
      o.after.push_back({courses[static_cast<std::size_t>(v.course)], v.reversed});
    const auto& lastv = o.after.back();
    start = &in.ends.ends[4 * static_cast<std::size_t>(lastv.course) + (lastv.reversed ? 3 : 1)];
    if (progress) progress(static_cast<double>(o.after.size()), total_courses);
  }
}

// The off-part blocks of every gap of `visits` (gap i before visit i; the last after the last).
std::vector<std::vector<program::OffPartBlock>> OffPart(const Inputs& in,
                                                        const std::vector<CourseVisit>& visits,
                                                        bool return_home, double* length_mm) {
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

// Lay-up motion in every measure (the same before and after): tool path, time at the
// programmed feeds, and the axes' weighted travel between the stations' IK solutions.
Costs LayupCosts(const Inputs& in, const MeasureSpec& axes_spec) {
  Costs c{};
  const sim::CellSetup cell = sim::MakeCellSetup(*in.loaded.robot, *in.loaded.scene);
  planner::SequenceProblem p;
  p.dim = trace::kNumJoints;
  p.weights = axes_spec.weights;
  p.norm = axes_spec.norm;
  trace::JointVector q = sim::HomeJoints(*in.loaded.robot, 0.0);
  for (const auto& course : in.program.courses) {
    c[2] += course.layup_length_mm;
    std::vector<double> prev;
    for (std::size_t i = 0; i < course.stations.size(); ++i) {
      const auto& st = course.stations[i];
      if (i + 1 < course.stations.size() && st.feed_mm_per_min > 0.0) {
        const double len =
            (course.stations[i + 1].pose.translation() - st.pose.translation()).norm();
        c[1] += len / st.feed_mm_per_min * 60.0;
      }
      const double rot = course.entry.rotator_deg ? *course.entry.rotator_deg * M_PI / 180.0 : 0.0;
      const auto s = sim::SolveToolPose(cell, st.pose, rot, course.entry.rail_mm, &q);
      q = s.ik.joints;
      std::vector<double> pt(trace::kNumJoints);
      for (int j = 0; j < trace::kNumJoints; ++j)
        pt[static_cast<std::size_t>(j)] = j == trace::kRailX ? q[j] * 1000.0 : q[j] * 180.0 / M_PI;
      if (!prev.empty()) c[0] += planner::MoveCost(p, prev.data(), pt.data());
      prev = std::move(pt);
    }
  }
  return c;
}

// Course ends the cell cannot reach forwards: the programme cannot run as written (exit 1).
bool ReportUnreachable(const Inputs& in) {
  bool any = !in.ends.home.ok;
  if (any)
    std::printf("%s: error[sequence-unreachable]: the cell cannot reach the home pose (%s)\n",
                in.program.file_name.c_str(), in.ends.home.reason.c_str());
  for (std::size_t c = 0; c < in.program.courses.size(); ++c) {
    for (int k = 0; k < 2; ++k) {
      const EndPoint& e = in.ends.ends[4 * c + static_cast<std::size_t>(k)];
      if (e.ok) continue;
      const auto& course = in.program.courses[c];
      std::printf(
          "%s:%d: error[sequence-unreachable]: course %d of ply %d: the cell cannot "
          "reach its lay-up %s (%s)\n",
          in.program.file_name.c_str(), k == 0 ? course.layup_first_line : course.layup_last_line,
          course.number, course.ply, k == 0 ? "start" : "end", e.reason.c_str());
      any = true;
    }
  }
  return any;
}

// Footprints, the precedence network and the IK of every course end.
bool Analyse(const SequenceArgs& a, Inputs& in) {
  const scene::Scene& scene = *in.loaded.scene;
  const process::TowLayout layout = process::TowLayoutOf(scene.head);
  in.footprints = planner::CourseFootprints(*scene.surface, layout, in.program);
  planner::PrecedenceOptions po;
  po.min_overlap_mm2 = scene.head.sequence.min_overlap_mm2;
  po.course_level = a.course_level;
  in.network = planner::BuildPrecedence(*scene.surface, in.program, in.footprints, po);
  const sim::CellSetup cell = sim::MakeCellSetup(*in.loaded.robot, scene);
  in.ends = SolveCourseEnds(cell, in.program, in.home);
  return !ReportUnreachable(in);
}

int RunSequence(const SequenceArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!OutputsDistinct({{"--output", a.output}, {"--report", a.report}}) ||
      !ProgramInputOk(a.program))
    return kExitBadInput;
  auto in = LoadInputs(a);
  if (!in) return kExitBadInput;
  SequenceOutcome o;
  o.program_file = a.program;
  o.scene_file = a.scene;
  o.output_file = a.output;
  o.measure = a.cost == "time"   ? Measure::kTime
              : a.cost == "tool" ? Measure::kTool
                                 : Measure::kAxes;
  o.bidirectional = a.bidirectional;
  o.return_home = a.return_home;
  o.course_level = a.course_level;
  o.solver = a.order.empty() ? a.solver : "given";
  if (!a.order.empty() && !ReadOrderFile(a.order, in->program, o.after)) return kExitBadInput;
  if (!Analyse(a, *in)) return kExitFindings;
  o.set_of_course = in->network.set_of_course;
  o.sets.resize(in->network.sets.size());
  for (std::size_t k = 0; k < o.sets.size(); ++k) {
    o.sets[k].courses = in->network.sets[k].courses;
    for (const int pi : in->network.sets[k].plies)
      o.sets[k].plies.push_back(in->program.plies[static_cast<std::size_t>(pi)].number);
  }
  for (std::size_t c = 0; c < in->program.courses.size(); ++c)
    o.before.push_back({static_cast<int>(c), false});
  const scene::Scene& scene = *in->loaded.scene;
  MeasureSpec specs[3];
  for (std::size_t mi = 0; mi < 3; ++mi)
    specs[mi] = SpecOf(kMeasures[mi], *in->loaded.robot, in->axis_weights);
  if (a.order.empty()) {
    PlanProgressPrinter progress("sequence", "courses", a.quiet);
    SolveSets(a, *in, specs[static_cast<std::size_t>(o.measure)], o, progress.Callback());
    progress.Finish();
  } else {
    for (auto& set : o.sets) set.solver = "given";
  }
  int violation = -1;
  if (!planner::RespectsPrecedence(*scene.surface, in->program, in->footprints, o.after,
                                   scene.head.sequence.min_overlap_mm2, &violation)) {
    const auto& c =
        in->program
            .courses[static_cast<std::size_t>(o.after[static_cast<std::size_t>(violation)].course)];
    PrintError(a.order.empty() ? "sequence-internal" : "sequence-order-precedence",
               "the order lays course " + std::to_string(c.number) + " of ply " +
                   std::to_string(c.ply) + " (line " + std::to_string(c.begin_line) +
                   ") before a course it overlaps that the programme lays first");
    return a.order.empty() ? kExitInternal : kExitBadInput;
  }
  CostsOf(*in, specs, o);
  o.layup = LayupCosts(*in, specs[0]);
  o.flown_offpart_before_mm = in->program.offpart_length_mm;
  const auto gaps = OffPart(*in, o.after, o.return_home, &o.flown_offpart_after_mm);
  program::AfpWriteOptions wo;
  wo.tow_count = scene.head.afp.tows;
  wo.header_extra = {{"sequenced", o.solver},
                     {"cost", MeasureName(o.measure)},
                     {"bidirectional", o.bidirectional ? "1" : "0"}};
  const program::OffPartSource source = [&](std::size_t i) { return gaps[i]; };
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int written = WriteProgramAndCsv(
      a.output, a.report,
      [&](std::ostream& out) {
        program::WriteAfpProgram(out, in->program, program::Dialect::Default(), o.after, source,
                                 wo);
      },
      [&](std::ostream& out) { WriteSequenceJson(o, in->program, out); });
  if (written != kExitOk) return written;
  PrintSequenceSummary(o);
  return kExitOk;
}

}  // namespace

void AddSequenceCommand(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<SequenceArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sequence",
      "Reorder an AFP programme's courses within their precedence sets to cut the off-part "
      "motion (seed 004); the lay-ups are kept, the off-part moves regenerated");
  cmd->add_option("program", a->program, "AFP programme (plies and courses marked: M70/M71/M72)")
      ->required();
  cmd->add_option("--scene", a->scene, "Scene YAML file (its surface, plies and AFP head)")
      ->required();
  cmd->add_option("-o,--output", a->output, "Programme file to write")->required();
  cmd->add_option("--report", a->report, "JSON report: costs per set and the course order");
  cmd->add_option("--cost", a->cost, "Cost to minimise: axes (seed eq. 3.4), time, tool")
      ->check(CLI::IsMember({"axes", "time", "tool"}));
  cmd->add_option("--solver", a->solver,
                  "local (ours, default), seed (seed 004's method) or exact (dynamic programming, "
                  "sets of up to 16 courses; larger sets use local)")
      ->check(CLI::IsMember({"local", "seed", "exact"}));
  cmd->add_flag("--bidirectional", a->bidirectional, "Courses may be laid backwards");
  cmd->add_option("--home", a->home,
                  "Home pose X,Y,Z,A,B,C (mm, deg; default: the programme's first pose)");
  cmd->add_flag("--return-home", a->return_home, "Return to the home pose after the last course");
  cmd->add_option("--time-limit", a->time_limit_s, "Seconds the local search may take per set")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--measure-gap", a->measure_gap,
                "Also solve every set of up to 16 courses exactly and report the optimum");
  cmd->add_flag("--course-level", a->course_level,
                "Course-level precedence: a course may move into an earlier set");
  cmd->add_option("--order", a->order,
                  "Lay the courses in this order (a report's \"order\") instead of solving");
  AddScenePathFlag(*cmd);
  AddQuietFlag(*cmd, a->quiet);
  cmd->callback([a, &exit_code] { exit_code = RunSequence(*a); });
}

}  // namespace stitchsim::app
