// The course-ordering solvers (issue 13, S9; seed 004 section 3.2): the exact solver agrees
// with brute force priced by an independent cost routine; our local search is within 1 % of
// the exact optimum on generated AFP-like sets (Done-when 2) and the seed's method never
// beats it; outputs are deterministic, visit every course once, and respect unidirectional
// lay-up; hand-computable cases.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <set>

#include "stitchsim/common/units.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner {
namespace {

// ---- An independent pricing of an order, straight from the problem's definition. ----
double Norm(const SequenceProblem& p, const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> d(static_cast<std::size_t>(p.dim));
  for (int i = 0; i < p.dim; ++i) d[i] = std::fabs(p.weights[i] * (b[i] - a[i]));
  if (p.norm == CostNorm::kL1) return std::accumulate(d.begin(), d.end(), 0.0);
  if (p.norm == CostNorm::kMax) return *std::max_element(d.begin(), d.end());
  return std::sqrt(std::inner_product(d.begin(), d.end(), d.begin(), 0.0));
}
std::vector<double> Point(const SequenceProblem& p, int course, int k) {
  const auto first = p.points.begin() + (4 * course + k) * p.dim;
  return {first, first + p.dim};
}
double IndependentCost(const SequenceProblem& p, const std::vector<Visit>& order) {
  std::vector<double> here = p.start;
  double cost = 0.0;
  for (const Visit& v : order) {
    cost += Norm(p, here, Point(p, v.course, v.reversed ? 2 : 0));
    here = Point(p, v.course, v.reversed ? 3 : 1);
  }
  if (p.finish) cost += Norm(p, here, *p.finish);
  return cost;
}

// All permutations times all direction choices.
double BruteForce(const SequenceProblem& p) {
  std::vector<int> perm(static_cast<std::size_t>(p.courses));
  std::iota(perm.begin(), perm.end(), 0);
  const int flips = p.bidirectional ? 1 << p.courses : 1;
  double best = INFINITY;
  do {
    for (int f = 0; f < flips; ++f) {
      std::vector<Visit> order;
      for (int i = 0; i < p.courses; ++i) order.push_back({perm[i], ((f >> i) & 1) != 0});
      best = std::min(best, IndependentCost(p, order));
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

// ---- Generated sets: plausible AFP geometry in 8 "axis" dimensions. ----
// Axes: x, y, z (mm), three head angles (rad), rail (mm), rotator (rad). A course's reversed
// points are its forward points swapped, with the head turned (angle + pi) and slightly
// different approach and retract offsets, so moves are not symmetric.
struct Gen {
  std::mt19937_64 rng;
  double U(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

  static void Add(SequenceProblem& p, const std::vector<double>& a, const std::vector<double>& b,
                  double lift) {
    std::vector<double> ra = b, rb = a;
    ra[3] += kPi;
    rb[3] += kPi;
    ra[2] += lift;
    for (const auto& q : {a, b, ra, rb}) p.points.insert(p.points.end(), q.begin(), q.end());
    ++p.courses;
  }
  // Parallel courses on a plate, at an angle, in a random (bad) order.
  void Plate(SequenceProblem& p, int n) {
    const double ang = U(0, kPi), len = U(300, 900), pitch = U(20, 60);
    std::vector<int> slot(static_cast<std::size_t>(n));
    std::iota(slot.begin(), slot.end(), 0);
    std::shuffle(slot.begin(), slot.end(), rng);
    for (int i = 0; i < n; ++i) {
      const double off = slot[i] * pitch + U(-2, 2), l0 = U(-20, 20), l1 = len + U(-50, 50);
      const double ux = std::cos(ang), uy = std::sin(ang);
      const double x0 = l0 * ux - off * uy, y0 = l0 * uy + off * ux;
      const double x1 = l1 * ux - off * uy, y1 = l1 * uy + off * ux;
      const double rail = 0.3 * x0;
      Add(p, {x0, y0, 0, ang, 0.1, 0, rail, 0}, {x1, y1, 0, ang, 0.1, 0, rail + 0.3 * (x1 - x0), 0},
          U(0, 10));
    }
  }
  // Courses along the axis of a cylinder, each at its rotator angle.
  void Cylinder(SequenceProblem& p, int n) {
    const double r = U(150, 500), len = U(400, 1200);
    for (int i = 0; i < n; ++i) {
      const double th = U(0, 2 * kPi), x0 = U(0, 50), x1 = len - U(0, 50);
      Add(p, {x0, 0, r, 0, 0.2, 0, x0, th}, {x1, 0, r, 0, 0.2, 0, x1, th}, U(0, 10));
    }
  }
  // Random 8-D points, all four of a course independent.
  void Random(SequenceProblem& p, int n) {
    for (int i = 0; i < 4 * n * 8; ++i) p.points.push_back(U(-100, 100));
    p.courses = n;
  }
  SequenceProblem Make(int kind, int n, CostNorm norm, bool bidirectional, bool finish) {
    SequenceProblem p;
    p.dim = 8;
    p.norm = norm;
    p.bidirectional = bidirectional;
    if (kind == 0) Plate(p, n);
    if (kind == 1) Cylinder(p, n);
    if (kind == 2) Random(p, n);
    for (int i = 0; i < 8; ++i)
      p.weights.push_back(kind == 2 ? U(0.2, 3) : (i < 3 || i == 6 ? 1.0 : 100.0));
    for (int i = 0; i < 8; ++i) p.start.push_back(U(-200, 200));
    if (finish) p.finish = p.start;
    return p;
  }
};

constexpr CostNorm kNorms[] = {CostNorm::kL1, CostNorm::kMax, CostNorm::kL2};

void ExpectValid(const SequenceProblem& p, const SequenceSolution& s) {
  ASSERT_EQ(static_cast<int>(s.order.size()), p.courses) << s.solver;
  std::set<int> seen;
  for (const Visit& v : s.order) {
    EXPECT_TRUE(seen.insert(v.course).second)
        << s.solver << " visits course " << v.course << " twice";
    if (!p.bidirectional) {
      EXPECT_FALSE(v.reversed) << s.solver << " reversed a course";
    }
  }
  EXPECT_NEAR(s.cost, IndependentCost(p, s.order), 1e-9 * (1 + s.cost)) << s.solver;
}

TEST(SequenceSolver, ExactAgreesWithBruteForce) {
  Gen g{std::mt19937_64(11)};
  int cases = 0;
  for (int n = 1; n <= 6; ++n) {
    for (CostNorm norm : kNorms) {
      for (int mode = 0; mode < 4; ++mode) {
        const SequenceProblem p = g.Make(n % 3, n, norm, (mode & 1) != 0, (mode & 2) != 0);
        const auto exact = SolveExact(p);
        ASSERT_TRUE(exact.has_value());
        ExpectValid(p, *exact);
        EXPECT_NEAR(exact->cost, BruteForce(p), 1e-9 * (1 + exact->cost))
            << "n " << n << " mode " << mode;
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 72);
}

// A budget well below the default (1,500 rounds without improvement end a start): the tests
// stay fast, and the default only searches longer from the same start.
LocalSearchOptions Quick() {
  LocalSearchOptions o;
  o.stagnation = 150;
  return o;
}

TEST(SequenceSolver, LocalSearchWithinOnePercentOfExactOnGeneratedSets) {
  Gen g{std::mt19937_64(2026)};
  double worst_local = 0, worst_seed = 0;
  int instances = 0;
  for (int rep = 0; rep < 5; ++rep) {
    for (int kind = 0; kind < 3; ++kind) {
      for (int mode = 0; mode < 4; ++mode) {
        for (CostNorm norm : kNorms) {
          const int n = 6 + static_cast<int>(g.rng() % 9);  // 6..14
          const SequenceProblem p = g.Make(kind, n, norm, (mode & 1) != 0, (mode & 2) != 0);
          const auto exact = SolveExact(p);
          ASSERT_TRUE(exact.has_value());
          LocalSearchOptions budget;
          // 2 starts of 400 rounds, well below the default (8 starts of 5,000 rounds at this
          // size): the default only searches longer.
          budget.stagnation = 400;
          budget.starts = 2;
          const SequenceSolution local = SolveLocalSearch(p, budget);
          const SequenceSolution seed = SolveSeedMethod(p);
          ExpectValid(p, *exact);
          ExpectValid(p, local);
          ExpectValid(p, seed);
          const double tol = 1e-9 * (1 + exact->cost);
          EXPECT_LE(local.cost, exact->cost * 1.01 + tol)
              << "instance " << instances << " kind " << kind << " mode " << mode << " n " << n
              << " norm " << static_cast<int>(norm);
          EXPECT_GE(local.cost, exact->cost - tol) << "instance " << instances;
          EXPECT_GE(seed.cost, exact->cost - tol) << "instance " << instances;
          worst_local = std::max(worst_local, local.cost / exact->cost - 1);
          worst_seed = std::max(worst_seed, seed.cost / exact->cost - 1);
          ++instances;
        }
      }
    }
  }
  EXPECT_GE(instances, 100);
  std::printf("%d instances: worst gap to exact: local search %.3f %%, seed method %.3f %%\n",
              instances, 100 * worst_local, 100 * worst_seed);
}

TEST(SequenceSolver, Deterministic) {
  Gen g{std::mt19937_64(7)};
  for (bool bidirectional : {false, true}) {
    const SequenceProblem p = g.Make(0, 300, CostNorm::kL1, bidirectional, false);
    const SequenceSolution a = SolveLocalSearch(p, Quick()), b = SolveLocalSearch(p, Quick());
    EXPECT_EQ(a.order, b.order);
    EXPECT_EQ(a.cost, b.cost);
    LocalSearchOptions generous = Quick();
    generous.time_limit_s = 1000;
    EXPECT_EQ(SolveLocalSearch(p, generous).order, a.order);
    // The starts run on threads; how many does not change the answer.
    LocalSearchOptions threaded = Quick();
    threaded.starts = 3;
    threaded.jobs = 2;
    LocalSearchOptions serial = threaded;
    serial.jobs = 1;
    EXPECT_EQ(SolveLocalSearch(p, threaded).order, SolveLocalSearch(p, serial).order);
    const SequenceSolution s1 = SolveSeedMethod(p), s2 = SolveSeedMethod(p);
    EXPECT_EQ(s1.order, s2.order);
    ExpectValid(p, a);
    ExpectValid(p, s1);
  }
}

// A time limit cuts only the kicks, between rounds: a limit that has passed before the first
// round gives the descent's own answer, the same as no rounds at all.
TEST(SequenceSolver, TimeLimitCutsWholeRounds) {
  Gen g{std::mt19937_64(8)};
  const SequenceProblem p = g.Make(1, 200, CostNorm::kL1, true, true);
  LocalSearchOptions cut, none;
  cut.time_limit_s = 1e-12;
  none.max_rounds = 0;
  const SequenceSolution a = SolveLocalSearch(p, cut), b = SolveLocalSearch(p, none);
  ExpectValid(p, a);
  EXPECT_EQ(a.order, b.order);
  EXPECT_GE(a.cost, SolveLocalSearch(p, Quick()).cost);
  // The cut says so; the run with no rounds to run finished them all.
  EXPECT_EQ(a.status, SolveStatus::kTimeLimit);
  EXPECT_EQ(b.status, SolveStatus::kRoundCap);
}

// Each solver says how it stopped: the exact one proves its answer, a search that runs all its
// rounds (no limit, or a limit far beyond them) finished, the seed's method ends by its caps.
TEST(SequenceSolver, StatusSaysHowTheSearchStopped) {
  Gen g{std::mt19937_64(9)};
  const SequenceProblem p = g.Make(0, 12, CostNorm::kL1, true, false);
  EXPECT_EQ(SolveExact(p)->status, SolveStatus::kOptimal);
  EXPECT_EQ(SolveSeedMethod(p).status, SolveStatus::kRoundCap);
  LocalSearchOptions generous;
  generous.time_limit_s = 1000;
  generous.max_rounds = 50;
  const SequenceSolution finished = SolveLocalSearch(p, generous);
  EXPECT_EQ(finished.status, SolveStatus::kRoundCap);
  EXPECT_STREQ(ToString(finished.status), "round-cap");
  LocalSearchOptions tiny;
  tiny.time_limit_s = 1e-12;
  const SequenceSolution cut = SolveLocalSearch(p, tiny);
  EXPECT_EQ(cut.status, SolveStatus::kTimeLimit);
  EXPECT_STREQ(ToString(cut.status), "time-limit");
  // The finished search ran its 50 rounds (each counted in iterations); the cut one none.
  EXPECT_GE(finished.iterations, 50);
  EXPECT_LT(cut.iterations, finished.iterations);
}

// Three unit courses on a line (L1, one axis) given in a bad order: [4,5], [0,1], [2,3].
SequenceProblem LineCase(bool bidirectional, double start) {
  SequenceProblem p;
  p.courses = 3;
  p.dim = 1;
  p.weights = {1.0};
  for (double a : {4.0, 0.0, 2.0}) p.points.insert(p.points.end(), {a, a + 1, a + 1, a});
  p.bidirectional = bidirectional;
  p.start = {start};
  return p;
}

TEST(SequenceSolver, HandComputedLine) {
  // From 0, forwards only: 1, 2, 0 costs 0 + 1 + 1 = 2.
  const SequenceProblem uni = LineCase(false, 0.0);
  const std::vector<Visit> uni_best{{1, false}, {2, false}, {0, false}};
  EXPECT_EQ(PathCost(uni, uni_best), 2.0);
  EXPECT_EQ(PathCost(uni, {{0, false}, {1, false}, {2, false}}), 4.0 + 5.0 + 1.0);
  for (const auto& s : {*SolveExact(uni), SolveLocalSearch(uni), SolveSeedMethod(uni)}) {
    EXPECT_EQ(s.order, uni_best) << s.solver;
    EXPECT_EQ(s.cost, 2.0) << s.solver;
  }
  // From 6, both ways: 0, 2, 1 all backwards costs 1 + 1 + 1 = 3.
  const SequenceProblem bi = LineCase(true, 6.0);
  const std::vector<Visit> bi_best{{0, true}, {2, true}, {1, true}};
  for (const auto& s : {*SolveExact(bi), SolveLocalSearch(bi)}) {
    EXPECT_EQ(s.order, bi_best) << s.solver;
    EXPECT_EQ(s.cost, 3.0) << s.solver;
  }
  // A finish at 6 after the forwards order: 2 + |5 - 6| = 3.
  SequenceProblem home = uni;
  home.finish = std::vector<double>{6.0};
  EXPECT_EQ(SolveExact(home)->cost, 3.0);
  EXPECT_EQ(SolveLocalSearch(home).cost, 3.0);
}

TEST(SequenceSolver, PathCostMatchesHandSum) {
  // Two courses in the plane, weights (2, 1). Course 0: (0,0)->(3,0), back (3,1)->(0,1);
  // course 1: (3,4)->(0,4), back (0,5)->(3,5). Start (0,-4), finish (0,0).
  SequenceProblem p;
  p.courses = 2;
  p.dim = 2;
  p.weights = {2.0, 1.0};
  p.points = {0, 0, 3, 0, 3, 1, 0, 1, 3, 4, 0, 4, 0, 5, 3, 5};
  p.start = {0, -4};
  p.finish = std::vector<double>{0, 0};
  p.bidirectional = true;
  const std::vector<Visit> order{{0, false}, {1, true}};
  // Moves: (0,-4)->(0,0): (0,4); (3,0)->(0,5): (-6,5); (3,5)->(0,0): (-6,-5).
  p.norm = CostNorm::kL1;
  EXPECT_DOUBLE_EQ(PathCost(p, order), 4 + 11 + 11);
  p.norm = CostNorm::kMax;
  EXPECT_DOUBLE_EQ(PathCost(p, order), 4 + 6 + 6);
  p.norm = CostNorm::kL2;
  EXPECT_DOUBLE_EQ(PathCost(p, order), 4 + 2 * std::sqrt(61.0));
}

TEST(SequenceSolver, LimitsAndEdgeCases) {
  Gen g{std::mt19937_64(3)};
  const SequenceProblem big = g.Make(2, kMaxExactCourses + 1, CostNorm::kL1, true, false);
  EXPECT_FALSE(SolveExact(big).has_value());
  SequenceProblem none;
  none.dim = 1;
  none.weights = {1.0};
  none.start = {0.0};
  none.finish = std::vector<double>{2.0};
  EXPECT_TRUE(SolveLocalSearch(none).order.empty());
  EXPECT_EQ(SolveLocalSearch(none).cost, 2.0);
  EXPECT_EQ(SolveSeedMethod(none).cost, 2.0);
  EXPECT_EQ(SolveExact(none)->cost, 2.0);
  // Larger unidirectional sets: still every course once, forwards.
  for (int kind = 0; kind < 3; ++kind) {
    const SequenceProblem p = g.Make(kind, 120, CostNorm::kL2, false, true);
    ExpectValid(p, SolveLocalSearch(p, Quick()));
    ExpectValid(p, SolveSeedMethod(p));
  }
}

}  // namespace
}  // namespace stitchsim::planner

namespace stitchsim::planner {
namespace {

// Precedence groups (the sets of one programme optimised together): the answer lays every
// group's courses before the next group's, and it equals brute force over the orders that do
// so (each group permuted on its own, every direction choice), priced independently.
TEST(SequenceSolver, GroupsAreLaidInTurnAndTheirJoinsOptimised) {
  Gen g{std::mt19937_64(11)};
  int cases = 0;
  for (int rep = 0; rep < 6; ++rep) {
    const bool bidirectional = rep % 2 == 1;
    SequenceProblem p = g.Make(rep % 3, 7, CostNorm::kL1, bidirectional, rep >= 3);
    p.group = {1, 0, 2, 1, 0, 2, 1};  // three groups of 2, 3 and 2 courses
    const SequenceSolution s = SolveLocalSearch(p, Quick());
    ExpectValid(p, s);
    for (std::size_t i = 1; i < s.order.size(); ++i) {
      EXPECT_LE(p.group[s.order[i - 1].course], p.group[s.order[i].course]) << "rep " << rep;
    }
    // Brute force: permutations sorted by group first are exactly the allowed orders.
    std::vector<int> perm{1, 4, 0, 3, 6, 2, 5};  // groups 0, 1, 2 in turn
    double best = INFINITY;
    const int flips = bidirectional ? 1 << p.courses : 1;
    auto next_in_groups = [&] {
      // Advance group 2's slice, carrying into group 1's, then group 0's (odometer).
      const int cut[4] = {0, 2, 5, 7};
      for (int k = 2; k >= 0; --k) {
        if (std::next_permutation(perm.begin() + cut[k], perm.begin() + cut[k + 1])) return true;
      }
      return false;
    };
    for (int k = 0; k < 3; ++k) {
      const int cut[4] = {0, 2, 5, 7};
      std::sort(perm.begin() + cut[k], perm.begin() + cut[k + 1]);
    }
    do {
      for (int f = 0; f < flips; ++f) {
        std::vector<Visit> order;
        for (int i = 0; i < p.courses; ++i) order.push_back({perm[i], ((f >> i) & 1) != 0});
        best = std::min(best, IndependentCost(p, order));
      }
    } while (next_in_groups());
    EXPECT_NEAR(s.cost, best, 1e-9 * (1 + best)) << "rep " << rep;
    ++cases;
  }
  EXPECT_EQ(cases, 6);
}

// Bidirectional lay-up allows every forward-only order: its answer is never dearer, on every
// kind of generated set (the search starts from the forward-only answer).
TEST(SequenceSolver, BidirectionalNeverWorseThanForwardOnly) {
  Gen g{std::mt19937_64(12)};
  for (int kind = 0; kind < 3; ++kind) {
    for (CostNorm norm : kNorms) {
      SequenceProblem p = g.Make(kind, 60, norm, false, kind == 1);
      const SequenceSolution forward = SolveLocalSearch(p, Quick());
      p.bidirectional = true;
      const SequenceSolution both = SolveLocalSearch(p, Quick());
      EXPECT_LE(both.cost, forward.cost) << "kind " << kind;
    }
  }
}

// A plate of C columns by R rows of parallel courses, bidirectional, L1 over (x, y, turned):
// course (j, r) runs from x = 320 j to 320 j + 300 at y = 6.35 r, laid backwards with the head
// turned (a third axis, 0 or 1, weighted 1,650: turning costs about 80 times a 20 mm hop to
// the next column). By hand, the cheapest order sweeps a row across the columns, turns, and
// sweeps the next row back: R (C - 1) 20 mm hops and R - 1 turns (each 1,650 + 6.35 y
// weighted 0.01). A return along a column (300 mm) without turning only starts a shorter
// sweep. The courses are given shuffled. The nearest-neighbour construction takes the 300 mm
// returns (cheaper than a turn) and without kicks its descent stayed at 84,398 (three times
// the sweeps); the greedy construction joins the 20 mm hops into rows first and turns whole
// rows to join them.
TEST(SequenceSolver, BidirectionalPlateIsLaidInSweepsWithoutAKick) {
  constexpr int kColumns = 20, kRows = 15;
  constexpr double kPitch = 320.0, kLength = 300.0, kRow = 6.35, kTurn = 1650.0, kY = 0.01;
  SequenceProblem p;
  p.dim = 3;
  p.norm = CostNorm::kL1;
  p.bidirectional = true;
  p.weights = {1.0, kY, kTurn};
  p.start = {0.0, 0.0, 0.0};
  std::vector<std::pair<int, int>> cells;
  for (int j = 0; j < kColumns; ++j) {
    for (int r = 0; r < kRows; ++r) cells.push_back({j, r});
  }
  std::shuffle(cells.begin(), cells.end(), std::mt19937_64(3));
  for (const auto& [j, r] : cells) {
    const double x = kPitch * j, y = kRow * r;
    for (const double v : {x, y, 0.0, x + kLength, y, 0.0, x + kLength, y, 1.0, x, y, 1.0})
      p.points.push_back(v);
    ++p.courses;
  }
  const double sweeps =
      kRows * (kColumns - 1) * (kPitch - kLength) + (kRows - 1) * (kTurn + kY * kRow);
  EXPECT_NEAR(sweeps, 28800.889, 1e-9);
  LocalSearchOptions no_kicks;
  no_kicks.max_rounds = 0;
  no_kicks.starts = 2;
  const SequenceSolution s = SolveLocalSearch(p, no_kicks);
  std::set<int> laid;
  for (const Visit& v : s.order) laid.insert(v.course);
  ASSERT_EQ(s.order.size(), static_cast<std::size_t>(p.courses));
  ASSERT_EQ(laid.size(), static_cast<std::size_t>(p.courses));  // every course, once
  EXPECT_NEAR(IndependentCost(p, s.order), s.cost, 1e-9);
  EXPECT_LE(s.cost, sweeps + 1e-9);
  // And the sweeps indeed: every move is a 20 mm hop or a turn onto the next row.
  int turns = 0;
  for (std::size_t i = 1; i < s.order.size(); ++i)
    turns += s.order[i].reversed != s.order[i - 1].reversed;
  EXPECT_EQ(turns, kRows - 1);
  EXPECT_LE(SolveLocalSearch(p, Quick()).cost, sweeps + 1e-9);
}

}  // namespace
}  // namespace stitchsim::planner
