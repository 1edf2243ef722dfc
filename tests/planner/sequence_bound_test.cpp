// The lower bound on an order's cost (issue 28, ComputeLowerBound): a closed form (courses of
// no length on a regular polygon: the optimum is its perimeter), hand-computed trivial cases,
// and on generated small sets the chain bound <= the exact optimum <= the local search's cost,
// with the bound close to the optimum (its mean and worst ratio printed, a floor asserted).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "stitchsim/common/units.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner {
namespace {

// Adds a course whose four points (forward start, end; backward start, end) are given (2-D).
void AddCourse2d(SequenceProblem& p, double fx0, double fy0, double fx1, double fy1, double bx0,
                 double by0, double bx1, double by1) {
  for (const double c : {fx0, fy0, fx1, fy1, bx0, by0, bx1, by1}) p.points.push_back(c);
  ++p.courses;
}

SequenceProblem Plane(CostNorm norm, bool bidirectional) {
  SequenceProblem p;
  p.dim = 2;
  p.weights = {1.0, 1.0};
  p.norm = norm;
  p.bidirectional = bidirectional;
  return p;
}

// k vertices of a regular polygon of radius r; start and finish at vertex 0, a course of no
// length at each other one: every order is a tour of the polygon, the best one its perimeter.
TEST(SequenceBound, RegularPolygonMeetsThePerimeter) {
  for (const int k : {5, 12, 40, 101}) {
    for (const bool bidirectional : {false, true}) {
      const double r = 250.0;
      SequenceProblem p = Plane(CostNorm::kL2, bidirectional);
      for (int i = 1; i < k; ++i) {
        const double x = r * std::cos(2 * kPi * i / k), y = r * std::sin(2 * kPi * i / k);
        AddCourse2d(p, x, y, x, y, x, y, x, y);
      }
      p.start = {r, 0.0};
      p.finish = p.start;
      const double perimeter = 2.0 * k * r * std::sin(kPi / k);
      const LowerBound b = ComputeLowerBound(p);
      EXPECT_EQ(b.method, "held-karp");
      EXPECT_NEAR(b.value, perimeter, 1e-6 * perimeter) << "k " << k;
      EXPECT_LE(b.value, perimeter) << "k " << k;
    }
  }
}

// Hand-computed: no course (start to finish), one course (its cheaper direction), and three
// courses on a line with the start between them, whose best order is found by hand.
TEST(SequenceBound, HandComputedLineAndTrivialSizes) {
  SequenceProblem p = Plane(CostNorm::kL1, false);
  p.start = {0.0, 0.0};
  EXPECT_EQ(ComputeLowerBound(p).value, 0.0);  // no course, no finish
  p.finish = std::vector<double>{3.0, 4.0};
  EXPECT_EQ(ComputeLowerBound(p).value, 7.0);  // start straight home (L1)
  EXPECT_EQ(ComputeLowerBound(p).method, "trivial");
  // One course from (10, 0) to (20, 0); backwards from (20, 1) to (10, 2).
  AddCourse2d(p, 10, 0, 20, 0, 20, 1, 10, 2);
  EXPECT_EQ(ComputeLowerBound(p).value, 10.0 + 17.0 + 4.0);  // forwards only
  p.bidirectional = true;
  EXPECT_EQ(ComputeLowerBound(p).value, 21.0 + 7.0 + 2.0);  // backwards is cheaper
  EXPECT_EQ(ComputeLowerBound(p).method, "exact");
  // Courses along y = 0 of length 10 from x = 10, 30, -30, start at 0, no finish, forward:
  // 10, 30, -30 costs 10 + 10 + 70 = 90; -30, 10, 30 costs 30 + 30 + 10 = 70, the optimum.
  SequenceProblem q = Plane(CostNorm::kL1, false);
  q.start = {0.0, 0.0};
  for (const double x : {10.0, 30.0, -30.0}) AddCourse2d(q, x, 0, x + 10, 0, x + 10, 0, x, 0);
  const auto exact = SolveExact(q);
  ASSERT_TRUE(exact.has_value());
  EXPECT_DOUBLE_EQ(exact->cost, 70.0);
  const LowerBound b = ComputeLowerBound(q);
  EXPECT_LE(b.value, 70.0);
  EXPECT_GE(b.value, 0.95 * 70.0);
}

// ---- Generated sets. ----
struct BoundGen {
  std::mt19937_64 rng;
  double U(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

  // Courses as short segments in a 600 x 400 field; laid backwards from a point near the
  // forward end to one near the forward start (the head turned round lands a little off).
  SequenceProblem Segments(int n, CostNorm norm, bool bidirectional, bool finish) {
    SequenceProblem p = Plane(norm, bidirectional);
    p.weights = {1.0, U(0.5, 2.0)};
    for (int i = 0; i < n; ++i) {
      const double x = U(0, 600), y = U(0, 400), a = U(0, 2 * kPi), len = U(0, 120);
      const double ex = x + len * std::cos(a), ey = y + len * std::sin(a);
      AddCourse2d(p, x, y, ex, ey, ex + U(-8, 8), ey + U(-8, 8), x + U(-8, 8), y + U(-8, 8));
    }
    p.start = {U(0, 600), U(0, 400)};
    if (finish) p.finish = std::vector<double>{U(0, 600), U(0, 400)};
    return p;
  }
  // Random asymmetric costs between visits (no triangle inequality).
  SequenceProblem Table(int n, bool bidirectional, bool finish) {
    SequenceProblem p;
    p.courses = n;
    p.bidirectional = bidirectional;
    auto t = std::make_shared<MoveTable>();
    const std::size_t m = 2 * static_cast<std::size_t>(n);
    for (std::size_t i = 0; i < m * m; ++i) t->move.push_back(U(1, 100));
    for (std::size_t i = 0; i < m; ++i) t->from_start.push_back(U(1, 100));
    if (finish) {
      for (std::size_t i = 0; i < m; ++i) t->to_finish.push_back(U(1, 100));
      t->start_to_finish = U(1, 100);
      p.finish = std::vector<double>{};
    }
    p.table = t;
    return p;
  }
};

struct Ratios {
  double sum = 0.0, worst = 1.0;
  int count = 0;
  void Add(double r) {
    sum += r;
    worst = std::min(worst, r);
    ++count;
  }
  double Mean() const { return count > 0 ? sum / count : 1.0; }
};

TEST(SequenceBound, BelowTheOptimumBelowTheHeuristicOnGeneratedSets) {
  BoundGen g{std::mt19937_64(28)};
  constexpr CostNorm kBoundNorms[] = {CostNorm::kL1, CostNorm::kMax, CostNorm::kL2};
  Ratios norm_forward, norm_bidirectional, table_forward, table_bidirectional;
  int instances = 0;
  for (int rep = 0; rep < 10; ++rep) {
    for (int mode = 0; mode < 4; ++mode) {
      const bool bidirectional = (mode & 1) != 0, finish = (mode & 2) != 0;
      for (int kind = 0; kind < 4; ++kind) {
        const int n = 6 + static_cast<int>(g.rng() % 9);  // 6..14
        const SequenceProblem p = kind < 3 ? g.Segments(n, kBoundNorms[kind], bidirectional, finish)
                                           : g.Table(n, bidirectional, finish);
        const auto exact = SolveExact(p);
        ASSERT_TRUE(exact.has_value());
        LocalSearchOptions lo;
        lo.max_rounds = 200;
        const SequenceSolution local = SolveLocalSearch(p, lo);
        const LowerBound b = ComputeLowerBound(p);
        const double tol = 1e-9 * (1.0 + exact->cost);
        EXPECT_LE(b.value, exact->cost + tol)
            << "instance " << instances << " mode " << mode << " kind " << kind << " n " << n;
        EXPECT_LE(exact->cost, local.cost + tol) << "instance " << instances;
        EXPECT_EQ(b.method, "held-karp");
        EXPECT_EQ(ComputeLowerBound(p).value, b.value) << "deterministic";
        const double ratio = b.value / exact->cost;
        (kind < 3 ? (bidirectional ? norm_bidirectional : norm_forward)
                  : (bidirectional ? table_bidirectional : table_forward))
            .Add(ratio);
        ++instances;
      }
    }
  }
  EXPECT_EQ(instances, 160);
  std::printf(
      "bound / optimum over %d sets (mean, worst): norms forward %.4f %.4f, bidirectional "
      "%.4f %.4f; tables forward %.4f %.4f, bidirectional %.4f %.4f\n",
      instances, norm_forward.Mean(), norm_forward.worst, norm_bidirectional.Mean(),
      norm_bidirectional.worst, table_forward.Mean(), table_forward.worst,
      table_bidirectional.Mean(), table_bidirectional.worst);
  EXPECT_GE(norm_forward.Mean(), 0.9);
  EXPECT_GE(norm_bidirectional.Mean(), 0.85);
  EXPECT_GE(table_forward.Mean(), 0.85);
  EXPECT_GE(table_bidirectional.Mean(), 0.6);
}

// A larger set: the bound stays below the local search's answer and close to it, within the
// work cap, and the same twice.
TEST(SequenceBound, LargerSetBelowLocalSearch) {
  BoundGen g{std::mt19937_64(5)};
  for (const bool bidirectional : {false, true}) {
    const SequenceProblem p = g.Segments(200, CostNorm::kL2, bidirectional, true);
    const LowerBound b = ComputeLowerBound(p);
    LocalSearchOptions two;  // an order to compare with: 2 starts (the default runs 8 here)
    two.starts = 2;
    const SequenceSolution local = SolveLocalSearch(p, two);
    EXPECT_LE(b.value, local.cost);
    EXPECT_GE(b.value, (bidirectional ? 0.7 : 0.9) * local.cost);
    std::printf("200 courses%s: bound %.2f, local %.2f (%.3f), %lld trees, %.3f s\n",
                bidirectional ? " bidirectional" : "", b.value, local.cost, b.value / local.cost,
                static_cast<long long>(b.iterations), b.seconds);
    BoundOptions few;
    few.max_work = 1;  // one 1-tree at least, whatever the cap
    const LowerBound one = ComputeLowerBound(p, few);
    EXPECT_EQ(one.iterations, 1);
    EXPECT_LE(one.value, b.value);
  }
}

}  // namespace
}  // namespace stitchsim::planner
