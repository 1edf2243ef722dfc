#pragma once
// The working tour of the local search (local.cpp): an array of visits with prefix sums of
// its forward cost, of the cost of traversing it backwards with every course kept as it is,
// and (bidirectional) with every course flipped, so that moving or reversing any stretch is
// priced exactly in O(1) even though move costs are not symmetric. With precedence groups
// (SequenceProblem::group) every group keeps its block of positions; a move that would take
// a course out of its block is not allowed.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "detail.h"
#include "stitchsim/planner/sequence/solver.h"

namespace stitchsim::planner::detail {

/// How a stretch is laid after a move: as it was; in reverse order with every course laid in
/// its own direction still (legal with forward-only lay-up); in reverse order with every
/// course flipped (bidirectional only: the stretch driven backwards).
enum class Stretch : std::uint8_t { kKeep, kReverse, kFlip };

/// A candidate change of the tour and its exact cost change.
struct TourMove {
  enum class Kind { kNone, kReverse, kChain } kind = Kind::kNone;
  int i = 0;                     ///< first position of the stretch
  int k = 0;                     ///< last position of the stretch
  int g = 0;                     ///< kChain: the stretch goes after position g (-1: first)
  Stretch how = Stretch::kKeep;  ///< kReverse: kReverse or kFlip; kChain: any
  double delta = 0.0;
};

/// Up to this many courses the local search tables every move cost once per call (TableOf):
/// (2n)^2 doubles, at most 32 MiB, shared by its phases and starts; above, costs are computed
/// when needed (a MoveTable problem brings its own).
inline constexpr int kTableCourses = 1024;
/// Every move cost of p (its norms of points, or its own table) as a MoveTable.
std::shared_ptr<const MoveTable> TableOf(const SequenceProblem& p);

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
  /// The tour's current move into position x (from the start) and out of it (to the finish).
  double CostInto(int x) const { return In(x - 1, t_[x]); }
  double CostOutOf(int x) const { return Out(t_[x], x + 1); }
  /// First and last position of the block that position x belongs to (the whole tour
  /// without groups).
  int BlockBegin(int x) const { return block_lo_[x]; }
  int BlockEnd(int x) const { return block_hi_[x]; }

  /// Whether stretch i..k may be turned (one block), and moved to after g (inside its block).
  bool CanTurn(int i, int k) const {
    return i >= 0 && k < Size() && i <= k && block_lo_[i] == block_lo_[k];
  }
  bool CanMove(int i, int k, int g) const {
    return CanTurn(i, k) && (g < i - 1 || g > k) && g >= block_lo_[i] - 1 && g <= block_hi_[i];
  }
  /// Cost change of turning positions i..k round in place (how: kReverse or kFlip; i == k
  /// with kFlip flips one course).
  double ReverseDelta(int i, int k, Stretch how) const;
  /// Cost change of moving stretch i..k to after position g, laid `how`.
  double ChainDelta(int i, int k, int g, Stretch how) const;
  /// Applies a move priced by the functions above (O(n)).
  void Apply(const TourMove& m);
  /// Bidirectional: the best direction of every course at positions lo..hi for the current
  /// order, the courses around them as laid (a shortest path over two states per position,
  /// O(hi - lo)); `out` gets those positions' visits; returns the cost change of adopting it.
  double BestDirections(int lo, int hi, std::vector<Visit>& out) const;
  /// Adopts directions from BestDirections(lo, ...) and its cost change.
  void Turn(int lo, const std::vector<Visit>& turned, double delta);
  /// The positions moves have changed since the last ClearTouched (lo > hi: none).
  int TouchedBegin() const { return touched_lo_; }
  int TouchedEnd() const { return touched_hi_; }
  void ClearTouched() {
    touched_lo_ = Size();
    touched_hi_ = -1;
  }
  /// Starts a round: Restore brings back the tour as it is now (the caller keeps a copy).
  void Mark() {
    round_lo_ = Size();
    round_hi_ = -1;
  }
  /// Replaces the tour by `order`, the copy saved at Mark(), and its cost: only the positions
  /// changed since then are recomputed.
  void Restore(const std::vector<Visit>& order, double cost);

 private:
  /// Move costs, from the table when there is one.
  double E(Visit a, Visit b) const {
    return tab_ == nullptr ? Edge(p_, a, b)
                           : tab_[static_cast<std::size_t>(VisitNode(a)) * stride_ +
                                  static_cast<std::size_t>(VisitNode(b))];
  }
  double S(Visit v) const { return from_start_[VisitNode(v)]; }
  double F(Visit v) const { return to_finish_[VisitNode(v)]; }
  /// Cost from the end of position x (x = -1: p.start) to the start of v.
  double In(int x, Visit v) const { return x < 0 ? S(v) : E(t_[x], v); }
  /// Cost from the end of v to the start of position y (y = n: p.finish, or nothing).
  double Out(Visit v, int y) const { return y >= Size() ? F(v) : E(v, t_[y]); }
  /// The current link between positions x and y = x + 1 (or a stretch's ends after removal).
  double Link(int x, int y) const;
  /// The moves inside positions i..k when laid `how`.
  double Inside(int i, int k, Stretch how) const;
  Visit FirstOf(int i, int k, Stretch how) const {
    return how == Stretch::kKeep ? t_[i] : how == Stretch::kReverse ? t_[k] : Flip(t_[k]);
  }
  Visit LastOf(int i, int k, Stretch how) const {
    return how == Stretch::kKeep ? t_[k] : how == Stretch::kReverse ? t_[i] : Flip(t_[i]);
  }
  /// Recomputes positions and prefix sums after positions from..to changed (O(to - from)
  /// table look-ups, then one add per later position).
  void Refresh(int from, int to);

  const SequenceProblem& p_;
  std::vector<Visit> t_;
  std::vector<int> pos_;
  std::vector<int> block_lo_, block_hi_;  ///< per position: its group's block
  std::vector<double> fwd_;               ///< fwd_[i]: moves t0 -> t1 -> ... -> ti
  std::vector<double> bwd_;               ///< bwd_[i]: moves ti -> ... -> t0, each course as laid
  std::vector<double> rev_;  ///< rev_[i]: moves flip(ti) -> ... -> flip(t0) (bidirectional)
  std::vector<Visit> scratch_;
  const double* tab_ = nullptr;                 ///< the problem's MoveTable; null: costs computed
  std::size_t stride_ = 0;                      ///< 2n
  std::vector<double> from_start_, to_finish_;  ///< per node
  double cost_ = 0.0;
  std::int64_t applied_ = 0;             ///< moves applied (every kFullRefresh-th recomputes all)
  int touched_lo_ = 0, touched_hi_ = 0;  ///< positions changed since ClearTouched
  int round_lo_ = 0, round_hi_ = -1;     ///< positions changed since Mark
  void TouchRange(int lo, int hi) {
    touched_lo_ = std::min(touched_lo_, lo);
    touched_hi_ = std::max(touched_hi_, hi);
    round_lo_ = std::min(round_lo_, lo);
    round_hi_ = std::max(round_hi_, hi);
  }
  static constexpr std::int64_t kFullRefresh = 1024;
};

}  // namespace stitchsim::planner::detail
