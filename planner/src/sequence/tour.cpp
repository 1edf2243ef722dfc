// The local search's tour: exact O(1) prices of stretch reversals and moves (see the header).
#include "tour.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace stitchsim::planner::detail {

Tour::Tour(const SequenceProblem& p, std::vector<Visit> order) : p_(p), t_(std::move(order)) {
  pos_.assign(static_cast<std::size_t>(p.courses), -1);
  const int m = 2 * p.courses;
  stride_ = static_cast<std::size_t>(m);
  for (int u = 0; u < m; ++u) {
    from_start_.push_back(FromStart(p, NodeVisit(u)));
    to_finish_.push_back(ToFinish(p, NodeVisit(u)));
  }
  if (p.table) tab_ = p.table->move.data();
  // Blocks: the positions of each group, in the order the tour lays the groups.
  const int n = Size();
  block_lo_.assign(static_cast<std::size_t>(n), 0);
  block_hi_.assign(static_cast<std::size_t>(n), n - 1);
  if (!p.group.empty()) {
    for (int x = 0; x < n;) {
      int y = x;
      while (y + 1 < n && p.group[t_[y + 1].course] == p.group[t_[x].course]) ++y;
      for (int z = x; z <= y; ++z) {
        block_lo_[z] = x;
        block_hi_[z] = y;
      }
      x = y + 1;
    }
  }
  Refresh(0, Size() - 1);
  cost_ = PathCost(p_, t_);
  touched_lo_ = 0;  // every direction still to choose
  touched_hi_ = n - 1;
}

std::shared_ptr<const MoveTable> TableOf(const SequenceProblem& p) {
  auto t = std::make_shared<MoveTable>();
  const int m = 2 * p.courses;
  const auto stride = static_cast<std::size_t>(m);
  t->move.resize(stride * stride);
  for (int a = 0; a < m; ++a) {
    t->from_start.push_back(FromStart(p, NodeVisit(a)));
    t->to_finish.push_back(ToFinish(p, NodeVisit(a)));
    for (int b = 0; b < m; ++b) t->move[a * stride + b] = Edge(p, NodeVisit(a), NodeVisit(b));
  }
  t->start_to_finish = StartToFinish(p);
  return t;
}

double Tour::Link(int x, int y) const {
  if (y >= Size()) {
    if (x >= 0) return F(t_[x]);
    return StartToFinish(p_);
  }
  return In(x, t_[y]);
}

double Tour::Inside(int i, int k, Stretch how) const {
  switch (how) {
    case Stretch::kKeep:
      return fwd_[k] - fwd_[i];
    case Stretch::kReverse:
      return bwd_[k] - bwd_[i];
    case Stretch::kFlip:
      return rev_[k] - rev_[i];
  }
  return 0.0;
}

double Tour::ReverseDelta(int i, int k, Stretch how) const {
  const double after =
      In(i - 1, FirstOf(i, k, how)) + Out(LastOf(i, k, how), k + 1) + Inside(i, k, how);
  const double before = In(i - 1, t_[i]) + Out(t_[k], k + 1) + Inside(i, k, Stretch::kKeep);
  return after - before;
}

double Tour::ChainDelta(int i, int k, int g, Stretch how) const {
  const double removal = Link(i - 1, k + 1) - In(i - 1, t_[i]) - Out(t_[k], k + 1);
  const double insertion =
      In(g, FirstOf(i, k, how)) + Out(LastOf(i, k, how), g + 1) - Link(g, g + 1);
  return removal + insertion + Inside(i, k, how) - Inside(i, k, Stretch::kKeep);
}

void Tour::Apply(const TourMove& m) {
  if (m.kind == TourMove::Kind::kNone) return;
  const auto begin = t_.begin();
  int from = m.i, to = m.k;
  if (m.kind == TourMove::Kind::kReverse) {
    std::reverse(begin + m.i, begin + m.k + 1);
    if (m.how == Stretch::kFlip) {
      for (int x = m.i; x <= m.k; ++x) t_[x] = Flip(t_[x]);
    }
  } else {
    scratch_.assign(begin + m.i, begin + m.k + 1);
    if (m.how != Stretch::kKeep) std::reverse(scratch_.begin(), scratch_.end());
    if (m.how == Stretch::kFlip) {
      for (Visit& v : scratch_) v = Flip(v);
    }
    const int len = m.k - m.i + 1;
    if (m.g < m.i) {  // shift g+1..i-1 right by len
      std::move_backward(begin + m.g + 1, begin + m.i, begin + m.k + 1);
      std::copy(scratch_.begin(), scratch_.end(), begin + m.g + 1);
      from = m.g + 1;
    } else {  // shift k+1..g left by len
      std::move(begin + m.k + 1, begin + m.g + 1, begin + m.i);
      std::copy(scratch_.begin(), scratch_.end(), begin + m.g + 1 - len);
      to = m.g;
    }
  }
  cost_ += m.delta;
  TouchRange(m.kind == TourMove::Kind::kReverse ? m.i : std::min(m.i, m.g + 1),
             m.kind == TourMove::Kind::kReverse ? m.k : std::max(m.k, m.g));
  // Now and then the whole tour afresh, so the constant shifts below never drift.
  if (++applied_ % kFullRefresh == 0) {
    Refresh(0, Size() - 1);
  } else {
    Refresh(std::max(0, from), to);
  }
}

