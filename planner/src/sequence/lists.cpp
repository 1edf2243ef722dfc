// The local search's construction and candidate lists (lists.h).
#include "lists.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
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

}  // namespace stitchsim::planner::detail
