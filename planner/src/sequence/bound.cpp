// A lower bound on the cost of every order of a course-ordering problem (ComputeLowerBound):
// the Held-Karp 1-tree bound with subgradient ascent on node penalties, on an undirected graph
// that the Jonker-Volgenant 2-node transformation makes from the path problem.
//
// The graph: nodes A_i (course i's forward start side) and B_i (its forward end side) for every
// course, S (start) and F (finish); N = 2 n + 2. A visit enters a course on one side and leaves
// it on the other: laid forwards it enters at A_i and leaves at B_i, laid backwards it enters at
// B_i and leaves at A_i. A and B are labels of the sides, not points: the reversed visit's own
// start and end (its node 2 i + 1 in the table, or points rows 4 i + 2 and 3, which in axes
// measures differ from the forward end and start turned round) are what its moves are priced
// from, so the relaxation assumes nothing about geometry. Every order then maps to a Hamiltonian
// cycle S, (entry, exit) of each visit, F, back to S that holds the forced edges {A_i, B_i} and
// {S, F} (cost 0), and each other edge of the cycle is one move of the order:
// - {exit of a, entry of b}: Edge(a, b); {S, entry of b}: FromStart(b); {exit of a, F}:
//   ToFinish(a) (0 without a finish: F is then a free end).
// An undirected edge can be used in two ways (which side is the exit); it costs the cheaper way
// that the lay-up allows: forward-only, {B_i, A_j} = Edge(i fwd, j fwd) and {A_i, A_j}, {B_i, B_j},
// {S, B_j}, {F, A_i} are forbidden, so the transformation is exact (every Hamiltonian cycle with
// the forced edges is an order of the same cost); bidirectional, each edge is the minimum of its
// two uses, so every order's cycle costs at most the order: a relaxation, still a lower bound.
// Precedence groups are ignored: the ungrouped problem allows more orders, so its bound holds.
//
// The 1-tree (with two special nodes): a spanning tree of the course nodes that holds the
// forced {A_i, B_i} edges (Prim adds a node's partner right after the node), plus the forced
// {S, F} and the cheapest other edge of S and of F. Every cycle of the transformation is one:
// without S and F it is a Hamiltonian path of the course nodes. S and F are kept out of the
// tree because without a finish every {F, B_i} costs 0: in a plain 1-tree F would take them
// all (a star of cost 0) and the ascent would need many rounds to undo it. Penalties pi make edge
// costs c + pi_u + pi_v; the tree's cost minus 2 sum(pi) is a lower bound for any pi; the ascent
// (Held and Karp, with Volgenant and Jonker's step rule as LKH uses it) moves pi along the degree
// excess. Work is counted in edge evaluations, never in seconds, so the answer does not depend on
// the machine.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "detail.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner {
namespace {

using detail::kInf;

// Largest node count whose full cost matrix is kept (2^22 doubles, 32 MiB: about 1,000
// courses); above it every cost is computed where it is needed.
constexpr std::int64_t kMaxCachedCosts = std::int64_t{1} << 22;

// The undirected costs of the transformation. Node numbering: A_i = 2 i, B_i = 2 i + 1,
// S = 2 n, F = 2 n + 1.
class TwoNodeGraph {
 public:
  explicit TwoNodeGraph(const SequenceProblem& p)
      : p_(p), n_(p.courses), nodes_(2 * p.courses + 2) {
    const auto nodes = static_cast<std::int64_t>(nodes_);
    if (nodes * nodes > kMaxCachedCosts) return;
    cache_.assign(static_cast<std::size_t>(nodes * nodes), kInf);
    for (int u = 0; u < nodes_; ++u) {
      for (int v = u + 1; v < nodes_; ++v) {
        const double c = Compute(u, v);
        cache_[Index(u, v)] = c;
        cache_[Index(v, u)] = c;
      }
    }
  }
  int Nodes() const { return nodes_; }
  int S() const { return 2 * n_; }
  int F() const { return 2 * n_ + 1; }
  /// Cost of the edge {u, v} (u != v, not a forced pair); kInf when the lay-up forbids it.
  double Cost(int u, int v) const { return cache_.empty() ? Compute(u, v) : cache_[Index(u, v)]; }
  /// The costs of u's edges to the course nodes `to` (indexed by node): the cached row, or
  /// `scratch` filled for those nodes.
  const double* CourseRow(int u, const std::vector<int>& to, std::vector<double>& scratch) const {
    if (!cache_.empty()) return cache_.data() + Index(u, 0);
    scratch.resize(static_cast<std::size_t>(nodes_));
    for (const int v : to) scratch[static_cast<std::size_t>(v)] = Compute(u, v);
    return scratch.data();
  }

