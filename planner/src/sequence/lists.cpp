// The local search's construction and candidate lists (lists.h).
#include "lists.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "detail.h"

namespace stitchsim::planner::detail {

std::vector<Visit> NearestNeighbourTour(const SequenceProblem& p) {
  std::vector<Visit> order;
  std::vector<char> used(static_cast<std::size_t>(p.courses), 0);
  const int dirs = p.bidirectional ? 2 : 1;
  std::vector<int> left;  // courses not yet laid, per group
  for (int c = 0; c < p.courses; ++c) {
    const int g = GroupOf(p, c);
    if (g >= static_cast<int>(left.size())) left.resize(static_cast<std::size_t>(g) + 1, 0);
    ++left[static_cast<std::size_t>(g)];
  }
  std::size_t group = 0;
  for (int step = 0; step < p.courses; ++step) {
    while (left[group] == 0) ++group;
    Visit best{};
    double best_cost = std::numeric_limits<double>::infinity();
    for (int c = 0; c < p.courses; ++c) {
      if (used[c] || GroupOf(p, c) != static_cast<int>(group)) continue;
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
    --left[group];
    order.push_back(best);
  }
  return order;
}

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
      if (a / 2 == b / 2 || std::abs(GroupOf(p, a / 2) - GroupOf(p, b / 2)) > 1) continue;
      const Visit vb = detail::NodeVisit(b);
      into.push_back({tour.Move(vb, va), b});
      from.push_back({tour.Move(va, vb), b});
    }
    const std::size_t kk =
        std::min<std::size_t>(static_cast<std::size_t>(std::max(0, k)), into.size());
    for (auto* row : {&into, &from}) {
      std::partial_sort(row->begin(), row->begin() + static_cast<std::ptrdiff_t>(kk), row->end());
      auto& list = row == &into ? lists.in[a] : lists.out[a];
      for (std::size_t i = 0; i < kk; ++i) list.push_back({(*row)[i].second, (*row)[i].first});
    }
  }
  return lists;
}

namespace {

/// Chains of courses for GreedyTour. Per course its neighbours and direction as stored, per
/// chain a turned flag (read the other way round, every course flipped): turning is O(1), and a
/// join re-stores only the smaller chain, O(n log n) over all joins.
class Chains {
 public:
  explicit Chains(int n)
      : chain_(static_cast<std::size_t>(n)),
        next_(static_cast<std::size_t>(n), -1),
        prev_(static_cast<std::size_t>(n), -1),
        head_(static_cast<std::size_t>(n)),
        tail_(static_cast<std::size_t>(n)),
        rev_(static_cast<std::size_t>(n), 0),
        turned_(static_cast<std::size_t>(n), 0),
        members_(static_cast<std::size_t>(n)) {
    for (int c = 0; c < n; ++c) {
      chain_[c] = head_[c] = tail_[c] = c;
      members_[c] = {c};
    }
  }
  int ChainOf(int c) const { return chain_[c]; }
  /// The chain's first and last course, a course's direction and the next course, as read.
  int Head(int f) const { return turned_[f] ? tail_[f] : head_[f]; }
  int Tail(int f) const { return turned_[f] ? head_[f] : tail_[f]; }
  bool Reversed(int c) const { return (rev_[c] != 0) != (turned_[chain_[c]] != 0); }
  int Next(int c) const { return turned_[chain_[c]] ? prev_[c] : next_[c]; }
  void Turn(int f) { turned_[f] ^= 1; }
  void SetReversed(int c, bool r) { rev_[c] = r != (turned_[chain_[c]] != 0) ? 1 : 0; }
  /// Chain b read after chain a.
  void Join(int a, int b) {
    const int keep = members_[a].size() >= members_[b].size() ? a : b, gone = a + b - keep;
    if (turned_[gone] != turned_[keep]) {  // store the smaller chain as the larger reads
      for (int c : members_[gone]) {
        std::swap(next_[c], prev_[c]);
        rev_[c] ^= 1;
      }
      std::swap(head_[gone], tail_[gone]);
      turned_[gone] ^= 1;
    }
    int head = 0, tail = 0;
    if (turned_[keep] == 0) {
      next_[tail_[a]] = head_[b];
      prev_[head_[b]] = tail_[a];
      head = head_[a];
      tail = tail_[b];
    } else {  // stored: b's courses, then a's
      next_[tail_[b]] = head_[a];
      prev_[head_[a]] = tail_[b];
      head = head_[b];
      tail = tail_[a];
    }
    for (int c : members_[gone]) chain_[c] = keep;
    members_[keep].insert(members_[keep].end(), members_[gone].begin(), members_[gone].end());
    members_[gone].clear();
    members_[gone].shrink_to_fit();
    head_[keep] = head;
    tail_[keep] = tail;
  }

