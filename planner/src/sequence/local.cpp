// Our ordering solver: iterated local search. The lead copies this block into
// docs/sequence.md.
//
// Construction. Nearest neighbour: from p.start, repeatedly the cheapest move to an unvisited
// visit (each course forwards, and backwards when bidirectional; with groups, only courses of
// the earliest group not yet finished); ties by course, then forwards first. Bidirectional
// (one set) also greedy (lists.h): the listed moves cheapest first, each kept if it joins the
// end of one chain of courses to the start of another, a chain turned round (every course
// flipped) where that makes the join; then the chains from p.start, the nearest next. The
// cheaper of the two is the start. Nearest neighbour chooses each course's direction for the
// next move only: on a plate of parallel courses in columns it takes the return along a column
// (cheaper than turning the head) again and again, and the search needed seconds to turn it
// into sweeps across the columns (bench/sequence_budget.sh: 290 after the first descent
// against 106 from the greedy start, whose chains are those sweeps). Forward-only keeps
// nearest neighbour: in a trial on TSPLIB (with a swap move, since dropped) the greedy start
// ended gil262 0.08 % above its optimum where nearest neighbour's reached it. Or the caller's
// order.
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
#include <limits>
#include <random>
#include <thread>

#include "descent.h"
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
using detail::Descent;
using detail::NearestNeighbourTour;
using detail::NodeLists;

constexpr std::uint64_t kKickSeed = 0x5eed004;
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
  {
    std::vector<Visit> any;
    for (int c = 0; c < n; ++c) any.push_back({c, false});
    const Tour probe(p, std::move(any));
    setup.lists = BuildNodeLists(probe, p, o.neighbours);
  }
  if (!o.initial.empty()) {
    setup.initial = o.initial;
  } else {
    setup.initial = NearestNeighbourTour(p);
    if (p.bidirectional && p.group.empty()) {
      std::vector<Visit> greedy = detail::GreedyTour(p, setup.lists);
      if (PathCost(p, greedy) < PathCost(p, setup.initial)) setup.initial = std::move(greedy);
    }
  }
  setup.initial_cost = PathCost(p, setup.initial);
  setup.eps = 1e-12 * (1.0 + setup.initial_cost);
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