 private:
  std::size_t Index(int u, int v) const {
    return static_cast<std::size_t>(u) * static_cast<std::size_t>(nodes_) +
           static_cast<std::size_t>(v);
  }
  bool Allowed(Visit v) const { return p_.bidirectional || !v.reversed; }
  // The visit of a course node's course that leaves (exit) or enters (entry) through it.
  static Visit ExitThrough(int node) { return {node / 2, (node & 1) == 0}; }
  static Visit EntryThrough(int node) { return {node / 2, (node & 1) == 1}; }
  // The move leaving through `from` and entering through `to` (course nodes).
  double Move(int from, int to) const {
    const Visit a = ExitThrough(from), b = EntryThrough(to);
    return Allowed(a) && Allowed(b) ? detail::Edge(p_, a, b) : kInf;
  }
  double Compute(int u, int v) const {
    if (u > v) std::swap(u, v);
    if (v == F() && u == S()) return 0.0;  // forced; never asked
    if (v == F()) {
      const Visit a = ExitThrough(u);
      return Allowed(a) ? detail::ToFinish(p_, a) : kInf;
    }
    if (v == S()) {
      const Visit b = EntryThrough(u);
      return Allowed(b) ? detail::FromStart(p_, b) : kInf;
    }
    return std::min(Move(u, v), Move(v, u));
  }

  const SequenceProblem& p_;
  int n_ = 0, nodes_ = 0;
  std::vector<double> cache_;  // nodes_^2, row = u; empty: computed on demand
};

// One 1-tree under penalties `pi`: its penalised cost minus 2 sum(pi) (the bound), each node's
// degree, and the sum of the magnitudes of the terms (for the rounding margin).
struct OneTree {
  double bound = 0.0;
  double magnitude = 0.0;
  std::vector<int> degree;
};

class OneTreeSolver {
 public:
  explicit OneTreeSolver(const TwoNodeGraph& g)
      : g_(g),
        key_(static_cast<std::size_t>(g.Nodes())),
        parent_(static_cast<std::size_t>(g.Nodes())) {}

  OneTree Solve(const std::vector<double>& pi, std::int64_t& work) {
    const int nodes = g_.Nodes(), s = g_.S(), f = g_.F();
    OneTree t;
    t.degree.assign(static_cast<std::size_t>(nodes), 0);
    double sum = 0.0, magnitude = 0.0;
    auto add_edge = [&](int u, int v, double penalised) {
      sum += penalised;
      magnitude += std::abs(penalised);
      ++t.degree[static_cast<std::size_t>(u)];
      ++t.degree[static_cast<std::size_t>(v)];
    };
    // Dense Prim over the course nodes, from course 0's pair; a course node's partner joins
    // with it. One pass over the nodes still out both lowers their keys by the pair just
    // joined and finds the next one to join.
    rest_.clear();
    for (int v = 2; v < nodes - 2; ++v) {
      key_[static_cast<std::size_t>(v)] = kInf;
      rest_.push_back(v);
    }
    add_edge(0, 1, pi[0] + pi[1]);
    int u = 0, w = 1;
    while (!rest_.empty()) {
      const double pu = pi[static_cast<std::size_t>(u)], pw = pi[static_cast<std::size_t>(w)];
      const double* cost_u = g_.CourseRow(u, rest_, scratch_u_);
      const double* cost_w = g_.CourseRow(w, rest_, scratch_w_);
      std::size_t best = 0;
      double best_key = kInf;
      for (std::size_t k = 0; k < rest_.size(); ++k) {
        const auto v = static_cast<std::size_t>(rest_[k]);
        double& key = key_[v];
        const double cu = cost_u[v] + pu + pi[v];
        if (cu < key) {
          key = cu;
          parent_[v] = u;
        }
        const double cw = cost_w[v] + pw + pi[v];
        if (cw < key) {
          key = cw;
          parent_[v] = w;
        }
        if (key < best_key) {  // the first of equal keys: the lowest node
          best_key = key;
          best = k;
        }
      }
      work += 2 * static_cast<std::int64_t>(rest_.size());
      if (best_key == kInf) return NoFiniteTree(nodes);
      u = rest_[best];
      w = u ^ 1;
      add_edge(u, parent_[static_cast<std::size_t>(u)], best_key);
      add_edge(u, w, pi[static_cast<std::size_t>(u)] + pi[static_cast<std::size_t>(w)]);
      // Drop both from the nodes still out (order kept: the scan, and so ties, stay fixed).
      rest_.erase(
          std::remove_if(rest_.begin(), rest_.end(), [&](int v) { return v == u || v == w; }),
          rest_.end());
    }
    // S and F: the forced edge between them and each one's cheapest edge to a course node.
    add_edge(s, f, pi[static_cast<std::size_t>(s)] + pi[static_cast<std::size_t>(f)]);
    for (const int end : {s, f}) {
      double cheapest = kInf;
      int other = -1;
      for (int v = 0; v < nodes - 2; ++v) {
        const double c =
            g_.Cost(end, v) + pi[static_cast<std::size_t>(end)] + pi[static_cast<std::size_t>(v)];
        if (c < cheapest) {
          cheapest = c;
          other = v;
        }
      }
      work += nodes - 2;
      if (cheapest == kInf) return NoFiniteTree(nodes);
      add_edge(end, other, cheapest);
    }
    double pi_sum = 0.0;
    for (const double x : pi) {
      pi_sum += x;
      magnitude += 2.0 * std::abs(x);
    }
    t.bound = sum - 2.0 * pi_sum;
    t.magnitude = magnitude;
    return t;
  }

