// Exact ordering of a small precedence set: Held-Karp dynamic programming over (set of
// courses laid, last course, its direction). For n courses it keeps 2^n * 2n costs (doubles)
// and as many one-byte back-pointers: at n = kMaxExactCourses = 16, 16 MiB + 2 MiB, and
// 2^n * (2n)^2 = 67 M transitions (well under a second in a Release build). Ties are broken
// by the lower node index (2 course + reversed), so the answer is deterministic.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>

#include "detail.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner {

namespace {

using detail::kInf;

constexpr std::uint8_t kNoParent = 0xFF;

/// Off-part cost between every pair of nodes (2 course + reversed), row = from.
std::vector<double> NodeCosts(const SequenceProblem& p) {
  const int m = 2 * p.courses;
  std::vector<double> c(static_cast<std::size_t>(m) * m, kInf);
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      if (a / 2 != b / 2)
        c[a * m + b] = detail::Edge(p, detail::NodeVisit(a), detail::NodeVisit(b));
    }
  }
  return c;
}

}  // namespace

std::optional<SequenceSolution> SolveExact(const SequenceProblem& p) {
  SequenceSolution s = detail::BeginSolution(p, "exact", SolveStatus::kOptimal);
  if (p.courses > kMaxExactCourses) return std::nullopt;
  const auto t0 = std::chrono::steady_clock::now();
  const int n = p.courses;
  const int m = 2 * n;
  const int dir_step = p.bidirectional ? 1 : 2;  // unidirectional: even nodes only
  if (n > 0) {
    const std::vector<double> edge = NodeCosts(p);
    const std::size_t masks = std::size_t{1} << n;
    std::vector<double> dp(masks * m, kInf);
    std::vector<std::uint8_t> parent(masks * m, kNoParent);
    for (int u = 0; u < m; u += dir_step) {
      dp[(std::size_t{1} << (u / 2)) * m + u] = detail::FromStart(p, detail::NodeVisit(u));
    }
    for (std::size_t mask = 1; mask < masks; ++mask) {
      for (int u = 0; u < m; u += dir_step) {
        const double here = dp[mask * m + u];
        if (here == kInf) continue;
        for (int v = 0; v < m; v += dir_step) {
          if (mask & (std::size_t{1} << (v / 2))) continue;
          const std::size_t next = (mask | (std::size_t{1} << (v / 2))) * m + v;
          const double cand = here + edge[u * m + v];
          if (cand < dp[next]) {
            dp[next] = cand;
            parent[next] = static_cast<std::uint8_t>(u);
          }
          ++s.iterations;
        }
      }
    }
    const std::size_t full = masks - 1;
    int last = -1;
    double best = kInf;
    for (int u = 0; u < m; u += dir_step) {
      const double total = dp[full * m + u] + detail::ToFinish(p, detail::NodeVisit(u));
      if (total < best) {
        best = total;
        last = u;
      }
    }
    std::size_t mask = full;
    for (int u = last; u != kNoParent;) {
      s.order.push_back(detail::NodeVisit(u));
      const int prev = parent[mask * m + u];
      mask &= ~(std::size_t{1} << (u / 2));
      u = prev;
    }
    std::reverse(s.order.begin(), s.order.end());
  }
  s.cost = PathCost(p, s.order);
  s.seconds = detail::SecondsSince(t0);
  return s;
}

}  // namespace stitchsim::planner
