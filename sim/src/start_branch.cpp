// The start-branch look-ahead (ExecuteOptions::choose_start_branch).
#include "detail/start_branch.h"

#include <cmath>
#include <istream>
#include <vector>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::sim::detail {
namespace {

using program::Axis;

// The start-branch look-ahead's state: one track per arm configuration at the first pose.
class StartBranchSearch {
 public:
  explicit StartBranchSearch(const CellSetup& cell) : cell_(cell), robot_(*cell.robot) {}

  bool Started() const { return have_first_; }

  // Continuity needs only poses a few degrees apart: a pose that barely moved from the last
  // one visited can be skipped (metres, radians).
  bool BarelyMoved(const Eigen::Isometry3d& tool, double rot) const {
    return have_first_ && geom::AngleBetween(last_tool_.linear(), tool.linear()) < 0.05 &&
           (last_tool_.translation() - tool.translation()).norm() < 0.2 &&
           std::abs(rot - last_rot_) < 0.05;
  }

  // Follows every track to one more pose (tool in the part frame, metres); false if the first
  // pose has no solution.
  bool Visit(const Eigen::Isometry3d& tool, double rot, std::optional<double> rail_mm) {
    last_tool_ = tool;
    last_rot_ = rot;
    const Eigen::Isometry3d world = PartPoseWorld(cell_, rot) * tool;
    RailPolicy policy;
    policy.base_offset_along_rail_m = cell_.rail_offset_m;
    if (rail_mm) policy.programmed_rail_m = *rail_mm / 1000.0;
    const double rail = RailForTarget(robot_, world, policy).rail_m;
    const Eigen::Isometry3d flange = FlangeTargetForTool(world, cell_.flange_to_tool_m);
    if (!have_first_) return Start(flange, rail, rot);
    Follow(flange, rail);
    return true;
  }

  // The feasible start nearest home, if any, and its track's index.
  std::optional<JointVector> Choose(int* track = nullptr) const {
    std::optional<JointVector> chosen;
    double chosen_cost = 1e300;
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      std::optional<JointVector> q = Place(tracks_[i]);
      if (!q) continue;
      const double cost = (*q - first_).segment<kNumArmJoints>(kA1).squaredNorm();
      if (cost < chosen_cost) {
        chosen_cost = cost;
        chosen = q;
        if (track != nullptr) *track = static_cast<int>(i);
      }
    }
    return chosen;
  }
  // Every track's last pose, unwrapped from its start (arm joints).
  std::vector<ArmJointVector> Positions() const {
    std::vector<ArmJointVector> out;
    for (const Track& t : tracks_) out.push_back(t.prev);
    return out;
  }
  // Track `i`'s start (as Choose places it) carried to `position`, one of its later poses.
  JointVector Carried(int i, const JointVector& start, const ArmJointVector& position) const {
    JointVector q = start;
    const Track& t = tracks_[static_cast<std::size_t>(i)];
    for (int j = 0; j < kNumArmJoints; ++j) q[kA1 + j] += position[j] - t.start[j];
    return q;
  }

 private:
  struct Track {
    ArmJointVector start, prev, lo, hi;
  };
  static constexpr double kTwoPi = 2 * kPi;

  // One track per analytic solution at the first pose.
  bool Start(const Eigen::Isometry3d& flange, double rail, double rot) {
    have_first_ = true;
    first_ = HomeJoints(robot_, rail);
    first_[kRotator] = rot;
    const ArmIkSolutions all = AllArmIkSolutions(robot_, flange, rail);
    for (int i = 0; i < all.count; ++i) {
      Track t;
      t.start = all.solution[static_cast<std::size_t>(i)].joints_rad;
      t.prev = t.lo = t.hi = t.start;
      tracks_.push_back(t);
    }
    return !tracks_.empty();
  }

  // Each track moves to the solution nearest it, angles unwrapped.
  void Follow(const Eigen::Isometry3d& flange, double rail) {
    // The solution set does not depend on the hint away from exact singularities: solve once.
    const ArmIkSolutions all = AllArmIkSolutions(robot_, flange, rail, &tracks_.front().prev);
    for (Track& t : tracks_) {
      double best_cost = 1e300;
      ArmJointVector best = t.prev;
      for (int i = 0; i < all.count; ++i) {
        ArmJointVector q = all.solution[static_cast<std::size_t>(i)].joints_rad;
        for (int j = 0; j < kNumArmJoints; ++j) {
          q[j] += kTwoPi * std::round((t.prev[j] - q[j]) / kTwoPi);
        }
        const double cost = (q - t.prev).squaredNorm();
        if (cost < best_cost) {
          best_cost = cost;
          best = q;
        }
      }
      t.prev = best;
      t.lo = t.lo.cwiseMin(best);
      t.hi = t.hi.cwiseMax(best);
    }
  }