 private:
  // No spanning tree of finite cost: no order of finite cost either, so +inf bounds them all
  // (every degree 2 so that the ascent stops).
  static OneTree NoFiniteTree(int nodes) {
    OneTree t;
    t.bound = kInf;
    t.degree.assign(static_cast<std::size_t>(nodes), 2);
    return t;
  }

  const TwoNodeGraph& g_;
  std::vector<double> key_;
  std::vector<int> parent_;
  std::vector<int> rest_;                      // course nodes not yet in the tree, ascending
  std::vector<double> scratch_u_, scratch_w_;  // rows computed on demand (no cache)
};

// Sum of squared degree excesses: 0 when the 1-tree is a tour (the bound is then its cost).
double ExcessNorm(const OneTree& t) {
  double norm = 0.0;
  for (const int d : t.degree) norm += static_cast<double>((d - 2) * (d - 2));
  return norm;
}

// The best of every 1-tree the ascent computes, less a rounding margin (the sums are taken in
// another order than PathCost's: a bound equal to the optimum must not exceed it).
struct Ascent {
  double best = -kInf;
  double margin = 0.0;
  std::int64_t trees = 0;
  void Keep(const OneTree& t) {
    ++trees;
    if (std::isfinite(t.magnitude) && t.bound > best) {  // NaN compares false
      best = t.bound;
      margin = 1e-10 * t.magnitude;
    }
  }
};

// The subgradient ascent: steps along 0.7 of the degree excess and 0.3 of the last one; the
// step doubles while the bound improves in the first phase, then each period (halved each time)
// ends with the step halved. Stops on a tour, a step below 1e-6 of an average edge, the periods
// run out, or the work cap.
Ascent HeldKarpAscent(const TwoNodeGraph& g, std::int64_t max_work) {
  const int nodes = g.Nodes();
  const std::int64_t per_tree = static_cast<std::int64_t>(nodes) * nodes / 2 + nodes;
  std::vector<double> pi(static_cast<std::size_t>(nodes), 0.0);
  OneTreeSolver solver(g);
  std::int64_t work = 0;
  OneTree t = solver.Solve(pi, work);
  Ascent a;
  a.Keep(t);
  double norm = ExcessNorm(t);
  const int courses = nodes / 2 - 1;
  const double scale = t.bound > 0.0 ? t.bound / (courses + 1) : 1.0;  // an average edge
  double step = 0.01 * scale;
  const double min_step = 1e-6 * scale;
  const std::int64_t budget = std::max<std::int64_t>(max_work / per_tree, 1);
  std::int64_t period =
      std::min<std::int64_t>(std::max(nodes / 2, 100), std::max<std::int64_t>(budget / 4, 2));
  std::vector<int> last_excess(static_cast<std::size_t>(nodes), 0);
  bool initial_phase = true;
  auto more_work = [&] { return work + per_tree <= max_work; };
  for (; period > 0 && step > min_step && norm > 0.0 && more_work(); period /= 2, step /= 2) {
    for (std::int64_t round = 1; round <= period && norm > 0.0 && more_work(); ++round) {
      for (std::size_t v = 0; v < pi.size(); ++v) {
        const int excess = t.degree[v] - 2;
        pi[v] += step * (0.7 * excess + 0.3 * last_excess[v]);
        last_excess[v] = excess;
      }
      const double before = a.best;
      t = solver.Solve(pi, work);
      a.Keep(t);
      norm = std::isfinite(t.bound) ? ExcessNorm(t) : 0.0;  // penalties overflowed: stop
      if (a.best > before) {
        if (initial_phase) step *= 2;
        if (round == period) period *= 2;
      } else if (initial_phase && round > period / 2) {
        initial_phase = false;
        round = 0;
        step *= 0.75;
      }
    }
  }
  return a;
}

}  // namespace

LowerBound ComputeLowerBound(const SequenceProblem& p, const BoundOptions& o) {
  detail::AssertWellFormed(p);
  const auto t0 = std::chrono::steady_clock::now();
  LowerBound b;
  if (p.courses == 0) {
    b.value = detail::StartToFinish(p);
    b.method = "trivial";
  } else if (p.courses == 1) {
    b.value = detail::FromStart(p, {0, false}) + detail::ToFinish(p, {0, false});
    if (p.bidirectional)
      b.value = std::min(b.value, detail::FromStart(p, {0, true}) + detail::ToFinish(p, {0, true}));
    b.method = "exact";
  } else {
    const TwoNodeGraph g(p);
    const Ascent a = HeldKarpAscent(g, o.max_work);
    b.value = a.best - a.margin;
    b.iterations = a.trees;
    b.method = "held-karp";
  }
  b.seconds = detail::SecondsSince(t0);
  return b;
}

}  // namespace stitchsim::planner
