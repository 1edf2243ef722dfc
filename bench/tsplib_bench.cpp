// The course-ordering solver on public TSPLIB instances with published optima (issue 28,
// Done-when 1): each instance (bench/data/tsplib/) as one precedence set of zero-length courses
// (TsplibProblem: city 1 is home, start and finish), solved by SolveLocalSearch with its default
// options and then with wall-clock budgets (large round and stagnation caps, so only the time
// stops it), beside the lower bound. Prints a markdown table: n, optimum, ours, gap to the
// optimum %, bound, gap to the bound %, seconds, how the search stopped.
//   build/bench/tsplib_bench [--budgets 1,10,60] [--only berlin52,ftv33] [--data DIR]
//                            [--jobs N] [--no-default]
// A plain executable: its figures are wall-clock budgets, not timings to average.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/planner/sequence/solver.h"
#include "stitchsim/planner/sequence/tsplib.h"

namespace stitchsim::planner {
namespace {

struct BenchOptions {
  std::vector<double> budgets_s{1, 10, 60};  // wall-clock budgets after the default run, s
  std::vector<std::string> only;             // instance names; empty: all of optima.txt
  std::string data = STITCHSIM_TSPLIB_DIR;   // the folder of the instances and optima.txt
  int jobs = 1;                              // LocalSearchOptions::jobs
  bool default_run = true;                   // also run the default options
};

std::vector<std::string> SplitCommas(std::string_view s) {
  std::vector<std::string> out;
  while (!s.empty()) {
    const auto comma = s.find(',');
    out.emplace_back(s.substr(0, comma));
    if (comma == std::string_view::npos) break;
    s.remove_prefix(comma + 1);
  }
  return out;
}

bool ParseBenchArgs(int argc, char** argv, BenchOptions& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--budgets" && has_value) {
      o.budgets_s.clear();
      for (const std::string& b : SplitCommas(argv[++i])) {
        char* end = nullptr;
        const double v = std::strtod(b.c_str(), &end);
        if (end == b.c_str() || *end != '\0' || !(v > 0)) return false;
        o.budgets_s.push_back(v);
      }
    } else if (arg == "--only" && has_value) {
      o.only = SplitCommas(argv[++i]);
    } else if (arg == "--data" && has_value) {
      o.data = argv[++i];
    } else if (arg == "--jobs" && has_value) {
      o.jobs = std::atoi(argv[++i]);
      if (o.jobs < 1) return false;
    } else if (arg == "--no-default") {
      o.default_run = false;
    } else {
      return false;
    }
  }
  return true;
}

void PrintDiagnostics(const DiagnosticSink& sink) {
  for (const Diagnostic& d : sink.Diagnostics())
    std::fprintf(stderr, "%s\n", FormatDiagnostic(d).c_str());
}

std::string BudgetName(double budget_s) {
  return budget_s > 0 ? std::to_string(static_cast<int>(budget_s)) + " s" : "default";
}

double GapPercent(double value, double reference) {
  return reference > 0 ? 100.0 * (value - reference) / reference : 0.0;
}

/// One row: a solve of one instance under one budget (0: the default options).
void SolveAndPrint(const TsplibOptimum& o, const SequenceProblem& p, const LowerBound& bound,
                   double budget_s, int jobs, double& worst_gap) {
  LocalSearchOptions options;
  options.jobs = jobs;
  if (budget_s > 0) {
    options.time_limit_s = budget_s;
    options.max_rounds = std::int64_t{1} << 40;
    options.stagnation = std::int64_t{1} << 40;
  }
  const SequenceSolution s = SolveLocalSearch(p, options);
  const double gap = GapPercent(s.cost, o.optimum);
  worst_gap = std::max(worst_gap, gap);
  const std::string budget = BudgetName(budget_s);
  std::printf("| %s | %s | %d | %.0f | %s | %.0f | %.3f |", o.name.c_str(),
              o.symmetric ? "TSP" : "ATSP", p.courses + 1, o.optimum, budget.c_str(), s.cost, gap);
  std::printf(" %.1f | %.3f | %.2f | %s |\n", bound.value, GapPercent(s.cost, bound.value),
              s.seconds, ToString(s.status));
  std::fflush(stdout);
}

int RunBench(const BenchOptions& bo) {
  DiagnosticSink sink;
  const auto optima = ReadTsplibOptima(bo.data + "/optima.txt", sink);
  if (!optima) {
    PrintDiagnostics(sink);
    return 2;
  }
  std::vector<double> budgets = bo.budgets_s;
  if (bo.default_run) budgets.insert(budgets.begin(), 0.0);
  // Worst gap to the optimum per budget: [b][0] asymmetric, [b][1] symmetric.
  std::vector<std::array<double, 2>> worst(budgets.size(), {0.0, 0.0});
  std::array<int, 2> solved{0, 0};
  std::printf(
      "| instance | type | n | optimum | budget | ours | gap to optimum %% | bound | "
      "gap to bound %% | s | stop |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const TsplibOptimum& o : *optima) {
    if (!bo.only.empty() && std::find(bo.only.begin(), bo.only.end(), o.name) == bo.only.end())
      continue;
    const auto in = ReadTsplib(bo.data + "/" + o.name + (o.symmetric ? ".tsp" : ".atsp"), sink);
    if (!in) {
      PrintDiagnostics(sink);
      return 2;
    }
    const SequenceProblem p = TsplibProblem(*in, false);
    const LowerBound bound = ComputeLowerBound(p);
    for (std::size_t b = 0; b < budgets.size(); ++b)
      SolveAndPrint(o, p, bound, budgets[b], bo.jobs, worst[b][o.symmetric ? 1 : 0]);
    ++solved[o.symmetric ? 1 : 0];
  }
  std::printf("\n");
  for (std::size_t b = 0; b < budgets.size(); ++b)
    std::printf("worst gap to optimum, %s: %.3f %% over %d TSP, %.3f %% over %d ATSP\n",
                BudgetName(budgets[b]).c_str(), worst[b][1], solved[1], worst[b][0], solved[0]);
  return solved[0] + solved[1] > 0 ? 0 : 2;
}

}  // namespace
}  // namespace stitchsim::planner

int main(int argc, char** argv) {
  stitchsim::planner::BenchOptions options;
  if (!stitchsim::planner::ParseBenchArgs(argc, argv, options)) {
    std::fprintf(stderr,
                 "usage: tsplib_bench [--budgets S,S,...] [--only NAME,...] [--data DIR] "
                 "[--jobs N] [--no-default]\n");
    return 2;
  }
  return stitchsim::planner::RunBench(options);
}