 private:
  std::vector<int> chain_, next_, prev_, head_, tail_;
  std::vector<char> rev_, turned_;
  std::vector<std::vector<int>> members_;
};

/// How a chain end can take an arc: it is not laid yet (`laid` false), it ends (or starts)
/// the chain laid as the arc needs, or (bidirectional) the chain turned round does.
enum class Fit { kNo, kFree, kAsIs, kTurned };

}  // namespace

std::vector<Visit> GreedyTour(const SequenceProblem& p, const NodeLists& lists) {
  const int n = p.courses;
  struct Arc {
    double cost;
    int from, to;  // nodes
  };
  std::vector<Arc> arcs;
  for (int a = 0; a < 2 * n; ++a) {
    for (const Candidate& c : lists.out[a]) arcs.push_back({c.cost, a, c.node});
  }
  std::sort(arcs.begin(), arcs.end(), [](const Arc& x, const Arc& y) {
    return x.cost != y.cost ? x.cost < y.cost : x.from != y.from ? x.from < y.from : x.to < y.to;
  });
  Chains chains(n);
  std::vector<char> laid(static_cast<std::size_t>(n), 0);  // direction fixed (joined)
  // Whether visit v can be the last (last = true) or first course of its chain.
  const auto fit = [&](Visit v, bool last) {
    const int f = chains.ChainOf(v.course);
    if (!laid[v.course]) return Fit::kFree;
    const int end = last ? chains.Tail(f) : chains.Head(f);
    const int other = last ? chains.Head(f) : chains.Tail(f);
    if (end == v.course && chains.Reversed(v.course) == v.reversed) return Fit::kAsIs;
    if (p.bidirectional && other == v.course && chains.Reversed(v.course) != v.reversed)
      return Fit::kTurned;
    return Fit::kNo;
  };
  for (const Arc& arc : arcs) {
    const Visit a = NodeVisit(arc.from), b = NodeVisit(arc.to);
    const int fa = chains.ChainOf(a.course), fb = chains.ChainOf(b.course);
    if (fa == fb) continue;
    const Fit ka = fit(a, true), kb = fit(b, false);
    if (ka == Fit::kNo || kb == Fit::kNo) continue;
    for (const auto& [v, f, k] : {std::tuple{a, fa, ka}, std::tuple{b, fb, kb}}) {
      if (k == Fit::kTurned) chains.Turn(f);
      if (k == Fit::kFree) chains.SetReversed(v.course, v.reversed);
      laid[v.course] = 1;
    }
    chains.Join(fa, fb);
  }
  // The chains from p.start, the cheapest first visit next (a single course not laid yet:
  // either way when bidirectional).
  std::vector<int> todo;
  for (int c = 0; c < n; ++c) {
    if (chains.ChainOf(c) == c) todo.push_back(c);
  }
  std::vector<Visit> order;
  order.reserve(static_cast<std::size_t>(n));
  while (!todo.empty()) {
    std::size_t best = 0;
    bool best_turn = false;
    double best_cost = kInf;
    for (std::size_t i = 0; i < todo.size(); ++i) {
      const int f = todo[i];
      for (int turn = 0; turn < (p.bidirectional ? 2 : 1); ++turn) {
        const int h = turn == 0 ? chains.Head(f) : chains.Tail(f);
        const Visit v{h, laid[h] ? chains.Reversed(h) != (turn == 1) : turn == 1};
        const double cost = order.empty() ? FromStart(p, v) : Edge(p, order.back(), v);
        if (cost < best_cost) {
          best_cost = cost;
          best = i;
          best_turn = turn == 1;
        }
      }
    }
    const int f = todo[best];
    todo.erase(todo.begin() + static_cast<std::ptrdiff_t>(best));
    if (!laid[chains.Head(f)]) {
      order.push_back({f, best_turn});
      continue;
    }
    if (best_turn) chains.Turn(f);
    for (int c = chains.Head(f); c >= 0; c = chains.Next(c))
      order.push_back({c, chains.Reversed(c)});
  }
  return order;
}

}  // namespace stitchsim::planner::detail
