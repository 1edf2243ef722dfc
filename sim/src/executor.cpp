#include "stitchsim/sim/executor.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <istream>
#include <vector>

#include "stitchsim/common/limits.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::sim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

using program::Axis;

struct Pose {
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  double drive = 0.0;
  double path = 0.0;
  std::optional<double> rail_mm;
  double rotator_rad = 0.0;
};

// The s-values (line fractions) at which the cycle phase crosses `phase_mark` while U runs
// from u0 to u1 (u1 > u0).
void PhaseCrossings(double u0, double u1, double l, double phase_mark, std::vector<double>& out) {
  const double first = std::ceil(u0 / l - phase_mark - 1e-12);
  for (double k = first;; k += 1.0) {
    const double u = (k + phase_mark) * l;
    if (u > u1 + 1e-12) break;
    if (u >= u0 - 1e-12) out.push_back(std::clamp((u - u0) / (u1 - u0), 0.0, 1.0));
  }
}

class Executor {
 public:
  Executor(const CellSetup& cell, const process::ProcessModel& process,
           const program::Dialect& dialect, const ExecuteOptions& options, TraceSink& sink)
      : cell_(cell), process_(process), options_(options), sink_(sink) {
    order_ = program::EulerOrderOf(dialect);
  }

  void Move(const program::MachineState& before, const program::MachineState& after,
            const program::Step& step, int line, ExecutionSummary& summary) {
    Pose to = PoseOf(after);
    Pose from = have_pose_ ? current_ : to;
    const double l = process_.stitch_length_mm;
    const double du = to.drive - from.drive;
    const bool advancing = du > 1e-12;
    LineRecord rec;
    rec.source_line = line;
    rec.rapid = step.motion == program::Motion::kRapid;
    rec.from = from.tool;
    rec.to = to.tool;
    rec.drive_from_mm = from.drive;
    rec.drive_to_mm = to.drive;
    rec.path_from_mm = from.path;
    rec.path_to_mm = to.path;
    rec.feed_mm_per_min = after.feed_mm_per_min.value_or(0.0);
    rec.stitching = after.stitching;
    rec.head_retracted = after.head_retracted;
    const double dist = (to.tool.translation() - from.tool.translation()).norm();
    const double angle = geom::AngleBetween(from.tool.linear(), to.tool.linear());
    // The samples this line needs, counted before any is taken: beyond the documented bound
    // the line is sampled at its ends only, and the verifier makes it a finding.
    const double coarse_needed =
        std::ceil(std::max(dist / options_.max_step_mm, angle / options_.max_step_rad));
    const double fine_needed = advancing ? std::ceil(std::max(dist / options_.in_preform_step_mm,
                                                              angle / options_.in_preform_step_rad))
                                         : 0.0;
    const double events_needed = advancing ? 2.0 * (du / l + 2.0) : 0.0;
    rec.samples_needed = coarse_needed + fine_needed + events_needed + 2.0;
    rec.over_sample_limit = !(rec.samples_needed <= limits::kMaxSamplesPerLine);
    const bool sampled = !rec.over_sample_limit;
    double duration = angle / options_.rotation_speed_rad_s;
    if (rec.rapid) {
      duration = std::max(duration, dist / options_.rapid_speed_mm_s);
    } else if (dist > 0 && rec.feed_mm_per_min > 0) {
      duration = std::max(duration, dist / (rec.feed_mm_per_min / 60.0));
    }
    if (advancing) duration = std::max(duration, du / l * 60.0 / options_.stitch_rate_per_min);
    if (!advancing && dist <= 1e-9 && angle > 1e-12) duration += options_.settle_time_s;
    rec.duration_s = duration;
    (void)before;
    sink_.OnLine(rec);

    // Sample fractions: line ends, needle events, a coarse IK grid, a fine in-preform grid.
    fractions_.clear();
    events_.clear();
    const int coarse = sampled ? std::max(1, static_cast<int>(coarse_needed)) : 1;
    if (advancing && sampled) {
      entries_.clear();
      exits_.clear();
      PhaseCrossings(from.drive, to.drive, l, process_.phase_in, entries_);
      PhaseCrossings(from.drive, to.drive, l, process_.phase_out, exits_);
      // Fine samples wherever the needles are in.
      const int fine = std::max(1, static_cast<int>(fine_needed));
      for (int i = 1; i < fine; ++i) {
        const double s = static_cast<double>(i) / fine;
        if (process::NeedlesIn(process_, process::CyclePhase(from.drive + s * du, l))) {
          fractions_.push_back(s);
        }
      }
    }
    const std::size_t n_fine = fractions_.size();
    for (int i = 1; i < coarse; ++i) fractions_.push_back(static_cast<double>(i) / coarse);
    std::vector<std::pair<double, SampleEvent>> samples;
    samples.reserve(fractions_.size() + entries_.size() + exits_.size() + 2);
    samples.emplace_back(0.0, SampleEvent::kLineStart);
    for (std::size_t i = 0; i < fractions_.size(); ++i) {
      samples.emplace_back(fractions_[i], i < n_fine ? SampleEvent::kNone : SampleEvent::kLineEnd);
    }
    if (advancing && sampled) {
      for (double s : entries_) samples.emplace_back(s, SampleEvent::kNeedleEntry);
      for (double s : exits_) samples.emplace_back(s, SampleEvent::kNeedleExit);
    }
    samples.emplace_back(1.0, SampleEvent::kLineEnd);
    std::stable_sort(samples.begin(), samples.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    if (options_.collision != nullptr) SubdivideForCollision(from, to, samples);
    // Coarse-grid samples were tagged kLineEnd above only to mark "solve IK here".
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const auto [s, tag] = samples[i];
      const bool last = i + 1 == samples.size();
      const bool first = i == 0;
      // The start of a line is the end of the previous one: skip it after the first move.
      if (first && have_pose_) continue;
      TraceSample t;
      t.time_s = time_s_ + s * duration;
      t.source_line = line;
      t.line_fraction = s;
      t.event = first ? SampleEvent::kLineStart
                      : (last ? SampleEvent::kLineEnd
                              : (tag == SampleEvent::kLineEnd ? SampleEvent::kNone : tag));
      t.tool_part = process::InterpolatePose(from.tool, to.tool, s);
      t.drive_mm = from.drive + s * du;
      t.path_mm = from.path + s * (to.path - from.path);
      t.phase = process::CyclePhase(t.drive_mm, l);
      t.drive_advancing = advancing;
      if (tag == SampleEvent::kNeedleEntry) {
        t.needles_in = true;
        t.phase = process_.phase_in;
        ++summary.stitches;
      } else if (tag == SampleEvent::kNeedleExit) {
        t.needles_in = true;  // the exit sample is the last with the needles in
        t.phase = process_.phase_out;
      } else {
        t.needles_in = advancing && process::NeedlesIn(process_, t.phase) &&
                       !(first && t.phase == process_.phase_in);
      }
      t.stitch = static_cast<long>(std::floor(t.drive_mm / l - 1e-9)) + 1;
      if (t.stitch < 0) t.stitch = 0;
      // Joints on the coarse grid and at line ends; needle events and the fine in-preform
      // samples feed the process rules, which need only the tool pose.
      const bool solve = first || last || tag == SampleEvent::kLineEnd;
      if (solve) {
        const ToolPoseSolution sol = SolveAt(from, to, s, have_joints_ ? &joints_ : nullptr);
        t.has_joints = true;
        t.ik_status = sol.ik.status;
        t.joints = sol.ik.joints;
        t.configuration = sol.ik.configuration;
        // A revolute joint that jumps by more than half a turn between samples has run into
        // its limit: the continuous motion would pass it (the controller would have to
        // unwind). Report the continuous value, beyond the limit.
        if (have_joints_ && sol.ik.ok()) {
          for (int j = kA1; j <= kA6; ++j) {
            const double d = t.joints[j] - joints_[j];
            if (std::abs(d) > 3.14159265358979323846) {
              t.joints[j] -=
                  2 * 3.14159265358979323846 * std::round(d / (2 * 3.14159265358979323846));
              t.ik_status = IkStatus::kJointLimit;
            }
          }
        }
        if (t.ik_status != IkStatus::kUnreachable && t.ik_status != IkStatus::kJointLimit) {
          joints_ = sol.ik.joints;
          have_joints_ = true;
        }
      }
      sink_.OnSample(t);
    }
    time_s_ += duration;
    current_ = to;
    have_pose_ = true;
  }

