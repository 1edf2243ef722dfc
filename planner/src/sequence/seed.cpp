// The seed's ordering method (seed 004, section 3.2), as we read it. The lead copies this
// block into docs/sequence.md.
//
// Graph. One vertex per allowed visit: course c laid forwards, and, when bidirectional, also
// backwards (node 2 c + reversed). The edge from u to v costs the move from u's end to v's
// start (eq. 3.4 or its time / tool variant). Like the seed, the method ignores p.start and
// p.finish while it searches (moves between sets "negligible"): paths are compared by their
// internal cost only; the returned cost is PathCost, which counts both.
//
// Seed pool (step 1). Every vertex (each course start, and end when bidirectional), plus the
// vertex with the largest total move cost from its start to every other vertex's start (it is
// already a vertex, so it only matters once the pool is capped). Cap: above kMaxPool = 64
// vertices the pool is the farthest vertex plus 63 vertices at evenly spaced node indices.
// The seed reads "all ply starts"; our problem has no plies, and course starts are the
// header's reading.
// Steps 2-3. A nearest-neighbour path from each pool vertex; the cheapest path's first vertex
// is the seed. Ties: lower cost first, then pool order (node index).
//
// Phase one (depth-first). Building a path with look-ahead depth d: from the current vertex,
// every look-ahead chain of d moves is enumerated in which each move goes to one of the
// kWidth = 3 nearest unvisited vertices; the path moves to the first vertex of the cheapest
// chain (ties: nearer first). d = 1 is the plain nearest-neighbour path (the seed path).
// Iterations d = 2, 3, ...: a path cheaper than the best so far becomes the best and its d
// the "final depth"; otherwise the no-progress count a rises. The depth rises after every
// iteration (an iteration at an unchanged depth would repeat itself: the method is
// deterministic). Stop when a == patience, d > max_depth or max_iterations paths were built.
// The seed makes max depth and breadth functions of the course and ply count; we take the
// caller's values (defaults 4 and 3), clipped to the course count.
//
// Phase two (breadth-first). k = breadth paths at the final depth, path r (r = 1..k) making
// its first move from the seed to the r-th nearest vertex and continuing as in phase one.
// The cheapest of all paths built is returned; earlier ones win ties.
//
// Bounded work. Every vertex keeps its kListSize = 16 nearest vertices (other courses) with
// their costs, computed once (O(n^2) moves). "Nearest unvisited" walks that list and falls
// back to a scan of the unvisited courses only when the list is exhausted; the unvisited set
// is a compact array, so late scans cost what is left. A path costs
// O(n * 3^d * 16) plus the late scans; with d <= 4, at most 12 + 3 paths and 64 pool paths.
// Release build, plate of 1,000 courses, bidirectional, L1 over 8 axes, default options:
// about 0.04 s (bench/sequence_solver_bench.cpp); 5,000 courses about 0.9 s.
#include <algorithm>
#include <chrono>
#include <limits>

#include "detail.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner {

namespace {

using detail::kInf;

constexpr int kMaxPool = 64;
constexpr int kWidth = 3;
constexpr int kListSize = 16;

struct Neighbour {
  double cost = 0.0;
  int node = 0;
};

/// The vertex graph and the working state of one path build.
class SeedGraph {
 public:
  explicit SeedGraph(const SequenceProblem& p) : p_(p), step_(p.bidirectional ? 1 : 2) {
    const int m = 2 * p.courses;
    lists_.resize(static_cast<std::size_t>(m));
    std::vector<Neighbour> row;
    for (int u = 0; u < m; u += step_) {
      row.clear();
      for (int v = 0; v < m; v += step_) {
        if (u / 2 != v / 2) row.push_back({Cost(u, v), v});
      }
      const auto less = [](const Neighbour& a, const Neighbour& b) {
        return a.cost < b.cost || (a.cost == b.cost && a.node < b.node);
      };
      const std::size_t k = std::min<std::size_t>(kListSize, row.size());
      std::partial_sort(row.begin(), row.begin() + static_cast<std::ptrdiff_t>(k), row.end(), less);
      lists_[u].assign(row.begin(), row.begin() + static_cast<std::ptrdiff_t>(k));
    }
  }

