#pragma once
// Ordering the courses of one precedence set (seed 004; docs/sequence.md): a shortest
// Hamiltonian path over courses, each laid forwards or (bidirectional lay-up) backwards,
// from a fixed start point and optionally back to a fixed end point. Pure combinatorics:
// every course end is a point in some space (machine axes, or the tool point), and the cost
// of an off-part move is a norm of the weighted difference of two points. Deterministic:
// identical input gives identical output, whatever the machine load.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace stitchsim::planner {

/// How the difference of two points becomes a cost: sum of |w_i d_i| (the seed's eq. 3.4,
/// weighted axis motion), max of |w_i d_i| (time: w_i = 1 / axis speed, the slowest axis
/// decides), or the Euclidean norm of (w_i d_i) (tool-point distance).
enum class CostNorm { kL1, kMax, kL2 };

/// The problem for one precedence set. Course i has four points, at rows 4 i + k of `points`
/// (each row `dim` values): k = 0 start and 1 end when laid forwards, 2 start and 3 end when
/// laid backwards. Laying a course costs nothing here (its lay-up is fixed); moving from the
/// end of one course to the start of the next costs Cost(end, start).
struct SequenceProblem {
  int courses = 0;
  int dim = 0;
  std::vector<double> points;   ///< 4 * courses rows of dim values
  std::vector<double> weights;  ///< dim values
  CostNorm norm = CostNorm::kL1;
  bool bidirectional = false;                 ///< false: every course laid forwards
  std::vector<double> start;                  ///< dim values: where the head is before the set
  std::optional<std::vector<double>> finish;  ///< dim values: where it must go after (home)
};

struct Visit {
  int course = 0;
  bool reversed = false;
  friend bool operator==(const Visit&, const Visit&) = default;
};

/// How a solver stopped, so that an order cut off by a limit says so (ompl's PlannerStatus).
enum class SolveStatus {
  kOptimal,    ///< proven optimal (exact)
  kRoundCap,   ///< a heuristic that ran all the rounds its caps allow (local: max_rounds; the
               ///< seed's method: patience, depth, iterations): a local optimum, unproven
  kTimeLimit,  ///< the local search's time limit cut its rounds: the best found so far
  kGiven,      ///< not solved: the caller's order (`sequence --order`)
};
/// "optimal", "round-cap", "time-limit", "given".
const char* ToString(SolveStatus status);

struct SequenceSolution {
  std::vector<Visit> order;                  ///< every course exactly once
  double cost = 0.0;                         ///< start -> ... -> finish (if any), by PathCost
  std::string solver;                        ///< "seed", "local", "exact", "given"
  SolveStatus status = SolveStatus::kGiven;  ///< set by the solver that made `order`
  double seconds = 0.0;                      ///< wall time taken (reported, never used to decide)
  std::int64_t iterations = 0;               ///< solver-specific work count (reported)
};

/// Cost of one move between two points of dim values each.
double MoveCost(const SequenceProblem& p, const double* from, const double* to);
/// Cost of `order` from p.start through every visit to p.finish (if set).
double PathCost(const SequenceProblem& p, const std::vector<Visit>& order);

/// The seed's method (section 3.2), as we read it: a start-vertex pool (every course start,
/// and end when bidirectional, plus the vertex farthest from all others), a nearest-neighbour
/// path from each, the best kept as the seed; then the depth-first local search (look-ahead
/// chains of `depth` nearest vertices, depth raised while it finds a cheaper path, stopping
/// after `patience` iterations without one, at `max_depth` or `max_iterations`), then one
/// breadth-first pass rooted at the 1st..k-th nearest vertices at the final depth. Like the
/// seed it ignores p.start when choosing the seed (motion between sets negligible); PathCost
/// of its answer still counts it. Its parameters are documented in docs/sequence.md.
struct SeedMethodOptions {
  int patience = 3;
  int max_depth = 4;
  int max_iterations = 12;
  int breadth = 3;
};
SequenceSolution SolveSeedMethod(const SequenceProblem& p, const SeedMethodOptions& o = {});

/// Our solver: nearest-neighbour construction from p.start, then Or-opt (move a chain of
/// 1..3 courses, either way round) and 2-opt (reverse a stretch, flipping each course's
/// direction when bidirectional) over k-nearest candidate lists until no move improves or the
/// time limit. Time-bounded but deterministic: the limit is checked in whole rounds and
/// `max_rounds` bounds the work, so a loaded machine can stop it earlier only through
/// `time_limit_s` (0: no time limit; identical output guaranteed).
struct LocalSearchOptions {
  double time_limit_s = 0.0;
  int neighbours = 12;
  int max_rounds = 1000;
};
SequenceSolution SolveLocalSearch(const SequenceProblem& p, const LocalSearchOptions& o = {});

/// Exact (Held-Karp dynamic programming over subsets and the last course's direction), for
/// at most kMaxExactCourses courses; nullopt above.
inline constexpr int kMaxExactCourses = 16;
std::optional<SequenceSolution> SolveExact(const SequenceProblem& p);

}  // namespace stitchsim::planner