  // IK at fraction s of the line from -> to.
  ToolPoseSolution SolveAt(const Pose& from, const Pose& to, double s,
                           const JointVector* previous) const {
    const double rot = from.rotator_rad + s * (to.rotator_rad - from.rotator_rad);
    std::optional<double> rail;
    if (from.rail_mm && to.rail_mm) {
      rail = *from.rail_mm + s * (*to.rail_mm - *from.rail_mm);
    } else if (to.rail_mm && s > 0.0) {
      rail = to.rail_mm;  // the programme takes over the rail on this line
    }
    return SolveToolPose(cell_, process::InterpolatePose(from.tool, to.tool, s), rot, rail,
                         previous);
  }

  // Clearance at q from the collision world; -1 in contact (or when the query failed: the
  // rules report both at this sample).
  double ClearanceAt(const JointVector& q) {
    CollisionOptions o;
    const CollisionResult r = options_.collision->Check(q, o);
    return r.contacts.empty() && r.error.empty() ? r.min_clearance_m : -1.0;
  }

  // The between-samples guarantee (see ExecuteOptions::collision): walks the IK samples of the
  // line in order, as the emitting loop will, and inserts fractions where the motion bound
  // MaxPointTravel to the next sample exceeds the clearance at the previous one.
  void SubdivideForCollision(const Pose& from, const Pose& to,
                             std::vector<std::pair<double, SampleEvent>>& samples) {
    JointVector prev = joints_;
    bool have_prev = have_joints_ && have_pose_;
    double prev_s = 0.0;
    double clearance = have_prev ? ClearanceAt(prev) : -1.0;
    std::vector<double> extra;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const bool first = i == 0, last = i + 1 == samples.size();
      if (!(first || last || samples[i].second == SampleEvent::kLineEnd)) continue;
      if (first && have_pose_) continue;
      const double s = samples[i].first;
      ToolPoseSolution sol = SolveAt(from, to, s, have_joints_ || have_prev ? &prev : nullptr);
      const auto usable = [](const ToolPoseSolution& x) {
        return x.ik.status != IkStatus::kUnreachable && x.ik.status != IkStatus::kJointLimit;
      };
      // In contact the sample itself reports it: no need to creep on. Near contact (even
      // touching) the step never falls below the minimum, so the walk ends.
      while (have_prev && usable(sol) && clearance >= 0.0 &&
             static_cast<int>(extra.size()) < options_.collision_max_extra_samples) {
        const double allowed = std::max(clearance, options_.collision_min_clearance_m);
        const double travel = options_.collision->MaxPointTravel(prev, sol.ik.joints);
        if (travel <= allowed) break;
        const double f = std::clamp(allowed / travel, 1.0 / 4096.0, 0.5);
        const double mid = prev_s + f * (s - prev_s);
        const ToolPoseSolution m = SolveAt(from, to, mid, &prev);
        if (!usable(m)) break;
        extra.push_back(mid);
        prev = m.ik.joints;
        prev_s = mid;
        clearance = ClearanceAt(prev);
        sol = SolveAt(from, to, s, &prev);
      }
      if (usable(sol)) {
        prev = sol.ik.joints;
        have_prev = true;
        clearance = ClearanceAt(prev);
      }
      prev_s = s;
    }
    if (extra.empty()) return;
    for (double s : extra) samples.emplace_back(s, SampleEvent::kLineEnd);
    std::stable_sort(samples.begin(), samples.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
  }