  int Step() const { return step_; }
  double Cost(int u, int v) const {
    return detail::Edge(p_, detail::NodeVisit(u), detail::NodeVisit(v));
  }

  /// Starts a path: every course unvisited.
  void Reset() {
    unvisited_.clear();
    slot_.assign(static_cast<std::size_t>(p_.courses), -1);
    for (int c = 0; c < p_.courses; ++c) {
      slot_[c] = static_cast<int>(unvisited_.size());
      unvisited_.push_back(c);
    }
  }
  bool Visited(int course) const { return slot_[course] < 0; }
  int Left() const { return static_cast<int>(unvisited_.size()); }
  /// Marks a course visited (swap-remove); Unvisit must undo in reverse order.
  void Visit(int course) {
    const int s = slot_[course];
    const int last = unvisited_.back();
    unvisited_[s] = last;
    slot_[last] = s;
    unvisited_.pop_back();
    slot_[course] = -1;
    removed_at_.push_back(s);
  }
  void Unvisit(int course) {
    const int s = removed_at_.back();
    removed_at_.pop_back();
    unvisited_.push_back(course);
    if (s < static_cast<int>(unvisited_.size()) - 1) std::swap(unvisited_[s], unvisited_.back());
    slot_[unvisited_.back()] = static_cast<int>(unvisited_.size()) - 1;
    slot_[unvisited_[s]] = s;
  }

  /// The (at most) `want` nearest unvisited vertices from u, nearest first, ties by node.
  void Nearest(int u, int want, std::vector<Neighbour>& out) const {
    out.clear();
    for (const Neighbour& nb : lists_[u]) {
      if (static_cast<int>(out.size()) == want) return;
      if (!Visited(nb.node / 2)) out.push_back(nb);
    }
    if (static_cast<int>(out.size()) == std::min(want, Left() * (step_ == 1 ? 2 : 1))) return;
    out.clear();  // list exhausted: scan what is left
    for (int c : unvisited_) {
      for (int v = 2 * c; v < 2 * c + 2; v += step_) out.push_back({Cost(u, v), v});
    }
    const auto less = [](const Neighbour& a, const Neighbour& b) {
      return a.cost < b.cost || (a.cost == b.cost && a.node < b.node);
    };
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(want), out.size());
    std::partial_sort(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(k), out.end(), less);
    out.resize(k);
  }

 private:
  const SequenceProblem& p_;
  int step_;
  std::vector<std::vector<Neighbour>> lists_;
  std::vector<int> unvisited_;
  std::vector<int> slot_;
  std::vector<int> removed_at_;
};

/// Cheapest chain of at most `depth` moves from u through the kWidth nearest unvisited.
double LookAhead(SeedGraph& g, int u, int depth) {
  if (depth == 0 || g.Left() == 0) return 0.0;
  std::vector<Neighbour> cands;
  g.Nearest(u, kWidth, cands);
  double best = kInf;
  for (const Neighbour& c : cands) {
    g.Visit(c.node / 2);
    best = std::min(best, c.cost + LookAhead(g, c.node, depth - 1));
    g.Unvisit(c.node / 2);
  }
  return best;
}

struct NodePath {
  std::vector<int> nodes;
  double cost = kInf;  ///< internal moves only
};

