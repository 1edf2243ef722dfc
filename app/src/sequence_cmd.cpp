// `stitchsim sequence PROG --scene S -o NEW.nc`: reorders the courses of an AFP programme
// within its precedence sets to cut the off-part motion, regenerates the off-part moves and
// writes the programme (and a JSON report) whole or not at all (docs/sequence.md). The run is
// run::RunSequence; this file parses, prints and picks the exit code.
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_common.h"
#include "commands.h"
#include "plan_progress.h"
#include "stitchsim/common/files.h"
#include "stitchsim/run/sequence_html.h"
#include "stitchsim/run/sequence_report.h"
#include "stitchsim/run/sequence_run.h"

namespace stitchsim::app {
namespace {

struct SequenceArgs {
  run::SequenceOptions run;
  std::string report, html, cost = "axes", solver = "local";
  bool quiet = false;  // no progress on stderr
};

// Signed change in per cent, for people ("-10.5 %" is a reduction).
double Change(double before, double after) {
  return before > 0.0 ? -100.0 * (before - after) / before : 0.0;
}

// A cost for people (6 significant digits).
std::string Cost6(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// How close a set's cost is to optimal: "optimal (bound ...)", "within X % of optimal (...)".
std::string Verdict(const run::SetOutcome& s) {
  if (!s.bound) return "no bound (the order interleaves the sets)";
  const std::string bound = "bound " + Cost6(*s.bound) + ", " + s.bound_method;
  if (!s.gap) return bound;
  if (s.optimum && *s.gap == 0.0) return "optimal (" + bound + ")";
  char within[64];
  std::snprintf(within, sizeof within, "within %.3f %% of optimal (", 100.0 * *s.gap);
  return within + (s.optimum ? "optimum " + Cost6(*s.optimum) + ", exact; " : std::string()) +
         bound + ")";
}

// The text summary on stdout.
void PrintSequenceSummary(const run::SequenceOutcome& o) {
  using run::MeasureName;
  std::printf("%s: %zu courses in %zu precedence sets; cost %s, solver %s%s%s -> %s (%.2f s)\n",
              o.program_file.c_str(), o.after.size(), o.sets.size(), MeasureName(o.measure),
              o.solver.c_str(), o.bidirectional ? ", bidirectional" : "",
              o.return_home ? ", return home" : "", o.output_file.c_str(), o.seconds);
  const auto mi = static_cast<std::size_t>(o.measure);
  for (std::size_t k = 0; k < o.sets.size(); ++k) {
    const run::SetOutcome& s = o.sets[k];
    std::string plies;
    for (const int p : s.plies) plies += (plies.empty() ? "" : ",") + std::to_string(p);
    std::printf("  set %zu (plies %s, %zu courses): off-part %s %.4g -> %.4g (%+.1f %%)%s\n", k + 1,
                plies.c_str(), s.courses.size(), MeasureName(o.measure), s.offpart_before[mi],
                s.offpart_after[mi], Change(s.offpart_before[mi], s.offpart_after[mi]),
                s.kept_original ? " (programme order kept: the solver found nothing cheaper)" : "");
    std::printf("    set cost %.6g (programme order %.6g%s), %s stopped: %s; %s\n", s.cost,
                s.original_cost, s.kept_original ? ", kept" : "", s.solver.c_str(),
                planner::ToString(s.status), Verdict(s).c_str());
  }
  if (o.joined_saving > 0.0)
    std::printf("  sets solved jointly with their neighbours: %.6g saved\n", o.joined_saving);
  if (o.course_level)
    std::printf("  precedence: %s-level answer taken (both solved, the cheaper kept)\n",
                o.precedence.c_str());
  if (o.kept_programme)
    std::printf("  programme order kept: the answer cost more than the programme's\n");
  for (std::size_t m = 0; m < std::size(run::kMeasures); ++m) {
    const run::Measure measure = run::kMeasures[m];
    const double tb = o.offpart_before[m] + o.layup[m], ta = o.offpart_after[m] + o.layup[m];
    std::printf("  %-5s off-part %.6g -> %.6g%s%s (%+.1f %%), total %.6g -> %.6g (%+.1f %%)\n",
                MeasureName(measure), o.offpart_before[m], o.offpart_after[m],
                *run::MeasureUnit(measure) != '\0' ? " " : "", run::MeasureUnit(measure),
                Change(o.offpart_before[m], o.offpart_after[m]), tb, ta, Change(tb, ta));
  }
  const double fb = o.flown_offpart_before_mm, fa = o.flown_offpart_after_mm, l = o.layup[2];
  std::printf(
      "  flown tool path: off-part %.1f -> %.1f mm (%+.1f %%), total %.1f -> %.1f mm "
      "(%+.1f %%)\n",
      fb, fa, Change(fb, fa), fb + l, fa + l, Change(fb + l, fa + l));
}

// The programme, the report (if asked) and the page written as a set: all or none.
int WriteWithPage(const SequenceArgs& a, const run::SequenceInputs& in, const run::SequenceRun& r) {
  std::string error;
  const std::string page = run::SequenceHtmlPage(r, in.program, error);
  if (page.empty()) {
    PrintError("internal", "--html: " + error);
    return kExitInternal;
  }
  std::ostringstream program, report;
  run::WriteSequencedProgram(in, r, program);
  std::vector<std::pair<std::filesystem::path, std::string>> files{
      {a.run.output_file, program.str()}, {a.html, page}};
  if (!a.report.empty()) {
    run::WriteSequenceJson(r.outcome, in.program, report);
    files.emplace_back(a.report, report.str());
  }
  if (error = WriteFilesAtomically(files); !error.empty()) {
    PrintError("io-write", error);
    return kExitBadInput;
  }
  return kExitOk;
}

int RunSequenceCommand(SequenceArgs& a) {
  run::SequenceOptions& o = a.run;
  if (!OutputsDistinct({{"--output", o.output_file}, {"--report", a.report}, {"--html", a.html}}) ||
      !ProgramInputOk(o.program_file))
    return kExitBadInput;
  o.scene_load = SceneLoadOptions();
  o.measure = a.cost == "time"    ? run::Measure::kTime
              : a.cost == "tool"  ? run::Measure::kTool
              : a.cost == "timed" ? run::Measure::kTimed
                                  : run::Measure::kAxes;
  o.solver = a.solver == "exact"  ? run::SequenceSolver::kExact
             : a.solver == "seed" ? run::SequenceSolver::kSeed
                                  : run::SequenceSolver::kLocal;
  DiagnosticSink sink;
  run::SequenceError error;
  const auto in = run::LoadSequenceInputs(o, sink, error);
  PrintDiagnostics(sink);
  if (!error.code.empty()) PrintError(error.code, error.message);
  if (!in) return kExitBadInput;
  PlanProgressPrinter progress("sequence", "courses", a.quiet);
  const run::SequenceRun r = run::RunSequence(*in, o, progress.Callback());
  progress.Finish();
  switch (r.status) {
    case run::SequenceStatus::kOk:
      break;
    case run::SequenceStatus::kUnreachable:
      for (const auto& e : r.unreachable)
        std::printf("%s\n", run::UnreachableMessage(in->program, e).c_str());
      return kExitFindings;
    case run::SequenceStatus::kBadOrder:
    case run::SequenceStatus::kInternal:
      PrintError(r.error.code, r.error.message);
      return r.status == run::SequenceStatus::kBadOrder ? kExitBadInput : kExitInternal;
  }
  const int written =
      a.html.empty()
          ? WriteProgramAndCsv(
                o.output_file, a.report,
                [&](std::ostream& out) { run::WriteSequencedProgram(*in, r, out); },
                [&](std::ostream& out) { run::WriteSequenceJson(r.outcome, in->program, out); })
          : WriteWithPage(a, *in, r);
  if (written != kExitOk) return written;
  PrintSequenceSummary(r.outcome);
  return kExitOk;
}

}  // namespace

void AddSequenceCommand(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<SequenceArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sequence",
      "Reorder an AFP programme's courses within their precedence sets to cut the off-part "
      "motion (seed 004); the lay-ups are kept, the off-part moves regenerated");
  cmd->add_option("program", a->run.program_file,
                  "AFP programme (plies and courses marked: M70/M71/M72)")
      ->required();
  cmd->add_option("--scene", a->run.scene_file, "Scene YAML file (its surface, plies and AFP head)")
      ->required();
  cmd->add_option("-o,--output", a->run.output_file, "Programme file to write")->required();
  cmd->add_option("--report", a->report,
                  "JSON report: costs per set and per ply, and the course order");
  cmd->add_option("--html", a->html,
                  "HTML page: per ply the courses and the original and new off-part paths side "
                  "by side, with the report's figures");
  cmd->add_option("--cost", a->cost,
                  "Cost to minimise: axes (seed eq. 3.4), time, tool, timed (the controller's "
                  "time law)")
      ->check(CLI::IsMember({"axes", "time", "tool", "timed"}));
  cmd->add_option("--solver", a->solver,
                  "local (ours, default), seed (seed 004's method) or exact (dynamic programming, "
                  "sets of up to 16 courses; larger sets use local)")
      ->check(CLI::IsMember({"local", "seed", "exact"}));
  cmd->add_flag("--bidirectional", a->run.bidirectional, "Courses may be laid backwards");
  cmd->add_option("--home", a->run.home,
                  "Home pose X,Y,Z,A,B,C (mm, deg; default: the programme's first pose)");
  cmd->add_flag("--return-home", a->run.return_home,
                "Return to the home pose after the last course");
  cmd->add_option("--time-limit", a->run.time_limit_s, "Seconds the local search may take per set")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--jobs,-j", a->run.jobs,
                  "Threads for the local search's starts (default: the number of cores); the "
                  "order is the same for any number")
      ->check(CLI::Range(0, 256));
  cmd->add_flag("--measure-gap", a->run.measure_gap,
                "Also solve sets of 13 to 16 courses exactly for the optimum (sets of up to 12 "
                "always are)");
  cmd->add_flag("--course-level", a->run.course_level,
                "Course-level precedence: a course may move into an earlier set");
  cmd->add_option("--order", a->run.order_file,
                  "Lay the courses in this order (a report's \"order\") instead of solving");
  AddScenePathFlag(*cmd);
  AddQuietFlag(*cmd, a->quiet);
  cmd->callback([a, &exit_code] { exit_code = RunSequenceCommand(*a); });
}

}  // namespace stitchsim::app