  void SeedJoints(const JointVector& q) {
    joints_ = q;
    have_joints_ = true;
  }

  Pose PoseOf(const program::MachineState& st) const {
    Pose p;
    p.tool = *program::ToolPoseOf(st, order_);  // the caller checked X Y Z A B C are set
    p.drive = st[Axis::kDrive].value_or(0.0);
    p.path = st[Axis::kPathLength].value_or(0.0);
    p.rail_mm = st[Axis::kRail];
    p.rotator_rad = st[Axis::kRotator].value_or(0.0) * kDeg;
    return p;
  }

  double Time() const { return time_s_; }

 private:
  const CellSetup& cell_;
  const process::ProcessModel& process_;
  const ExecuteOptions& options_;
  TraceSink& sink_;
  geom::EulerOrder order_;
  Pose current_;
  bool have_pose_ = false;
  JointVector joints_ = JointVector::Zero();
  bool have_joints_ = false;
  double time_s_ = 0.0;
  std::vector<double> fractions_, entries_, exits_;
  std::vector<SampleEvent> events_;
};

// Look-ahead over the line ends, as a controller plans before a long move: every arm
// configuration at the first pose is followed continuously (angles unwrapped, limits
// ignored); the start chosen is the one, shifted by whole turns where a joint allows, whose
// whole travel stays within the limits, nearest the home pose. E.g. a closed circle turns
// a6 through 360 deg: only some starts leave room for that.
std::optional<JointVector> ChooseStartBranch(const CellSetup& cell, const program::Dialect& dialect,
                                             std::istream& in, const std::string& file_name) {
  constexpr double kTwoPi = 2 * 3.14159265358979323846;
  const RobotModel& robot = *cell.robot;
  BoundedDiagnosticSink ignored(4);
  program::ProgramReader reader(in, dialect, file_name, ignored);
  program::ModalState state(dialect, file_name, ignored);
  const geom::EulerOrder order = program::EulerOrderOf(dialect);
  struct Track {
    ArmJointVector start, prev, lo, hi;
  };
  std::vector<Track> tracks;
  JointVector first = JointVector::Zero();
  bool have_first = false;
  Eigen::Isometry3d last_tool = Eigen::Isometry3d::Identity();
  double last_rot = 0.0;
  struct Pending {
    Eigen::Isometry3d tool;
    double rot;
    std::optional<double> rail_mm;
  };
  std::optional<Pending> pending;
  // Follows every track to one more pose; false if the first pose has no solution.
  auto visit = [&](const Eigen::Isometry3d& tool, double rot, std::optional<double> rail_mm) {
    last_tool = tool;
    last_rot = rot;
    const Eigen::Isometry3d world = PartPoseWorld(cell, rot) * tool;
    RailPolicy policy;
    policy.base_offset_along_rail_m = cell.rail_offset_m;
    if (rail_mm) policy.programmed_rail_m = *rail_mm / 1000.0;
    const double rail = RailForTarget(robot, world, policy).rail_m;
    const Eigen::Isometry3d flange = FlangeTargetForTool(world, cell.flange_to_tool_m);
    if (!have_first) {
      have_first = true;
      first = HomeJoints(robot, rail);
      first[kRotator] = rot;
      const ArmIkSolutions all = AllArmIkSolutions(robot, flange, rail);
      for (int i = 0; i < all.count; ++i) {
        Track t;
        t.start = all.solution[static_cast<std::size_t>(i)].joints_rad;
        t.prev = t.lo = t.hi = t.start;
        tracks.push_back(t);
      }
      if (tracks.empty()) return false;
      return true;
    }
    // The solution set does not depend on the hint away from exact singularities: solve once.
    const ArmIkSolutions all = AllArmIkSolutions(robot, flange, rail, &tracks.front().prev);
    for (Track& t : tracks) {
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
    return true;
  };
  program::Block block;
  while (reader.Next(block)) {
    const program::Step& step = state.Update(block);
    if (ignored.HasErrors()) return std::nullopt;
    if (!step.is_move) continue;
    const auto& st = state.State();
    for (Axis a : {Axis::kX, Axis::kY, Axis::kZ, Axis::kA, Axis::kB, Axis::kC}) {
      if (!st[a]) return std::nullopt;
    }
    Eigen::Isometry3d tool = *program::ToolPoseOf(st, order);
    tool.translation() /= 1000.0;  // metres
    const double rot = st[Axis::kRotator].value_or(0.0) * kDeg;
    // Continuity needs only poses a few degrees apart: skip the ones that barely moved
    // (but never the last one, kept as `pending`).
    if (have_first && geom::AngleBetween(last_tool.linear(), tool.linear()) < 0.05 &&
        (last_tool.translation() - tool.translation()).norm() < 0.2 &&
        std::abs(rot - last_rot) < 0.05 && !st[Axis::kRail]) {
      pending = Pending{tool, rot, std::nullopt};
      continue;
    }
    pending.reset();
    if (!visit(tool, rot, st[Axis::kRail])) return std::nullopt;
  }
  if (pending && !visit(pending->tool, pending->rot, pending->rail_mm)) return std::nullopt;
  if (!have_first) return std::nullopt;
  std::optional<JointVector> chosen;
  double chosen_cost = 1e300;
  for (const Track& t : tracks) {
    JointVector q = first;
    bool feasible = true;
    for (int j = 0; j < kNumArmJoints && feasible; ++j) {
      const int m = kA1 + j;
      const double lower = robot.lower_limits()[m], upper = robot.upper_limits()[m];
      // Whole turns that bring [lo, hi] inside the limits, the start nearest home.
      std::optional<double> best_shift;
      for (int k = -3; k <= 3; ++k) {
        const double shift = kTwoPi * k;
        if (t.lo[j] + shift < lower - 1e-9 || t.hi[j] + shift > upper + 1e-9) continue;
        if (!best_shift || std::abs(t.start[j] + shift - first[m]) <
                               std::abs(t.start[j] + *best_shift - first[m])) {
          best_shift = shift;
        }
      }
      if (!best_shift) {
        feasible = false;
      } else {
        q[m] = t.start[j] + *best_shift;
      }
    }
    if (!feasible) continue;
    const double cost = (q - first).segment<kNumArmJoints>(kA1).squaredNorm();
    if (cost < chosen_cost) {
      chosen_cost = cost;
      chosen = q;
    }
  }
  return chosen;
}

}  // namespace

