// Our ordering solver: iterated local search. The lead copies this block into
// docs/sequence.md.
//
// Construction. From p.start, repeatedly the cheapest move to an unvisited visit (each course
// forwards, and backwards when bidirectional; with groups, only courses of the earliest
// group not yet finished); ties by course, then forwards first. Or the caller's order.
//
// Moves (Tour, tour.h, prices each exactly in O(1) from prefix sums of the tour's forward
// cost, of its backwards traversal with every course as laid, and with every course flipped;
// costs are not symmetric):
// - Or-opt: a chain of 1..3 courses (starting at the course popped) moved elsewhere, as it was,
//   in reverse order (each course still laid its way), or, when bidirectional, laid backwards
//   (reverse order, each flipped).
// - Stretch reversal (2-opt), in both lay-up modes: a stretch visited in reverse order with
//   each course still laid its way (legal with forward-only lay-up), or, when bidirectional,
//   with every course flipped (the stretch driven backwards; one course: a single flip).
// - Segment insertion (both modes): a stretch of any length moved elsewhere, as it was or,
//   bidirectional, driven backwards (the 3-opt "or-3opt" move, and with the stretch turned);
//   both new links from the lists. (The stretch in reverse order, each course laid its way,
//   is left out: on the TSPLIB programmes it led the search to worse orders, a280 +0.8 %.)
// Candidates come from k-nearest lists per visit (a course in one direction): the
// options.neighbours visits of other courses (same or neighbouring group) with the cheapest
// move into it, and out of it (O(n^2) moves to build, once). A move is tried only if one of
// its new links is from such a list and joins visits as the tour lays them now (plus moves
// to the very start and end). With groups a move never takes a course out of its group's
// block of positions, so the moves between groups are optimised with the rest.
//
// Descent. A FIFO queue of courses (initially in tour order); for the course popped, every
// candidate move around it is priced and the best improving one (ties: first found) applied;
// the courses at the changed links are queued again. It ends when the queue is empty.
//
// Direction pass (bidirectional). When the queue is empty, the direction of every course in the
// stretch the moves changed (and one either side; the whole tour after the construction) is
// chosen anew for the order found, exactly, the courses around it as laid (a shortest path
// over two states per position); if that saves anything the changed courses are queued and
// the descent resumes. Candidate lists keep their move costs, so the gain test reads no table.
//
// Kicks. Each round: 1..3 kicks (each a random stretch of 1..S courses, S = min(30, n / 2),
// moved to a random place at most 2 S positions away, within its block, laid as it was, in
// reverse order or, bidirectional, flipped: a segment kick that contains the double bridge
// of two adjacent stretches), then a descent from the kicks' courses; the result replaces the
// current tour unless it is worse (equal cost is accepted, so plateaus, common under the max
// norm, can be crossed). A move or kick counts as an improvement only if it saves more than
// 1e-12 (1 + the construction's cost).
//
// Starts and stops. options.starts independent starts (default 8 up to 300 courses, else 2), each
// from the same construction with its own kick sequence (std::mt19937_64 seeded with the start's
// number); the cheapest answer wins, ties to the lower start. A start stops when `stagnation`
// rounds in a row found nothing cheaper (default max(5000, 10 n)) or after max_rounds (default 50
// times that): a count of rounds, so the answer is the same on any machine. options.jobs threads
// run the starts; the answer does not depend on how many. Only time_limit_s reads the clock
// (between rounds); when it cuts a start, the answer is the best found so far and says so.
//
// Dominance. Bidirectional lay-up allows every forward-only order, so a bidirectional search
// without a given order first solves the forward-only problem (the same search, with the same
// options, as a forward-only call), then begins its first start at that answer (the others
// at its own construction, for variety): it can only end at or below the forward-only answer. With
// a time limit the forward-only phase gets a tenth of it (then the guarantee holds only when no
// limit cut either run).
//
// Work and memory. Up to 1,024 courses every move cost is tabled once per call ((2n)^2
// doubles, 32 MiB at 1,024, shared by both phases and every start; a MoveTable problem brings
// its own); above, costs are computed when needed.
// Building the lists is O(n^2); a move is priced in O(1) and applied in O(changed positions)
// table look-ups plus one add per later position; a round that is not kept is undone by
// copying back the positions it changed.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <thread>

