#pragma once
// The working tour of the local search (local.cpp): an array of visits with
// prefix sums of its forward cost and of the cost of traversing it backwards (every course
// flipped), so that moving or reversing any stretch is priced exactly in O(1) even though
// move costs are not symmetric.
#include <vector>

#include "detail.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner::detail {

/// A candidate change of the tour and its exact cost change.
struct TourMove {
  enum class Kind { kNone, kReverse, kChain } kind = Kind::kNone;
  int i = 0;          ///< first position of the stretch
  int k = 0;          ///< last position of the stretch
  int g = 0;          ///< kChain: the stretch goes after position g (-1: first)
  bool flip = false;  ///< kChain: the stretch is laid backwards, each course flipped
  double delta = 0.0;
};

/// Up to this many courses the tour keeps every move cost in a table: (2n)^2 doubles, at most
/// 32 MiB; above, costs are computed when needed.
inline constexpr int kTableCourses = 1024;

class Tour {
 public:
  Tour(const SequenceProblem& p, std::vector<Visit> order);

  int Size() const { return static_cast<int>(t_.size()); }
  const std::vector<Visit>& Order() const { return t_; }
  Visit At(int i) const { return t_[i]; }
  int PositionOf(int course) const { return pos_[course]; }
  double Cost() const { return cost_; }
  /// The move from the end of a to the start of b (from the table when there is one).
  double Move(Visit a, Visit b) const { return E(a, b); }

  /// Cost change of reversing positions i..k (bidirectional only; i == k flips one course).
  double ReverseDelta(int i, int k) const;
  /// Cost change of moving stretch i..k to after position g (g outside i-1..k), as it is or
  /// flipped (bidirectional only).
  double ChainDelta(int i, int k, int g, bool flip) const;
  /// Applies a move priced by the functions above (O(n)).
  void Apply(const TourMove& m);
  /// Bidirectional: the best direction of every course for the current order (a shortest
  /// path over two states per position, O(n)); returns the cost change of adopting it.
  double BestDirections(std::vector<Visit>& out) const;
  /// Replaces the tour (a saved copy) and its cost.
  void Restore(const std::vector<Visit>& order, double cost);

 private:
  /// Move costs, from the table when there is one.
  double E(Visit a, Visit b) const {
    return table_.empty() ? Edge(p_, a, b) : table_[VisitNode(a) * 2 * t_.size() + VisitNode(b)];
  }
  double S(Visit v) const { return from_start_[VisitNode(v)]; }
  double F(Visit v) const { return to_finish_[VisitNode(v)]; }
  /// Cost from the end of position x (x = -1: p.start) to the start of v.
  double In(int x, Visit v) const { return x < 0 ? S(v) : E(t_[x], v); }
  /// Cost from the end of v to the start of position y (y = n: p.finish, or nothing).
  double Out(Visit v, int y) const { return y >= Size() ? F(v) : E(v, t_[y]); }
  /// The current link between positions x and y = x + 1 (or a stretch's ends after removal).
  double Link(int x, int y) const;
  void Refresh();

  const SequenceProblem& p_;
  std::vector<Visit> t_;
  std::vector<int> pos_;
  std::vector<double> fwd_;  ///< fwd_[i]: moves t0 -> t1 -> ... -> ti
  std::vector<double> rev_;  ///< rev_[i]: moves flip(ti) -> ... -> flip(t0)
  std::vector<Visit> scratch_;
  std::vector<double> table_;  ///< (2n)^2 move costs between nodes, if n <= kTableCourses
  std::vector<double> from_start_, to_finish_;  ///< per node
  double cost_ = 0.0;
};

}  // namespace stitchsim::planner::detail
