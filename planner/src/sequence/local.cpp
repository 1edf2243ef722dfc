// Our ordering solver: nearest-neighbour construction, then a descent over Or-opt, 2-opt and
// segment-insertion moves priced exactly, then perturbation. The lead copies this block into
// docs/sequence.md.
//
// Construction. From p.start, repeatedly the cheapest move to an unvisited visit (each course
// forwards, and backwards when bidirectional); ties by course, then forwards first.
//
// Moves (Tour, tour.h, prices each exactly in O(1) from prefix sums of the tour's
// forward cost and of its backwards traversal; costs are not symmetric):
// - Or-opt: a chain of 1..3 courses moved elsewhere, as it was or, when bidirectional, laid
//   backwards (order reversed, every course flipped).
// - 2-opt (bidirectional only): a stretch reversed, every course in it flipped; a stretch of
//   one course is a single flip.
// - Segment insertion (both modes): a stretch of any length moved elsewhere unchanged (the
//   3-opt "or-3opt" move). It replaces 2-opt when NOT bidirectional, where a stretch cannot be
//   laid backwards.
// Candidates come from k-nearest lists per visit (a course in one direction): the
// options.neighbours visits of other courses with the cheapest move into it, and out of it
// (O(n^2) moves to build, once). A move is tried only if one of its new links is from such a
// list and joins visits as the tour lays them now (plus moves to the very start and end).
//
// Descent. A FIFO queue of courses (initially in tour order); for the course popped, every
// candidate move around it is priced and the best improving one (ties: first found) applied;
// the courses at the changed links are queued again. It ends when the queue is empty.
//
// Direction pass (bidirectional). When the queue is empty, every course's direction is chosen
// anew for the order found, exactly (a shortest path over two states per position, O(n));
// if that saves anything the changed courses are queued and the descent resumes.
//
// Perturbation. Then, for at most options.max_rounds rounds: 1..3 kicks (each a random
// stretch of 1..S courses, S = min(10, n / 2), moved to a random place at most 2 S positions
// away, flipped with probability 1/2 when bidirectional: a segment kick that contains the
// double-bridge of two adjacent stretches; draws from std::mt19937_64 with a fixed seed), a
// descent from the kicks' courses; the result replaces the current tour unless it is worse
// (equal cost is accepted, so plateaus, common under the max norm, can be crossed), and the
// cheapest tour seen is returned.
// A move or kick counts as an improvement only if it saves more than 1e-12 (1 + the
// nearest-neighbour tour's cost).
//
// Work and memory. Up to 1,024 courses every move cost is tabled once ((2n)^2 doubles, 32 MiB
// at 1,024); above, costs are computed when needed. Building the lists is O(n^2); a move
// is priced in O(1) and applied in O(n). Release build, 2-core machine, plate of 1,000
// courses, bidirectional, L1 over 8 axes, default options: about 0.25 s for the whole call
// (bench/sequence_solver_bench.cpp).
//
// Determinism and the time limit. Everything above is a function of the input; the clock is
// read only between rounds. Without a time limit (0) or when the rounds run out before it, the
// output is identical on every run. When the limit cuts the rounds, the answer is the best
// found so far; it is still a descent's local optimum and never worse than the first one, but
// how many kicks it saw depends on the machine's speed (SequenceSolution::iterations reports
// the moves applied plus the rounds run).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>

#include "detail.h"
#include "stitchsim/planner/sequence/solver.h"
#include "tour.h"