ExecuteOptions ExecuteOptionsFor(const scene::Scene& scene) {
  ExecuteOptions o;
  o.mounted_head = scene.head.name;
  if (scene.head.IsStitching()) {
    o.rapid_speed_mm_s = scene.head.stitch.rapid_speed_mm_s;
    o.rotation_speed_rad_s = scene.head.stitch.rotation_speed_deg_s * kDeg;
    o.stitch_rate_per_min = scene.head.stitch.stitch_rate_per_min;
    o.settle_time_s = scene.head.stitch.settle_time_s;
  } else {
    o.rapid_speed_mm_s = scene.head.afp.rapid_speed_mm_s;
  }
  return o;
}

ProgramInput::ProgramInput(std::istream& in, const program::Dialect& dialect, std::string file_name,
                           DiagnosticSink& diagnostics)
    : in_(in),
      origin_(in.tellg()),
      dialect_(dialect),
      file_name_(std::move(file_name)),
      reader_(in, dialect, file_name_, diagnostics) {}

namespace {

// The start branch from a look-ahead over the whole programme, when the input can seek: back
// to the start, through to the end, then back to where the reader stands.
std::optional<JointVector> LookAhead(const CellSetup& cell, std::istream& in, std::streampos origin,
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

// `T<n> M6` must mount the cell's head.
bool HeadMatches(const program::Dialect& dialect, const program::MachineState& st,
                 const program::Block& block, const ExecuteOptions& options,
                 const std::string& file_name, DiagnosticSink& diagnostics) {
  if (options.mounted_head.empty() || options.allow_head_mismatch || !st.active_tool) return true;
  const program::ToolEntry* tool = dialect.FindTool(*st.active_tool);
  if (tool == nullptr || tool->head == options.mounted_head) return true;
  diagnostics.Error("exec-head-mismatch", {file_name, block.source_line, 1},
                    "T" + std::to_string(*st.active_tool) + " M6 mounts head '" + tool->head +
                        "', but the cell carries '" + options.mounted_head +
                        "' (the scene's head); --allow-mismatch verifies it anyway");
  return false;
}

}  // namespace

ExecutionSummary ExecuteProgram(const CellSetup& cell, const process::ProcessModel& process,
                                const program::Dialect& dialect, std::istream& in,
                                const std::string& file_name, const ExecuteOptions& options,
                                DiagnosticSink& diagnostics, TraceSink& sink) {
  ProgramInput input(in, dialect, file_name, diagnostics);
  return ExecuteProgram(cell, process, input, options, diagnostics, sink);
}

ExecutionSummary ExecuteProgram(const CellSetup& cell, const process::ProcessModel& process,
                                ProgramInput& input, const ExecuteOptions& options,
                                DiagnosticSink& diagnostics, TraceSink& sink) {
  const program::Dialect& dialect = input.dialect_;
  const std::string& file_name = input.file_name_;
  program::ProgramReader& reader = input.reader_;
  ExecutionSummary summary;
  std::optional<JointVector> start;
  if (options.choose_start_branch) {
    start = LookAhead(cell, input.in_, input.origin_, dialect, file_name);
  }
  program::ModalState state(dialect, file_name, diagnostics);
  Executor exec(cell, process, dialect, options, sink);
  if (start) exec.SeedJoints(*start);
  program::Block block;
  const std::size_t errors_before = diagnostics.ErrorCount();
  while (reader.Next(block)) {
    const program::Step& step = state.Update(block);
    if (diagnostics.ErrorCount() > errors_before) break;
    if (step.tool_changed &&
        !HeadMatches(dialect, state.State(), block, options, file_name, diagnostics)) {
      break;
    }
    if (!step.is_move) continue;
    const auto& st = state.State();
    for (Axis a : {Axis::kX, Axis::kY, Axis::kZ, Axis::kA, Axis::kB, Axis::kC}) {
      if (!st[a]) {
        diagnostics.Error("exec-incomplete-pose", {file_name, block.source_line, 1},
                          "the first move must give the whole tool pose (X Y Z A B C); " +
                              std::string(program::RoleName(a)) + " is not known yet");
        break;
      }
    }
    if (diagnostics.ErrorCount() > errors_before) break;
    const auto& u_before = state.Previous()[Axis::kDrive];
    const auto& u_after = st[Axis::kDrive];
    if (u_before && u_after && *u_after < *u_before - 1e-9) {
      diagnostics.Error("exec-drive-reversed", {file_name, block.source_line, 1},
                        "the drive axis U runs backwards");
      break;
    }
    exec.Move(state.Previous(), st, step, block.source_line, summary);
    ++summary.moves;
  }
  // Drain the reader so its end-of-file checks (missing '%', ...) run.
  while (diagnostics.ErrorCount() == errors_before && reader.Next(block)) {
    state.Update(block);
  }
  if (diagnostics.ErrorCount() == errors_before && options.require_program_end &&
      !state.State().program_ended) {
    diagnostics.Error("exec-missing-program-end", {file_name, reader.LineCount(), 1},
                      "the programme stops here without its end (M" +
                          std::to_string(dialect.m.program_end) + "): cut short?");
  }
  summary.lines = reader.LineCount();
  summary.header = reader.Header();
  summary.time_s = exec.Time();
  summary.ok = diagnostics.ErrorCount() == errors_before;
  return summary;
}

}  // namespace stitchsim::sim
