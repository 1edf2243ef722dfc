#pragma once
// Private helpers shared by the sequence solvers (the files of this folder): where a visit starts
// and ends, the cost of one move between two visits.
#include <cassert>
#include <chrono>
#include <limits>
#include <vector>

#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Row `row` of p.points (dim values).
inline const double* Row(const SequenceProblem& p, int row) {
  return p.points.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(p.dim);
}
/// Where the head starts laying visit v, and where it lifts off.
inline const double* StartOf(const SequenceProblem& p, Visit v) {
  return Row(p, 4 * v.course + (v.reversed ? 2 : 0));
}
inline const double* EndOf(const SequenceProblem& p, Visit v) {
  return Row(p, 4 * v.course + (v.reversed ? 3 : 1));
}
inline Visit Flip(Visit v) { return {v.course, !v.reversed}; }

/// Node numbering of visits: 2 course + reversed.
inline Visit NodeVisit(int node) { return {node / 2, (node & 1) != 0}; }
inline int VisitNode(Visit v) { return 2 * v.course + (v.reversed ? 1 : 0); }

/// The off-part move from the end of `a` to the start of `b`.
inline double Edge(const SequenceProblem& p, Visit a, Visit b) {
  if (p.table) {
    return p.table
        ->move[static_cast<std::size_t>(VisitNode(a)) * 2 * static_cast<std::size_t>(p.courses) +
               static_cast<std::size_t>(VisitNode(b))];
  }
  return MoveCost(p, EndOf(p, a), StartOf(p, b));
}
/// From p.start to the start of v; from the end of v to p.finish (0 without a finish).
inline double FromStart(const SequenceProblem& p, Visit v) {
  if (p.table) return p.table->from_start[static_cast<std::size_t>(VisitNode(v))];
  return MoveCost(p, p.start.data(), StartOf(p, v));
}
inline double ToFinish(const SequenceProblem& p, Visit v) {
  if (!p.finish) return 0.0;
  if (p.table) return p.table->to_finish[static_cast<std::size_t>(VisitNode(v))];
  return MoveCost(p, EndOf(p, v), p.finish->data());
}
/// The path of no course: start straight to finish (0 without a finish).
inline double StartToFinish(const SequenceProblem& p) {
  if (!p.finish) return 0.0;
  if (p.table) return p.table->start_to_finish;
  return MoveCost(p, p.start.data(), p.finish->data());
}

/// Asserts the problem's arrays have the sizes its counts promise (programming errors).
inline void AssertWellFormed(const SequenceProblem& p) {
  assert(p.courses >= 0 && p.dim >= 0);
  assert(p.group.empty() || p.group.size() == static_cast<std::size_t>(p.courses));
  if (p.table) {
    const auto m = 2u * static_cast<std::size_t>(p.courses);
    assert(p.table->move.size() == m * m && p.table->from_start.size() == m);
    assert(!p.finish || p.table->to_finish.size() == m);
    (void)m;
    return;
  }
  assert(p.points.size() == 4u * static_cast<std::size_t>(p.courses * p.dim));
  assert(p.weights.size() == static_cast<std::size_t>(p.dim));
  assert(p.start.size() == static_cast<std::size_t>(p.dim));
  assert(!p.finish || p.finish->size() == static_cast<std::size_t>(p.dim));
  (void)p;
}

/// Seconds since t0 on the steady clock.
/// A solver's answer begun: the problem checked, the solver named, and how it stops unless
/// it says otherwise.
inline SequenceSolution BeginSolution(const SequenceProblem& p, const char* solver,
                                      SolveStatus status) {
  AssertWellFormed(p);
  SequenceSolution s;
  s.solver = solver;
  s.status = status;
  return s;
}

inline double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace stitchsim::planner::detail