#include "detail.h"
#include "lists.h"
#include "stitchsim/planner/sequence/solver.h"
#include "tour.h"

namespace stitchsim::planner {

namespace {

using detail::Stretch;
using detail::Tour;
using detail::TourMove;
using Kind = TourMove::Kind;
using detail::BuildNodeLists;
using detail::Candidate;
using detail::NearestNeighbourTour;
using detail::NodeLists;

constexpr std::uint64_t kKickSeed = 0x5eed004;
constexpr int kMaxChain = 3;
constexpr int kMaxKickStretch = 30;
constexpr std::uint64_t kMaxKicks = 3;
constexpr int kDefaultStarts = 2;
// Sets of up to kSmallSet courses get kSmallSetStarts starts: a start of the search is cheap
// there and one start's answer depends on its kicks' luck (TSPLIB's a280: 0.08 % or 1.4 %
// above the optimum with two different seeds); the cheapest of 8 is steady.
constexpr int kSmallSet = 300;
constexpr int kSmallSetStarts = 8;
constexpr std::int64_t kMinStagnation = 5000;
constexpr std::int64_t kStagnationPerCourse = 10;
constexpr std::int64_t kRoundsPerStagnation = 50;

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
      // Directions afresh over the stretch the moves changed (and one course either side).
      const int lo = std::max(0, tour_.TouchedBegin() - 1);
      const int hi = std::min(tour_.Size() - 1, tour_.TouchedEnd() + 1);
      tour_.ClearTouched();
      const double delta = tour_.BestDirections(lo, hi, turned);
      if (!(delta < -eps_)) break;
      for (int x = lo; x <= hi; ++x) {
        if (turned[x - lo].reversed != tour_.At(x).reversed) QueueAround(x);
      }
      tour_.Turn(lo, turned, delta);
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
  int WhereNode(int node) const { return Where(detail::NodeVisit(node)); }
  void Offer(Kind kind, int i, int k, int g, Stretch how, double delta) {
    if (delta < best_.delta) best_ = TourMove{kind, i, k, g, how, delta};
  }
  void TryReverse(int i, int k, Stretch how) {
    if (!tour_.CanTurn(i, k) || (how == Stretch::kReverse && i == k)) return;
    if (how == Stretch::kFlip && !p_.bidirectional) return;
    Offer(Kind::kReverse, i, k, 0, how, tour_.ReverseDelta(i, k, how));
  }
  void TryChain(int i, int k, int g, Stretch how) {
    if (!tour_.CanMove(i, k, g)) return;
    if (how == Stretch::kFlip && !p_.bidirectional) return;
    if (how == Stretch::kReverse && i == k) return;
    Offer(Kind::kChain, i, k, g, how, tour_.ChainDelta(i, k, g, how));
  }
  /// For every new link u -> `node` from the lists cheaper than `limit`, with u laid at g,
  /// and every new link w -> t[g + 1] from the lists cheaper than the link into g + 1 now:
  /// f(g, w).
  template <class F>
  void EnterFrom(int node, double limit, F&& f) {
    for (const Candidate& nu : lists_.in[node]) {
      if (nu.cost >= limit) break;
      const int g = WhereNode(nu.node);
      if (g < 0 || g + 1 >= tour_.Size()) continue;
      const double gap = tour_.CostInto(g + 1);
      for (const Candidate& nw : lists_.in[detail::VisitNode(tour_.At(g + 1))]) {
        if (nw.cost >= gap) break;
        f(g, detail::NodeVisit(nw.node));
      }
    }
  }
  /// For every new link `node` -> v from the lists cheaper than `limit`, with v laid at h + 1,
  /// and every new link t[h] -> w from the lists cheaper than the link out of h now: f(h, w).
  template <class F>
  void LeaveTo(int node, double limit, F&& f) {
    for (const Candidate& nv : lists_.out[node]) {
      if (nv.cost >= limit) break;
      const int h = WhereNode(nv.node) - 1;
      if (h < 0) continue;
      const double gap = tour_.CostOutOf(h);
      for (const Candidate& nw : lists_.out[detail::VisitNode(tour_.At(h))]) {
        if (nw.cost >= gap) break;
        f(h, detail::NodeVisit(nw.node));
      }
    }
  }
  void TryAround(int x);
  void TryReversals(int x);
  void TryFlips(int x);
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
  TryReversals(x);
  if (p_.bidirectional) TryFlips(x);
  for (int len = 1; len <= kMaxChain; ++len) TryOrOpt(x, x + len - 1);
  TrySegments(x);
}

// A stretch visited in reverse order, each course laid its own way: new links
// t[i-1] -> t[k] and t[i] -> t[k+1], one of them from the lists with the course at x as an end.
void Descent::TryReversals(int x) {
  const Visit cv = tour_.At(x);
  const int c = detail::VisitNode(cv);
  const int lo = tour_.BlockBegin(x), hi = tour_.BlockEnd(x);
  TryReverse(lo, x, Stretch::kReverse);
  TryReverse(x, hi, Stretch::kReverse);
  const double out = tour_.CostOutOf(x), in = tour_.CostInto(x);
  for (const Candidate& nv : lists_.out[c]) {  // new link c -> v replaces c's way out
    if (nv.cost >= out) break;
    const int v = nv.node;
    const int y = WhereNode(v);
    if (y > x) TryReverse(x + 1, y, Stretch::kReverse);  // c -> t[k]: stretch x+1..y
    if (y > x) TryReverse(x, y - 1, Stretch::kReverse);  // t[i] = c -> t[k+1] = v
  }
  for (const Candidate& nu : lists_.in[c]) {  // new link u -> c replaces c's way in
    if (nu.cost >= in) break;
    const int u = nu.node;
    const int y = WhereNode(u);
    if (y >= 0 && y < x) TryReverse(y, x - 1, Stretch::kReverse);  // t[i] = u -> t[k+1] = c
    if (y >= 0 && y < x) TryReverse(y + 1, x, Stretch::kReverse);  // t[i-1] = u -> t[k] = c
  }
}

// Bidirectional: a stretch driven backwards, every course flipped.
void Descent::TryFlips(int x) {
  const int n = tour_.Size();
  const Visit c = tour_.At(x);
  TryReverse(x, x, Stretch::kFlip);
  TryReverse(std::max(0, tour_.BlockBegin(x)), x, Stretch::kFlip);
  TryReverse(x, std::min(n - 1, tour_.BlockEnd(x)), Stretch::kFlip);
  for (const Candidate& nv : lists_.out[detail::VisitNode(c)]) {
    const int v = nv.node;
    TryReverse(x + 1, Where(detail::Flip(detail::NodeVisit(v))), Stretch::kFlip);
  }
  for (const Candidate& nu : lists_.in[detail::VisitNode(c)]) {
    const int u = nu.node;
    TryReverse(Where(detail::Flip(detail::NodeVisit(u))), x - 1, Stretch::kFlip);
  }
  for (const Candidate& nv : lists_.out[detail::VisitNode(detail::Flip(c))]) {
    const int v = nv.node;
    const int y = WhereNode(v);
    if (y >= 0) TryReverse(x, y - 1, Stretch::kFlip);
  }
  for (const Candidate& nu : lists_.in[detail::VisitNode(detail::Flip(c))]) {
    const int u = nu.node;
    const int y = WhereNode(u);
    if (y >= 0) TryReverse(y + 1, x, Stretch::kFlip);
  }
}

void Descent::TryOrOpt(int i, int k) {
  const int n = tour_.Size();
  if (i < 0 || k >= n) return;
  // The chain's links with the tour: a new link into it must beat the one into it now, a new
  // link out of it the one out of it now (the gain criterion on sorted lists).
  const double cut_in = std::max(tour_.CostInto(i), tour_.CostOutOf(k)), cut_out = cut_in;
  for (const Stretch how : {Stretch::kKeep, Stretch::kReverse, Stretch::kFlip}) {
    if ((how == Stretch::kFlip && !p_.bidirectional) || (how == Stretch::kReverse && i == k))
      continue;
    TryChain(i, k, tour_.BlockBegin(i) - 1, how);
    TryChain(i, k, tour_.BlockEnd(i), how);
    const Visit first = how == Stretch::kKeep      ? tour_.At(i)
                        : how == Stretch::kReverse ? tour_.At(k)
                                                   : detail::Flip(tour_.At(k));
    const Visit last = how == Stretch::kKeep      ? tour_.At(k)
                       : how == Stretch::kReverse ? tour_.At(i)
                                                  : detail::Flip(tour_.At(i));
    for (const Candidate& nu : lists_.in[detail::VisitNode(first)]) {
      if (nu.cost >= cut_in) break;
      const int u = nu.node;
      const int g = WhereNode(u);
      if (g >= 0) TryChain(i, k, g, how);
    }
    for (const Candidate& nv : lists_.out[detail::VisitNode(last)]) {
      if (nv.cost >= cut_out) break;
      const int v = nv.node;
      const int h = WhereNode(v);
      if (h >= 0) TryChain(i, k, h - 1, how);
    }
  }
}

// Stretches of any length moved elsewhere, laid as they were or driven backwards
// (bidirectional): both new links from the lists, one at the course at x, the stretch's first
// or last position.
void Descent::TrySegments(int x) {
  const Visit cv = tour_.At(x);
  const double in = tour_.CostInto(x), out = tour_.CostOutOf(x);
  const int kept = detail::VisitNode(cv), turned = detail::VisitNode(detail::Flip(cv));
  // x first (i = x), the new link replacing the one into x: kept, x entered from t[g] and
  // t[k] -> t[g + 1]; driven backwards, flip(t[x]) -> t[g + 1] and t[g] -> flip(t[k]).
  EnterFrom(kept, in, [&](int g, Visit w) { TryChain(x, Where(w), g, Stretch::kKeep); });
  if (p_.bidirectional) {
    LeaveTo(turned, in, [&](int g, Visit w) {
      const int k = Where(detail::Flip(w));
      if (k >= x) TryChain(x, k, g, Stretch::kFlip);
    });
  }
  // x last (k = x), the new link replacing the one out of x: kept, x -> t[h + 1] and
  // t[h] -> t[i]; driven backwards, t[g] -> flip(t[x]) and flip(t[i]) -> t[g + 1].
  LeaveTo(kept, out, [&](int h, Visit w) {
    const int i = Where(w);
    if (i >= 0) TryChain(i, x, h, Stretch::kKeep);
  });
  if (p_.bidirectional) {
    EnterFrom(turned, out, [&](int g, Visit w) {
      const int i = Where(detail::Flip(w));
      if (i >= 0 && i <= x) TryChain(i, x, g, Stretch::kFlip);
    });
  }
}

void Descent::PushEnds(const TourMove& m) {
  const int n = tour_.Size();
  for (int x : {m.i - 1, m.i, m.k, m.k + 1, m.g, m.g + 1}) {
    if (x >= 0 && x < n) Push(tour_.At(x).course);
  }
}

/// A kick: a random stretch of 1..max_stretch courses of one block moved at most
/// 2 max_stretch positions away within it, laid as it was, reversed or (bidirectional)
/// flipped; kNone if the draw is not a move.
TourMove RandomKick(const Tour& tour, std::mt19937_64& rng, int max_stretch, bool bidirectional) {
  const auto draw = [&rng](int count) {
    return static_cast<int>(rng() % static_cast<std::uint64_t>(std::max(1, count)));
  };
  const int n = tour.Size();
  const int i = draw(n);
  const int lo = tour.BlockBegin(i), hi = tour.BlockEnd(i);
  const int size = hi - lo + 1;
  if (size < 3) return TourMove{};
  const int len = 1 + draw(std::min(max_stretch, size - 1));
  const int k = std::min(hi, i + len - 1);
  const int reach = 2 * max_stretch;
  const int glo = std::max(lo - 1, i - 1 - reach), ghi = std::min(hi, k + reach);
  int g = glo + draw(ghi - glo + 1);
  const std::uint64_t mode = rng() % (bidirectional ? 3u : 2u);
  const Stretch how = mode == 0 ? Stretch::kKeep : mode == 1 ? Stretch::kReverse : Stretch::kFlip;
  if (g >= i - 1 && g <= k) g = g - i + 1 < k - g ? i - 2 : k + 1;  // step out of the stretch
  if (!tour.CanMove(i, k, g)) return TourMove{};
  TourMove m{Kind::kChain, i, k, g, (how == Stretch::kReverse && i == k) ? Stretch::kKeep : how,
             0.0};
  m.delta = tour.ChainDelta(i, k, g, m.how);
  return m;
}

/// One start's answer.
struct StartResult {
  std::vector<Visit> order;
  double cost = 0.0;
  std::int64_t iterations = 0;
  SolveStatus status = SolveStatus::kStagnation;
};

/// The shared, read-only part of a search: the problem, the construction, the lists.
struct SearchSetup {
  const SequenceProblem& p;
  std::vector<Visit> initial;  ///< where start 0 begins (every start, when `others` is empty)
  std::vector<Visit> others;   ///< where starts 1, 2, ... begin, if not at `initial`
  double initial_cost = 0.0;
  double eps = 0.0;
  NodeLists lists;
  std::int64_t stagnation = 0, max_rounds = 0;
  int max_stretch = 1;
  double time_limit_s = 0.0;
  std::chrono::steady_clock::time_point t0{};
};

StartResult RunStart(const SearchSetup& setup, int start) {
  const SequenceProblem& p = setup.p;
  StartResult r;
  Tour tour(p, start > 0 && !setup.others.empty() ? setup.others : setup.initial);
  Descent descent(p, tour, setup.lists, setup.eps);
  for (const Visit& v : tour.Order()) descent.Push(v.course);
  r.iterations += descent.Run();
  std::mt19937_64 rng(kKickSeed + static_cast<std::uint64_t>(start));
  std::vector<Visit> best = tour.Order(), saved;
  double best_cost = tour.Cost();
  std::int64_t since_better = 0;
  for (std::int64_t round = 0; p.courses >= 3; ++round) {
    if (since_better >= setup.stagnation) break;
    if (round >= setup.max_rounds) {
      r.status = SolveStatus::kRoundCap;
      break;
    }
    if (setup.time_limit_s > 0 && detail::SecondsSince(setup.t0) >= setup.time_limit_s) {
      r.status = SolveStatus::kTimeLimit;
      break;
    }
    ++r.iterations;
    ++since_better;
    saved = tour.Order();
    const double saved_cost = tour.Cost();
    tour.Mark();
    for (int kicks = 1 + static_cast<int>(rng() % kMaxKicks); kicks > 0; --kicks) {
      const TourMove kick = RandomKick(tour, rng, setup.max_stretch, p.bidirectional);
      descent.PushEnds(kick);
      tour.Apply(kick);
    }
    r.iterations += descent.Run();
    if (tour.Cost() > saved_cost + setup.eps) {
      tour.Restore(saved, saved_cost);
    } else if (tour.Cost() < best_cost - setup.eps) {
      best = tour.Order();
      best_cost = tour.Cost();
      since_better = 0;
    }
  }
  r.order = std::move(best);
  r.cost = PathCost(p, r.order);
  return r;
}

/// The search's setup: every start at o.initial, or at the construction.
SearchSetup MakeSetup(const SequenceProblem& p, const LocalSearchOptions& o,
                      std::chrono::steady_clock::time_point t0) {
  const int n = p.courses;
  SearchSetup setup{p, {}, {}, 0.0, 0.0, {}, 0, 0, 1, 0.0, t0};
  setup.initial = o.initial.empty() ? NearestNeighbourTour(p) : o.initial;
  setup.initial_cost = PathCost(p, setup.initial);
  setup.eps = 1e-12 * (1.0 + setup.initial_cost);
  {
    const Tour probe(p, setup.initial);
    setup.lists = BuildNodeLists(probe, p, o.neighbours);
  }
  setup.stagnation =
      o.stagnation > 0 ? o.stagnation : std::max(kMinStagnation, kStagnationPerCourse * n);
  setup.max_rounds = o.max_rounds >= 0 ? o.max_rounds : kRoundsPerStagnation * setup.stagnation;
  setup.max_stretch = std::min(kMaxKickStretch, std::max(1, n / 2));
  setup.time_limit_s = o.time_limit_s;
  return setup;
}

/// Start 0 begins at `from` from now on, the others where every start began.
void BeginFirstAt(SearchSetup& setup, const std::vector<Visit>& from) {
  setup.others = std::move(setup.initial);
  setup.initial = from;
  setup.initial_cost = PathCost(setup.p, setup.initial);
  setup.eps = 1e-12 * (1.0 + setup.initial_cost);
}

/// The iterated local search, every start on o.jobs threads; the cheapest start's answer.
SequenceSolution Search(const SearchSetup& setup, const LocalSearchOptions& o) {
  SequenceSolution s = detail::BeginSolution(setup.p, "local", SolveStatus::kStagnation);
  const int starts = o.starts > 0                   ? o.starts
                     : setup.p.courses <= kSmallSet ? kSmallSetStarts
                                                    : kDefaultStarts;
  std::vector<StartResult> results(static_cast<std::size_t>(starts));
  std::atomic<int> next{0};
  const auto worker = [&] {
    for (int k = next++; k < starts; k = next++) results[k] = RunStart(setup, k);
  };
  const int threads = std::clamp(o.jobs, 1, starts);
  std::vector<std::thread> pool;
  for (int j = 1; j < threads; ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  std::size_t best = 0;
  for (std::size_t k = 0; k < results.size(); ++k) {
    s.iterations += results[k].iterations;
    if (results[k].cost < results[best].cost) best = k;
    // The stop that says the most: a time limit over a round cap over stagnation.
    if (results[k].status == SolveStatus::kTimeLimit ||
        (results[k].status == SolveStatus::kRoundCap && s.status != SolveStatus::kTimeLimit))
      s.status = results[k].status;
  }
  s.order = std::move(results[best].order);
  s.cost = results[best].cost;
  return s;
}

}  // namespace

SequenceSolution SolveLocalSearch(const SequenceProblem& given, const LocalSearchOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  // Every move cost tabled once, shared by both phases and every start (and thread).
  SequenceProblem tabled;
  if (!given.table && given.courses >= 2 && given.courses <= detail::kTableCourses) {
    tabled = given;
    tabled.table = detail::TableOf(given);
  }
  const SequenceProblem& p = tabled.table ? tabled : given;
  SequenceSolution s;
  SearchSetup setup = MakeSetup(p, o, t0);
  if (p.bidirectional && o.initial.empty() && p.courses >= 2) {
    // Dominance: every forward-only order is a bidirectional one; start from the best of them.
    // With a time limit the forward-only phase gets a tenth of it: the bidirectional search
    // that follows is the one that uses the freedom.
    SequenceProblem forward = p;
    forward.bidirectional = false;
    LocalSearchOptions once = o;
    once.time_limit_s = o.time_limit_s / 10.0;
    const SequenceSolution first = Search(MakeSetup(forward, once, t0), once);
    BeginFirstAt(setup, first.order);
    s = Search(setup, o);
    s.iterations += first.iterations;
    if (first.status == SolveStatus::kTimeLimit) s.status = SolveStatus::kTimeLimit;
  } else {
    s = Search(setup, o);
  }
  s.seconds = detail::SecondsSince(t0);
  return s;
}

}  // namespace stitchsim::planner
