// Dominance (issue 28, Done-when 2): every forward-only order is also a bidirectional one, so
// the bidirectional search must never return a dearer order than the forward-only search on the
// same problem. Checked on every TSPLIB bench instance (bench/data/tsplib/, as TsplibProblem:
// reversed courses cost the same as forward ones) and on generated plates whose reversed
// courses do differ. Only costs are compared: nothing assumes how the solver achieves it.

#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>

#include "stitchsim/planner/sequence/solver.h"
#include "stitchsim/planner/sequence/tsplib.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
const fs::path kDominanceTsplibDir = fs::path(STITCHSIM_SOURCE_DIR) / "bench" / "data" / "tsplib";

/// Solves p forward-only and bidirectional; the bidirectional answer must cost no more.
void ExpectBidirectionalNoWorse(SequenceProblem p, const std::string& what, double optimum = 0.0) {
  LocalSearchOptions budget;  // small and deterministic (rounds, not seconds): a fast test
  budget.max_rounds = 100;
  budget.stagnation = 50;
  budget.starts = 1;
  p.bidirectional = false;
  const SequenceSolution forward = SolveLocalSearch(p, budget);
  p.bidirectional = true;
  const SequenceSolution both = SolveLocalSearch(p, budget);
  // Each answer priced again by PathCost, not taken from the solver.
  p.bidirectional = false;
  const double forward_cost = PathCost(p, forward.order);
  p.bidirectional = true;
  const double both_cost = PathCost(p, both.order);
  EXPECT_EQ(forward_cost, forward.cost) << what;
  EXPECT_EQ(both_cost, both.cost) << what;
  for (const Visit& v : forward.order) ASSERT_FALSE(v.reversed) << what;
  // No order beats the published optimum: a cost below it would mean a misread instance.
  EXPECT_GE(forward_cost, optimum) << what;
  EXPECT_GE(both_cost, optimum) << what;
  EXPECT_LE(both_cost, forward_cost * (1 + 1e-12))
      << what << ": bidirectional " << both_cost << " against forward-only " << forward_cost;
}

TEST(SequenceDominance, BidirectionalNeverWorseOnTsplibInstances) {
  DiagnosticSink sink;
  const auto optima = ReadTsplibOptima((kDominanceTsplibDir / "optima.txt").string(), sink);
  ASSERT_TRUE(optima.has_value());
  ASSERT_FALSE(optima->empty());
  for (const TsplibOptimum& o : *optima) {
    const auto in = ReadTsplib(
        (kDominanceTsplibDir / (o.name + (o.symmetric ? ".tsp" : ".atsp"))).string(), sink);
    ASSERT_TRUE(in.has_value()) << o.name;
    ExpectBidirectionalNoWorse(TsplibProblem(*in, false), o.name, o.optimum);
  }
}

// Courses of a plate in bands (as bench/sequence_solver_bench.cpp), laid in x or -x: reversing
// one moves its start to the other end, so bidirectional lay-up changes the costs.
SequenceProblem DominancePlate(int courses, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-5.0, 5.0), len(100.0, 400.0);
  SequenceProblem p;
  p.dim = 2;
  p.norm = CostNorm::kL2;
  p.weights = {1, 1};
  p.start = {-100, -100};
  p.finish = p.start;
  for (int c = 0; c < courses; ++c) {
    const double x0 = (c % 4) * 500.0 + jitter(rng), x1 = x0 + len(rng);
    const double y = (c / 4) * 20.0 + jitter(rng);
    for (const double v : {x0, y, x1, y, x1, y, x0, y}) p.points.push_back(v);
  }
  p.courses = courses;
  return p;
}

TEST(SequenceDominance, BidirectionalNeverWorseOnPlates) {
  for (const int courses : {12, 40, 150})
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
      ExpectBidirectionalNoWorse(
          DominancePlate(courses, seed),
          std::to_string(courses) + " courses, seed " + std::to_string(seed));
}

}  // namespace
}  // namespace stitchsim::planner