/// A path from `seed` (then `first`, if >= 0) choosing each move by a depth-d look-ahead.
NodePath BuildPath(SeedGraph& g, int seed, int first, int depth) {
  NodePath path;
  g.Reset();
  g.Visit(seed / 2);
  path.nodes.push_back(seed);
  path.cost = 0.0;
  if (first >= 0) {
    g.Visit(first / 2);
    path.nodes.push_back(first);
    path.cost += g.Cost(seed, first);
  }
  std::vector<Neighbour> cands;
  while (g.Left() > 0) {
    const int u = path.nodes.back();
    g.Nearest(u, depth == 1 ? 1 : kWidth, cands);
    Neighbour pick = cands.front();
    double pick_total = kInf;
    for (const Neighbour& c : cands) {
      g.Visit(c.node / 2);
      const double total = c.cost + LookAhead(g, c.node, depth - 1);
      g.Unvisit(c.node / 2);
      if (total < pick_total) {
        pick_total = total;
        pick = c;
      }
    }
    g.Visit(pick.node / 2);
    path.nodes.push_back(pick.node);
    path.cost += pick.cost;
  }
  return path;
}

/// The start-vertex pool (steps 1-3 above): the seed vertex.
int PickSeed(SeedGraph& g, const SequenceProblem& p, std::int64_t& paths) {
  const int m = 2 * p.courses;
  std::vector<int> pool;
  int farthest = 0;
  double far_sum = -1.0;
  for (int u = 0; u < m; u += g.Step()) {
    double sum = 0.0;
    for (int v = 0; v < m; v += g.Step()) {
      // Start to start; with a move table (no points) the moves into u stand in for it.
      sum += p.table ? detail::Edge(p, detail::NodeVisit(v), detail::NodeVisit(u))
                     : MoveCost(p, detail::StartOf(p, detail::NodeVisit(u)),
                                detail::StartOf(p, detail::NodeVisit(v)));
    }
    if (sum > far_sum) {
      far_sum = sum;
      farthest = u;
    }
  }
  const int vertices = m / g.Step();
  if (vertices <= kMaxPool) {
    for (int u = 0; u < m; u += g.Step()) pool.push_back(u);
  } else {
    pool.push_back(farthest);
    for (int i = 0; i < kMaxPool - 1; ++i) {
      const int u = static_cast<int>(static_cast<long>(i) * vertices / (kMaxPool - 1)) * g.Step();
      if (u != farthest) pool.push_back(u);
    }
  }
  int seed = pool.front();
  double best = kInf;
  for (int u : pool) {
    const double cost = BuildPath(g, u, -1, 1).cost;
    ++paths;
    if (cost < best) {
      best = cost;
      seed = u;
    }
  }
  return seed;
}

}  // namespace

SequenceSolution SolveSeedMethod(const SequenceProblem& p, const SeedMethodOptions& o) {
  // Its caps end it; nothing proves the answer optimal.
  SequenceSolution s = detail::BeginSolution(p, "seed", SolveStatus::kRoundCap);
  const auto t0 = std::chrono::steady_clock::now();
  if (p.courses > 0) {
    SeedGraph g(p);
    const int seed = PickSeed(g, p, s.iterations);
    NodePath best = BuildPath(g, seed, -1, 1);
    const double eps = 1e-12 * (1.0 + best.cost);
    const int max_depth = std::min(o.max_depth, p.courses);
    int final_depth = 1;
    int no_progress = 0;
    for (int it = 0, d = 2; it < o.max_iterations && d <= max_depth && no_progress < o.patience;
         ++it, ++d) {
      NodePath path = BuildPath(g, seed, -1, d);
      ++s.iterations;
      if (path.cost < best.cost - eps) {
        best = std::move(path);
        final_depth = d;
      } else {
        ++no_progress;
      }
    }
    g.Reset();
    g.Visit(seed / 2);
    std::vector<Neighbour> roots;
    g.Nearest(seed, std::max(0, o.breadth), roots);
    for (const Neighbour& r : roots) {
      NodePath path = BuildPath(g, seed, r.node, final_depth);
      ++s.iterations;
      if (path.cost < best.cost - eps) best = std::move(path);
    }
    for (int u : best.nodes) s.order.push_back(detail::NodeVisit(u));
  }
  s.cost = PathCost(p, s.order);
  s.seconds = detail::SecondsSince(t0);
  return s;
}

}  // namespace stitchsim::planner
