#pragma once
// Ordering the courses of one precedence set (seed 004; docs/sequence.md): a shortest
// Hamiltonian path over courses, each laid forwards or (bidirectional lay-up) backwards,
// from a fixed start point and optionally back to a fixed end point. Pure combinatorics:
// every course end is a point in some space (machine axes, or the tool point), and the cost
// of an off-part move is a norm of the weighted difference of two points. Deterministic:
// identical input gives identical output, whatever the machine load.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace stitchsim::planner {

/// How the difference of two points becomes a cost: sum of |w_i d_i| (the seed's eq. 3.4,
/// weighted axis motion), max of |w_i d_i| (time: w_i = 1 / axis speed, the slowest axis
/// decides), or the Euclidean norm of (w_i d_i) (tool-point distance).
enum class CostNorm { kL1, kMax, kL2 };

/// Move costs given outright instead of as a norm of two points: a measure that is no norm
/// (the controller's time law, `--cost timed`) or a matrix instance (TSPLIB's ATSP). Visits are
/// numbered as nodes u = 2 course + reversed; every array is indexed by node.
struct MoveTable {
  std::vector<double> move;  ///< (2 courses)^2: move[u * 2 courses + v], end of u -> start of v
  std::vector<double> from_start;  ///< 2 courses: start -> start of u
  std::vector<double> to_finish;   ///< 2 courses: end of u -> finish (zeros without a finish)
  double start_to_finish = 0.0;    ///< an empty set's path (0 without a finish)
};

/// The problem for one precedence set (or, with `group`, a run of sets laid in turn). Course i
/// has four points, at rows 4 i + k of `points` (each row `dim` values): k = 0 start and 1 end
/// when laid forwards, 2 start and 3 end when laid backwards. Laying a course costs nothing
/// here (its lay-up is fixed); moving from the end of one course to the start of the next
/// costs Cost(end, start), or the table's entry when `table` is set (then points, weights,
/// start and finish are unused and dim may be 0; `finish` still says whether the path ends at
/// a fixed point).
struct SequenceProblem {
  int courses = 0;
  int dim = 0;
  std::vector<double> points;   ///< 4 * courses rows of dim values
  std::vector<double> weights;  ///< dim values
  CostNorm norm = CostNorm::kL1;
  bool bidirectional = false;                 ///< false: every course laid forwards
  std::vector<double> start;                  ///< dim values: where the head is before the set
  std::optional<std::vector<double>> finish;  ///< dim values: where it must go after (home)
  std::shared_ptr<const MoveTable> table;     ///< explicit costs; null: norms of the points
  /// Per course, its precedence set (0, 1, ...): every course of set g is laid before any of
  /// set g + 1, so the order is the sets' orders joined and the moves between sets are
  /// optimised with them (docs/sequence.md). Empty: one set.
  std::vector<int> group;
};

struct Visit {
  int course = 0;
  bool reversed = false;
  friend bool operator==(const Visit&, const Visit&) = default;
};

/// How a solver stopped, so that an order cut off by a limit says so (ompl's PlannerStatus).
enum class SolveStatus {
  kOptimal,     ///< proven optimal (exact)
  kRoundCap,    ///< a heuristic that ran all the rounds its caps allow (local: max_rounds; the
                ///< seed's method: patience, depth, iterations): a local optimum, unproven
  kTimeLimit,   ///< the local search's time limit cut its rounds: the best found so far
  kGiven,       ///< not solved: the caller's order (`sequence --order`)
  kStagnation,  ///< the local search stopped: its rounds without improvement reached their cap
};
/// "optimal", "round-cap", "time-limit", "given", "stagnation".
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

/// Our solver (docs/sequence.md, "Ours"): iterated local search. Per start, a construction
/// (nearest neighbour, or `initial`), a descent over exactly priced moves (Or-opt chains,
/// stretch reversal with and without flipping the courses, segment insertion, direction
/// flips) on k-nearest candidate lists, then rounds of kicks each followed by a descent,
/// kept unless worse. Several independent starts (different kick seeds), the cheapest kept
/// (ties: the lower start). Deterministic: the work is bounded in rounds, never in seconds:
/// a start stops when `stagnation` rounds in a row found nothing cheaper or after
/// `max_rounds`; only `time_limit_s` (0: none) reads the clock, and the answer says which
/// stop it hit. `jobs` threads run the starts; the answer does not depend on it.
struct LocalSearchOptions {
  double time_limit_s = 0.0;     ///< wall-clock stop for the whole call, s (0: none)
  int neighbours = 10;           ///< candidate list length per visit
  std::int64_t max_rounds = -1;  ///< kick rounds per start at most (-1: automatic; 0: none)
  std::int64_t stagnation = 0;   ///< rounds without improvement that end a start (0: automatic)
  int starts = 0;                ///< independent starts (0: automatic, from n)
  int jobs = 1;                  ///< threads running the starts (>= 1)
  std::vector<Visit> initial;    ///< every start begins from this order when given (dominance)
};
SequenceSolution SolveLocalSearch(const SequenceProblem& p, const LocalSearchOptions& o = {});

/// A lower bound on the cost of every order of p: any solver's answer costs at least this.
struct LowerBound {
  double value = 0.0;           ///< in the problem's cost units
  std::string method;           ///< how it was found ("held-karp", "exact", "trivial")
  std::int64_t iterations = 0;  ///< method-specific work count (reported)
  double seconds = 0.0;         ///< wall time (reported, never used to decide)
};
/// Deterministic work bound of the lower bound's computation.
struct BoundOptions {
  std::int64_t max_work = 300'000'000;  ///< edge evaluations at most
};
LowerBound ComputeLowerBound(const SequenceProblem& p, const BoundOptions& o = {});

/// Exact (Held-Karp dynamic programming over subsets and the last course's direction), for
/// at most kMaxExactCourses courses; nullopt above.
inline constexpr int kMaxExactCourses = 16;
std::optional<SequenceSolution> SolveExact(const SequenceProblem& p);

}  // namespace stitchsim::planner