namespace stitchsim::planner {

namespace {

using detail::Tour;
using detail::TourMove;
using Kind = TourMove::Kind;

constexpr std::uint64_t kKickSeed = 0x5eed004;
constexpr int kMaxChain = 3;
constexpr int kMaxKickStretch = 10;
constexpr std::uint64_t kMaxKicks = 3;

std::vector<Visit> NearestNeighbourTour(const SequenceProblem& p) {
  std::vector<Visit> order;
  std::vector<char> used(static_cast<std::size_t>(p.courses), 0);
  const int dirs = p.bidirectional ? 2 : 1;
  for (int step = 0; step < p.courses; ++step) {
    Visit best{};
    double best_cost = std::numeric_limits<double>::infinity();
    for (int c = 0; c < p.courses; ++c) {
      if (used[c]) continue;
      for (int r = 0; r < dirs; ++r) {
        const Visit v{c, r == 1};
        const double cost =
            order.empty() ? detail::FromStart(p, v) : detail::Edge(p, order.back(), v);
        if (cost < best_cost) {
          best_cost = cost;
          best = v;
        }
      }
    }
    used[best.course] = 1;
    order.push_back(best);
  }
  return order;
}

/// For every visit node (2 course + reversed), the k nodes of other courses with the cheapest
/// move into it (in) and out of it (out), ties by node; forward nodes only if unidirectional.
struct NodeLists {
  std::vector<std::vector<int>> in, out;
};

NodeLists BuildNodeLists(const Tour& tour, const SequenceProblem& p, int k) {
  const int m = 2 * p.courses;
  const int step = p.bidirectional ? 1 : 2;
  NodeLists lists;
  lists.in.resize(static_cast<std::size_t>(m));
  lists.out.resize(static_cast<std::size_t>(m));
  std::vector<std::pair<double, int>> into, from;
  for (int a = 0; a < m; a += step) {
    into.clear();
    from.clear();
    const Visit va = detail::NodeVisit(a);
    for (int b = 0; b < m; b += step) {
      if (a / 2 == b / 2) continue;
      const Visit vb = detail::NodeVisit(b);
      into.push_back({tour.Move(vb, va), b});
      from.push_back({tour.Move(va, vb), b});
    }
    const std::size_t kk =
        std::min<std::size_t>(static_cast<std::size_t>(std::max(0, k)), into.size());
    for (auto* row : {&into, &from}) {
      std::partial_sort(row->begin(), row->begin() + static_cast<std::ptrdiff_t>(kk), row->end());
      auto& list = row == &into ? lists.in[a] : lists.out[a];
      for (std::size_t i = 0; i < kk; ++i) list.push_back((*row)[i].second);
    }
  }
  return lists;
}

/// The descent: candidate moves around queued courses, best improving one applied.
class Descent {
 public:
  Descent(const SequenceProblem& p, Tour& tour, const NodeLists& lists, double eps)
      : p_(p),
        tour_(tour),
        lists_(lists),
        eps_(eps),
        queued_(static_cast<std::size_t>(p.courses), 0) {}

  void Push(int course) {
    if (queued_[course]) return;
    queued_[course] = 1;
    queue_.push_back(course);
  }
  /// Queues the courses at the links a move changes (call before applying it).
  void PushEnds(const TourMove& m);
  /// Descends, then re-chooses every course's direction for the order found, and descends
  /// again while that helps; returns the moves applied.
  std::int64_t Run() {
    std::int64_t applied = Drain();
    std::vector<Visit> turned;
    while (p_.bidirectional && tour_.Size() > 0) {
      const double delta = tour_.BestDirections(turned);
      if (!(delta < -eps_)) break;
      for (int x = 0; x < tour_.Size(); ++x) {
        if (turned[x].reversed != tour_.At(x).reversed) QueueAround(x);
      }
      tour_.Restore(turned, tour_.Cost() + delta);
      applied += 1 + Drain();
    }
    return applied;
  }

