#pragma once
// The local search's descent (local.cpp): from the courses queued, every candidate move around
// each is priced on the tour and the best improving one applied, until none improves;
// bidirectional, then the directions of the changed stretch chosen afresh. The moves and the
// candidates are described in local.cpp.
#include <cstdint>
#include <deque>
#include <vector>

#include "detail.h"
#include "lists.h"
#include "stitchsim/planner/sequence/solver.h"
#include "tour.h"

namespace stitchsim::planner::detail {

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
      if (best_.kind == TourMove::Kind::kNone) continue;
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
  int WhereNode(int node) const { return Where(NodeVisit(node)); }
  void Offer(TourMove::Kind kind, int i, int k, int g, Stretch how, double delta) {
    if (delta < best_.delta) best_ = TourMove{kind, i, k, g, how, delta};
  }
  void TryReverse(int i, int k, Stretch how) {
    if (!tour_.CanTurn(i, k) || (how == Stretch::kReverse && i == k)) return;
    if (how == Stretch::kFlip && !p_.bidirectional) return;
    Offer(TourMove::Kind::kReverse, i, k, 0, how, tour_.ReverseDelta(i, k, how));
  }
  void TryChain(int i, int k, int g, Stretch how) {
    if (!tour_.CanMove(i, k, g)) return;
    if (how == Stretch::kFlip && !p_.bidirectional) return;
    if (how == Stretch::kReverse && i == k) return;
    Offer(TourMove::Kind::kChain, i, k, g, how, tour_.ChainDelta(i, k, g, how));
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
      for (const Candidate& nw : lists_.in[VisitNode(tour_.At(g + 1))]) {
        if (nw.cost >= gap) break;
        f(g, NodeVisit(nw.node));
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
      for (const Candidate& nw : lists_.out[VisitNode(tour_.At(h))]) {
        if (nw.cost >= gap) break;
        f(h, NodeVisit(nw.node));
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

}  // namespace stitchsim::planner::detail