double Tour::BestDirections(int lo, int hi, std::vector<Visit>& out) const {
  const int n = Size();
  lo = std::max(0, lo);
  hi = std::min(n - 1, hi);
  if (lo > hi || !p_.bidirectional) return 0.0;
  const int len = hi - lo + 1;
  // best[x][r]: cheapest way to have laid positions lo..lo+x with lo+x in direction r, from
  // position lo - 1 as it is laid.
  std::vector<std::array<double, 2>> best(static_cast<std::size_t>(len));
  std::vector<std::array<std::uint8_t, 2>> from(static_cast<std::size_t>(len), {0, 0});
  for (int r = 0; r < 2; ++r) best[0][r] = In(lo - 1, {t_[lo].course, r == 1});
  for (int x = 1; x < len; ++x) {
    const int at = lo + x;
    for (int r = 0; r < 2; ++r) {
      const Visit v{t_[at].course, r == 1};
      const double via0 = best[x - 1][0] + E({t_[at - 1].course, false}, v);
      const double via1 = best[x - 1][1] + E({t_[at - 1].course, true}, v);
      best[x][r] = via1 < via0 ? via1 : via0;
      from[x][r] = via1 < via0 ? 1 : 0;
    }
  }
  const double end0 = best[len - 1][0] + Out({t_[hi].course, false}, hi + 1);
  const double end1 = best[len - 1][1] + Out({t_[hi].course, true}, hi + 1);
  out.assign(t_.begin() + lo, t_.begin() + hi + 1);
  int r = end1 < end0 ? 1 : 0;
  for (int x = len - 1; x >= 0; --x) {
    out[x].reversed = r == 1;
    r = from[x][r];
  }
  const double now = fwd_[hi] - fwd_[lo] + CostInto(lo) + CostOutOf(hi);
  return std::min(end0, end1) - now;
}

void Tour::Turn(int lo, const std::vector<Visit>& turned, double delta) {
  std::copy(turned.begin(), turned.end(), t_.begin() + lo);
  cost_ += delta;
  // Not touched for the direction pass (it chose these), but changed since Mark.
  round_lo_ = std::min(round_lo_, lo);
  round_hi_ = std::max(round_hi_, lo + static_cast<int>(turned.size()) - 1);
  Refresh(lo, lo + static_cast<int>(turned.size()) - 1);
}

void Tour::Restore(const std::vector<Visit>& order, double cost) {
  cost_ = cost;
  if (round_lo_ <= round_hi_) {
    std::copy(order.begin() + round_lo_, order.begin() + round_hi_ + 1, t_.begin() + round_lo_);
    Refresh(round_lo_, round_hi_);
  }
  Mark();
  ClearTouched();  // a saved tour: its directions were chosen when it was saved
}

void Tour::Refresh(int from, int to) {
  const int n = Size();
  fwd_.resize(static_cast<std::size_t>(n));
  bwd_.resize(static_cast<std::size_t>(n));
  rev_.resize(static_cast<std::size_t>(n));
  // Positions from..to changed; the prefix sums change there and at to + 1 (its link in),
  // and beyond by a constant each: the sums of the links from to + 1 on are as they were.
  const int last = std::min(n - 1, to + 1);
  const std::array<double, 3> old = last >= 0 && last < n && to + 1 < n
                                        ? std::array<double, 3>{fwd_[last], bwd_[last], rev_[last]}
                                        : std::array<double, 3>{0.0, 0.0, 0.0};
  for (int x = from; x <= last; ++x) {
    pos_[t_[x].course] = x;
    if (x == 0) {
      fwd_[0] = bwd_[0] = rev_[0] = 0.0;
      continue;
    }
    fwd_[x] = fwd_[x - 1] + E(t_[x - 1], t_[x]);
    bwd_[x] = bwd_[x - 1] + E(t_[x], t_[x - 1]);
    if (p_.bidirectional) rev_[x] = rev_[x - 1] + E(Flip(t_[x]), Flip(t_[x - 1]));
  }
  if (last + 1 >= n || to + 1 >= n) return;
  const double df = fwd_[last] - old[0], db = bwd_[last] - old[1], dr = rev_[last] - old[2];
  for (int x = last + 1; x < n; ++x) {
    fwd_[x] += df;
    bwd_[x] += db;
    rev_[x] += dr;
  }
}

}  // namespace stitchsim::planner::detail
