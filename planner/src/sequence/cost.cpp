// Costs of the course-ordering problem (seed 004, eq. 3.4 and its time / tool variants), and
// PathCost, the one definition of an order's cost that every solver reports.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "detail.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner {

const char* ToString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kOptimal:
      return "optimal";
    case SolveStatus::kRoundCap:
      return "round-cap";
    case SolveStatus::kTimeLimit:
      return "time-limit";
    case SolveStatus::kGiven:
      return "given";
    case SolveStatus::kStagnation:
      return "stagnation";
  }
  return "?";
}

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
  if (order.empty()) return detail::StartToFinish(p);
  double cost = detail::FromStart(p, order.front());
  for (std::size_t i = 1; i < order.size(); ++i) cost += detail::Edge(p, order[i - 1], order[i]);
  return cost + detail::ToFinish(p, order.back());
}

}  // namespace stitchsim::planner
