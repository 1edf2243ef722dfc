// Costs of the course-ordering problem (seed 004, eq. 3.4 and its time / tool variants), and
// the nearest-course lists the heuristics search over.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "sequence_detail.h"
#include "stitchsim/planner/sequence_solver.h"

namespace stitchsim::planner {

double MoveCost(const SequenceProblem& p, const double* from, const double* to) {
  double acc = 0.0;
  switch (p.norm) {
    case CostNorm::kL1:
      for (int i = 0; i < p.dim; ++i) acc += std::abs(p.weights[i] * (to[i] - from[i]));
      return acc;
    case CostNorm::kMax:
      for (int i = 0; i < p.dim; ++i)
        acc = std::max(acc, std::abs(p.weights[i] * (to[i] - from[i])));
      return acc;
    case CostNorm::kL2:
      for (int i = 0; i < p.dim; ++i) {
        const double d = p.weights[i] * (to[i] - from[i]);
        acc += d * d;
      }
      return std::sqrt(acc);
  }
  return acc;
}

double PathCost(const SequenceProblem& p, const std::vector<Visit>& order) {
  detail::AssertWellFormed(p);
  if (order.empty()) return p.finish ? MoveCost(p, p.start.data(), p.finish->data()) : 0.0;
  double cost = detail::FromStart(p, order.front());
  for (std::size_t i = 1; i < order.size(); ++i) cost += detail::Edge(p, order[i - 1], order[i]);
  return cost + detail::ToFinish(p, order.back());
}

namespace detail {

std::vector<std::vector<int>> NearestCourses(const SequenceProblem& p, int k) {
  const int n = p.courses;
  const int dirs = p.bidirectional ? 2 : 1;
  k = std::clamp(k, 0, std::max(0, n - 1));
  std::vector<std::vector<int>> out(static_cast<std::size_t>(n));
  std::vector<std::pair<double, int>> row(static_cast<std::size_t>(n));
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      double best = std::numeric_limits<double>::infinity();
      if (b == a) {
        row[b] = {best, b};
        continue;
      }
      for (int ra = 0; ra < dirs; ++ra) {
        for (int rb = 0; rb < dirs; ++rb) {
          const Visit va{a, ra == 1}, vb{b, rb == 1};
          best = std::min({best, Edge(p, va, vb), Edge(p, vb, va)});
        }
      }
      row[b] = {best, b};
    }
    std::partial_sort(row.begin(), row.begin() + k, row.end());
    auto& list = out[static_cast<std::size_t>(a)];
    for (int i = 0; i < k; ++i) list.push_back(row[i].second);
  }
  return out;
}

}  // namespace detail
}  // namespace stitchsim::planner