  // The track's start shifted by the whole turns that bring its travel [lo, hi] inside the
  // limits, each joint nearest home; nullopt when a joint has no such shift.
  std::optional<JointVector> Place(const Track& t) const {
    JointVector q = first_;
    for (int j = 0; j < kNumArmJoints; ++j) {
      const int m = kA1 + j;
      const double lower = robot_.lower_limits()[m], upper = robot_.upper_limits()[m];
      std::optional<double> best_shift;
      for (int k = -3; k <= 3; ++k) {
        const double shift = kTwoPi * k;
        if (t.lo[j] + shift < lower - 1e-9 || t.hi[j] + shift > upper + 1e-9) continue;
        if (!best_shift || std::abs(t.start[j] + shift - first_[m]) <
                               std::abs(t.start[j] + *best_shift - first_[m])) {
          best_shift = shift;
        }
      }
      if (!best_shift) return std::nullopt;
      q[m] = t.start[j] + *best_shift;
    }
    return q;
  }

  const CellSetup& cell_;
  const RobotModel& robot_;
  std::vector<Track> tracks_;
  JointVector first_ = JointVector::Zero();
  bool have_first_ = false;
  Eigen::Isometry3d last_tool_ = Eigen::Isometry3d::Identity();
  double last_rot_ = 0.0;
};

}  // namespace

struct StartBranchScan::Impl {
  Impl(const CellSetup& cell, geom::EulerOrder o) : search(cell), order(o) {}
  StartBranchSearch search;
  geom::EulerOrder order;
  struct Pending {
    Eigen::Isometry3d tool;
    double rot;
  };
  std::optional<Pending> pending;    // the last pose skipped (never skip the last one)
  bool failed = false;               // the first pose has no solution
  std::optional<JointVector> start;  // Finish's choice
  int track = -1;                    // ... and its track
};

StartBranchScan::StartBranchScan(const CellSetup& cell, geom::EulerOrder order)
    : impl_(std::make_unique<Impl>(cell, order)) {}
StartBranchScan::~StartBranchScan() = default;

void StartBranchScan::Visit(const program::MachineState& st) {
  Impl& d = *impl_;
  if (d.failed) return;
  Eigen::Isometry3d tool = *program::ToolPoseOf(st, d.order);
  tool.translation() /= 1000.0;  // metres
  const double rot = st[Axis::kRotator].value_or(0.0) * kDeg;
  if (d.search.BarelyMoved(tool, rot) && !st[Axis::kRail]) {
    d.pending = Impl::Pending{tool, rot};
    return;
  }
  d.pending.reset();
  if (!d.search.Visit(tool, rot, st[Axis::kRail])) d.failed = true;
}

std::optional<JointVector> StartBranchScan::Finish() {
  Impl& d = *impl_;
  if (d.pending && !d.search.Visit(d.pending->tool, d.pending->rot, std::nullopt)) d.failed = true;
  d.pending.reset();
  if (d.failed || !d.search.Started()) return std::nullopt;
  d.start = d.search.Choose(&d.track);
  return d.start;
}

std::vector<ArmJointVector> StartBranchScan::Positions() const { return impl_->search.Positions(); }

std::optional<JointVector> StartBranchScan::At(const std::vector<ArmJointVector>& positions) const {
  const Impl& d = *impl_;
  if (!d.start || d.track < 0 || static_cast<std::size_t>(d.track) >= positions.size()) {
    return std::nullopt;
  }
  return d.search.Carried(d.track, *d.start, positions[static_cast<std::size_t>(d.track)]);
}

namespace {

// Look-ahead over the line ends, as a controller plans before a long move: every arm
// configuration at the first pose is followed continuously (angles unwrapped, limits
// ignored); the start chosen is the one, shifted by whole turns where a joint allows, whose
// whole travel stays within the limits, nearest the home pose. E.g. a closed circle turns
// a6 through 360 deg: only some starts leave room for that.
std::optional<JointVector> ChooseStartBranch(const CellSetup& cell, const program::Dialect& dialect,
                                             std::istream& in, const std::string& file_name) {
  BoundedDiagnosticSink ignored(4);
  program::ProgramReader reader(in, dialect, file_name, ignored);
  program::ModalState state(dialect, file_name, ignored);
  StartBranchScan scan(cell, program::EulerOrderOf(dialect));
  program::Block block;
  while (reader.Next(block)) {
    const program::Step& step = state.Update(block);
    if (ignored.HasErrors()) return std::nullopt;
    if (!step.is_move) continue;
    const auto& st = state.State();
    for (Axis a : {Axis::kX, Axis::kY, Axis::kZ, Axis::kA, Axis::kB, Axis::kC}) {
      if (!st[a]) return std::nullopt;
    }
    scan.Visit(st);
  }
  return scan.Finish();
}

}  // namespace

// The start branch from a look-ahead over the whole programme, when the input can seek: back
// to the start, through to the end, then back to where the reader stands.
std::optional<JointVector> StartBranchLookAhead(const CellSetup& cell, std::istream& in,
                                                std::streampos origin,
                                                const program::Dialect& dialect,
                                                const std::string& file_name) {
  if (origin == std::streampos(-1)) return std::nullopt;
  in.clear();
  const std::streampos resume = in.tellg();
  if (resume == std::streampos(-1) || !in.seekg(origin)) {
    in.clear();
    return std::nullopt;
  }
  std::optional<JointVector> start = ChooseStartBranch(cell, dialect, in, file_name);
  in.clear();
  in.seekg(resume);
  return start;
}

}  // namespace stitchsim::sim::detail