 private:
  void QueueAround(int x) {
    for (int y = std::max(0, x - 1); y <= std::min(tour_.Size() - 1, x + 1); ++y)
      Push(tour_.At(y).course);
  }
  /// Runs until no queued course has an improving move; returns the moves applied.
  std::int64_t Drain() {
    std::int64_t applied = 0;
    while (!queue_.empty()) {
      const int c = queue_.front();
      queue_.pop_front();
      queued_[c] = 0;
      best_ = TourMove{};
      best_.delta = -eps_;
      TryAround(tour_.PositionOf(c));
      if (best_.kind == Kind::kNone) continue;
      PushEnds(best_);
      tour_.Apply(best_);
      Push(c);
      ++applied;
    }
    return applied;
  }
  /// Position of v's course if it is laid as v now, else -1.
  int Where(Visit v) const {
    const int x = tour_.PositionOf(v.course);
    return tour_.At(x).reversed == v.reversed ? x : -1;
  }
  void Offer(Kind kind, int i, int k, int g, bool flip, double delta) {
    if (delta < best_.delta) best_ = TourMove{kind, i, k, g, flip, delta};
  }
  void TryReverse(int i, int k) {
    if (i < 0 || k >= tour_.Size() || i > k) return;
    Offer(Kind::kReverse, i, k, 0, false, tour_.ReverseDelta(i, k));
  }
  void TryChain(int i, int k, int g, bool flip) {
    const int n = tour_.Size();
    if (i < 0 || k >= n || i > k || g < -1 || g >= n || (g >= i - 1 && g <= k)) return;
    if (flip && !p_.bidirectional) return;
    Offer(Kind::kChain, i, k, g, flip, tour_.ChainDelta(i, k, g, flip));
  }
  void TryAround(int x);
  void TryOrOpt(int i, int k);
  void TrySegments(int x);

