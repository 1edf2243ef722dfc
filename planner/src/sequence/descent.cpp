// The local search's descent (descent.h): the candidate moves around one course.
#include "descent.h"

#include <algorithm>

namespace stitchsim::planner::detail {

namespace {
constexpr int kMaxChain = 3;  ///< Or-opt chains of 1..kMaxChain courses
using Kind = TourMove::Kind;
}  // namespace

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
  const int c = VisitNode(cv);
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
  for (const Candidate& nv : lists_.out[VisitNode(c)]) {
    const int v = nv.node;
    TryReverse(x + 1, Where(Flip(NodeVisit(v))), Stretch::kFlip);
  }
  for (const Candidate& nu : lists_.in[VisitNode(c)]) {
    const int u = nu.node;
    TryReverse(Where(Flip(NodeVisit(u))), x - 1, Stretch::kFlip);
  }
  for (const Candidate& nv : lists_.out[VisitNode(Flip(c))]) {
    const int v = nv.node;
    const int y = WhereNode(v);
    if (y >= 0) TryReverse(x, y - 1, Stretch::kFlip);
  }
  for (const Candidate& nu : lists_.in[VisitNode(Flip(c))]) {
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
                                                   : Flip(tour_.At(k));
    const Visit last = how == Stretch::kKeep      ? tour_.At(k)
                       : how == Stretch::kReverse ? tour_.At(i)
                                                  : Flip(tour_.At(i));
    for (const Candidate& nu : lists_.in[VisitNode(first)]) {
      if (nu.cost >= cut_in) break;
      const int u = nu.node;
      const int g = WhereNode(u);
      if (g >= 0) TryChain(i, k, g, how);
    }
    for (const Candidate& nv : lists_.out[VisitNode(last)]) {
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
  const int kept = VisitNode(cv), turned = VisitNode(Flip(cv));
  // x first (i = x), the new link replacing the one into x: kept, x entered from t[g] and
  // t[k] -> t[g + 1]; driven backwards, flip(t[x]) -> t[g + 1] and t[g] -> flip(t[k]).
  EnterFrom(kept, in, [&](int g, Visit w) { TryChain(x, Where(w), g, Stretch::kKeep); });
  if (p_.bidirectional) {
    LeaveTo(turned, in, [&](int g, Visit w) {
      const int k = Where(Flip(w));
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
      const int i = Where(Flip(w));
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

}  // namespace stitchsim::planner::detail