  const SequenceProblem& p_;
  Tour& tour_;
  const NodeLists& lists_;
  double eps_;
  std::deque<int> queue_;
  std::vector<char> queued_;
  TourMove best_;
};

void Descent::TryAround(int x) {
  const int n = tour_.Size();
  const Visit c = tour_.At(x);
  if (p_.bidirectional) {
    TryReverse(x, x);
    TryReverse(0, x);
    TryReverse(x, n - 1);
    for (int v : lists_.out[detail::VisitNode(c)]) {
      TryReverse(x + 1, Where(detail::Flip(detail::NodeVisit(v))));  // c -> flipped stretch
    }
    for (int u : lists_.in[detail::VisitNode(c)]) {
      TryReverse(Where(detail::Flip(detail::NodeVisit(u))), x - 1);  // flipped stretch -> c
    }
    for (int v : lists_.out[detail::VisitNode(detail::Flip(c))]) {
      TryReverse(x, Where(detail::NodeVisit(v)) - 1);  // stretch from c, flipped -> v
    }
    for (int u : lists_.in[detail::VisitNode(detail::Flip(c))]) {
      TryReverse(Where(detail::NodeVisit(u)) + 1, x);  // u -> stretch to c, flipped
    }
  }
  for (int len = 1; len <= kMaxChain; ++len) {
    TryOrOpt(x, x + len - 1);
    if (len > 1) TryOrOpt(x - len + 1, x);
  }
  TrySegments(x);
}

void Descent::TryOrOpt(int i, int k) {
  const int n = tour_.Size();
  if (i < 0 || k >= n) return;
  for (int f = 0; f < (p_.bidirectional ? 2 : 1); ++f) {
    const bool flip = f == 1;
    TryChain(i, k, -1, flip);
    TryChain(i, k, n - 1, flip);
    const Visit first = flip ? detail::Flip(tour_.At(k)) : tour_.At(i);
    const Visit last = flip ? detail::Flip(tour_.At(i)) : tour_.At(k);
    for (int u : lists_.in[detail::VisitNode(first)]) {
      const int g = Where(detail::NodeVisit(u));
      if (g >= 0) TryChain(i, k, g, flip);
    }
    for (int v : lists_.out[detail::VisitNode(last)]) {
      const int h = Where(detail::NodeVisit(v));
      if (h >= 0) TryChain(i, k, h - 1, flip);
    }
  }
}

// Stretches of any length moved unchanged: new links t[g] -> t[i] and t[k] -> t[g+1] both
// from the lists, with the course at x as the stretch's first or last.
void Descent::TrySegments(int x) {
  const int n = tour_.Size();
  const int c = detail::VisitNode(tour_.At(x));
  for (int u : lists_.in[c]) {  // stretch starts at x, goes after g
    const int g = Where(detail::NodeVisit(u));
    if (g < 0 || g + 1 >= n) continue;
    for (int w : lists_.in[detail::VisitNode(tour_.At(g + 1))]) {
      TryChain(x, Where(detail::NodeVisit(w)), g, false);
    }
  }
  for (int v : lists_.out[c]) {  // stretch ends at x, goes after h
    const int h = Where(detail::NodeVisit(v)) - 1;
    if (h < 0) continue;
    for (int w : lists_.out[detail::VisitNode(tour_.At(h))]) {
      const int i = Where(detail::NodeVisit(w));
      if (i >= 0) TryChain(i, x, h, false);
    }
  }
}

void Descent::PushEnds(const TourMove& m) {
  const int n = tour_.Size();
  for (int x : {m.i - 1, m.i, m.k, m.k + 1, m.g, m.g + 1}) {
    if (x >= 0 && x < n) Push(tour_.At(x).course);
  }
}

/// A kick: a random stretch of 1..max_stretch courses moved at most 2 max_stretch positions
/// away, flipped with probability 1/2 when bidirectional; kNone if the draw is not a move.
TourMove RandomKick(const Tour& tour, std::mt19937_64& rng, int max_stretch, bool bidirectional) {
  const auto draw = [&rng](int count) {
    return static_cast<int>(rng() % static_cast<std::uint64_t>(std::max(1, count)));
  };
  const int n = tour.Size();
  const int len = 1 + draw(std::min(max_stretch, n - 1));
  const int i = draw(n - len + 1);
  const int k = i + len - 1;
  const int reach = 2 * max_stretch;
  const int lo = std::max(-1, i - 1 - reach), hi = std::min(n - 1, k + reach);
  int g = lo + draw(hi - lo + 1);
  const bool flip = bidirectional && (rng() & 1u) != 0;
  if (g >= i - 1 && g <= k) g = g - i + 1 < k - g ? i - 2 : k + 1;  // step out of the stretch
  if (g < -1 || g >= n) return TourMove{};
  TourMove m{Kind::kChain, i, k, g, flip, 0.0};
  m.delta = tour.ChainDelta(i, k, g, flip);
  return m;
}

}  // namespace

SequenceSolution SolveLocalSearch(const SequenceProblem& p, const LocalSearchOptions& o) {
  SequenceSolution s = detail::BeginSolution(p, "local", SolveStatus::kRoundCap);
  const auto t0 = std::chrono::steady_clock::now();
  const int n = p.courses;
  Tour tour(p, NearestNeighbourTour(p));
  const double eps = 1e-12 * (1.0 + tour.Cost());
  const NodeLists lists = BuildNodeLists(tour, p, o.neighbours);
  Descent descent(p, tour, lists, eps);
  for (const Visit& v : tour.Order()) descent.Push(v.course);
  s.iterations += descent.Run();
  std::mt19937_64 rng(kKickSeed);
  const int max_stretch = std::min(kMaxKickStretch, std::max(1, n / 2));
  std::vector<Visit> best = tour.Order(), saved;
  double best_cost = tour.Cost();
  for (int round = 0; n >= 3 && round < o.max_rounds; ++round) {
    if (o.time_limit_s > 0 && detail::SecondsSince(t0) >= o.time_limit_s) {
      s.status = SolveStatus::kTimeLimit;
      break;
    }
    ++s.iterations;
    saved = tour.Order();
    const double saved_cost = tour.Cost();
    for (int kicks = 1 + static_cast<int>(rng() % kMaxKicks); kicks > 0; --kicks) {
      const TourMove kick = RandomKick(tour, rng, max_stretch, p.bidirectional);
      descent.PushEnds(kick);
      tour.Apply(kick);
    }
    s.iterations += descent.Run();
    if (tour.Cost() > saved_cost + eps) {
      tour.Restore(saved, saved_cost);
    } else if (tour.Cost() < best_cost - eps) {
      best = tour.Order();
      best_cost = tour.Cost();
    }
  }
  s.order = best;
  s.cost = PathCost(p, s.order);
  s.seconds = detail::SecondsSince(t0);
  return s;
}

}  // namespace stitchsim::planner
