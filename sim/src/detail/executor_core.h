#pragma once
// Private to sim: the executor's line-by-line machinery (executor.cpp runs a whole programme,
// chunk.cpp its first pass and its chunks).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "stitchsim/common/limits.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/tool_pose.h"
#include "stitchsim/sim/executor.h"

namespace stitchsim::sim::detail {

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
inline void PhaseCrossings(double u0, double u1, double l, double phase_mark,
                           std::vector<double>& out) {
  const double first = std::ceil(u0 / l - phase_mark - 1e-12);
  for (double k = first;; k += 1.0) {
    const double u = (k + phase_mark) * l;
    if (u > u1 + 1e-12) break;
    if (u >= u0 - 1e-12) out.push_back(std::clamp((u - u0) / (u1 - u0), 0.0, 1.0));
  }
}

// How one line is sampled: its record and the counts its samples are planned from.
struct LinePlan {
  LineRecord rec;
  double stitch_length_mm = 0.0;
  double du = 0.0;  ///< U travel of the line
  bool advancing = false;
  bool sampled = false;  ///< within the per-line sample bound
  double coarse_needed = 0.0, fine_needed = 0.0;
};

using SampleList = std::vector<std::pair<double, SampleEvent>>;

// The tag of a sample the collision subdivision inserted (solved like the grid, emitted as
// kNone with TraceSample::collision_probe set).
constexpr SampleEvent kCollisionProbe = static_cast<SampleEvent>(100);

inline void SortSamples(SampleList& samples) {
  std::stable_sort(samples.begin(), samples.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
}

class Executor {
 public:
  Executor(const CellSetup& cell, const process::ProcessModel& process,
           const program::Dialect& dialect, const ExecuteOptions& options, TraceSink& sink)
      : cell_(cell), process_(process), options_(options), sink_(sink) {
    order_ = program::EulerOrderOf(dialect);
    if (options_.collision != nullptr) {
      const std::vector<std::string> names = options_.collision->BodyNames();
      for (std::size_t i = 0; i < names.size(); ++i) body_index_.emplace(names[i], int(i));
    }
  }

  void Move(const program::MachineState& before, const program::MachineState& after,
            const program::Step& step, int line, ExecutionSummary& summary) {
    (void)before;
    Pose to = PoseOf(after);
    Pose from = have_pose_ ? current_ : to;
    const LinePlan plan = PlanLine(from, to, after, step, line);
    sink_.OnLine(plan.rec);
    memo_.clear();
    PlanSamples(from, to, plan, samples_);
    if (options_.collision != nullptr && options_.collision_subdivide) {
      SubdivideForCollision(from, to, samples_);
    }
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const bool first = i == 0;
      // The start of a line is the end of the previous one: skip it after the first move.
      if (first && have_pose_) continue;
      EmitSample(from, to, plan, samples_[i], first, i + 1 == samples_.size(), summary);
    }
    time_s_ += plan.rec.duration_s;
    current_ = to;
    have_pose_ = true;
  }

  // The line's record: poses, axes, modal state, duration, and the samples it needs, counted
  // before any is taken (beyond the documented bound the line is sampled at its ends only, and
  // the verifier makes it a finding).
  LinePlan PlanLine(const Pose& from, const Pose& to, const program::MachineState& after,
                    const program::Step& step, int line) const {
    LinePlan p;
    LineRecord& rec = p.rec;
    p.stitch_length_mm = process_.stitch_length_mm;
    p.du = to.drive - from.drive;
    p.advancing = p.du > 1e-12;
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
    rec.tows = after.tows;
    rec.ply = after.ply;
    rec.course = after.course;
    const double dist = (to.tool.translation() - from.tool.translation()).norm();
    const double angle = geom::AngleBetween(from.tool.linear(), to.tool.linear());
    p.coarse_needed =
        std::ceil(std::max(dist / options_.max_step_mm, angle / options_.max_step_rad));
    p.fine_needed = p.advancing ? std::ceil(std::max(dist / options_.in_preform_step_mm,
                                                     angle / options_.in_preform_step_rad))
                                : 0.0;
    const double events_needed = p.advancing ? 2.0 * (p.du / p.stitch_length_mm + 2.0) : 0.0;
    rec.samples_needed = p.coarse_needed + p.fine_needed + events_needed + 2.0;
    rec.over_sample_limit = !(rec.samples_needed <= limits::kMaxSamplesPerLine);
    p.sampled = !rec.over_sample_limit;
    double duration = angle / options_.rotation_speed_rad_s;
    if (rec.rapid) {
      duration = std::max(duration, dist / options_.rapid_speed_mm_s);
    } else if (dist > 0 && rec.feed_mm_per_min > 0) {
      duration = std::max(duration, dist / (rec.feed_mm_per_min / 60.0));
    }
    if (p.advancing) {
      duration =
          std::max(duration, p.du / p.stitch_length_mm * 60.0 / options_.stitch_rate_per_min);
    }
    if (!p.advancing && dist <= 1e-9 && angle > 1e-12) duration += options_.settle_time_s;
    rec.duration_s = duration;
    return p;
  }

  // Sample fractions: line ends, needle events, a coarse IK grid, a fine in-preform grid. The
  // coarse-grid samples are tagged kLineEnd to mark "solve IK here" (emitted as kNone).
  void PlanSamples(const Pose& from, const Pose& to, const LinePlan& p, SampleList& samples) {
    fractions_.clear();
    entries_.clear();
    exits_.clear();
    const double l = p.stitch_length_mm;
    const int coarse = p.sampled ? std::max(1, static_cast<int>(p.coarse_needed)) : 1;
    if (p.advancing && p.sampled) {
      PhaseCrossings(from.drive, to.drive, l, process_.phase_in, entries_);
      PhaseCrossings(from.drive, to.drive, l, process_.phase_out, exits_);
      // Fine samples wherever the needles are in.
      const int fine = std::max(1, static_cast<int>(p.fine_needed));
      for (int i = 1; i < fine; ++i) {
        const double s = static_cast<double>(i) / fine;
        if (process::NeedlesIn(process_, process::CyclePhase(from.drive + s * p.du, l))) {
          fractions_.push_back(s);
        }
      }
    }
    const std::size_t n_fine = fractions_.size();
    for (int i = 1; i < coarse; ++i) fractions_.push_back(static_cast<double>(i) / coarse);
    samples.clear();
    samples.reserve(fractions_.size() + entries_.size() + exits_.size() + 2);
    samples.emplace_back(0.0, SampleEvent::kLineStart);
    for (std::size_t i = 0; i < fractions_.size(); ++i) {
      samples.emplace_back(fractions_[i], i < n_fine ? SampleEvent::kNone : SampleEvent::kLineEnd);
    }
    for (double s : entries_) samples.emplace_back(s, SampleEvent::kNeedleEntry);
    for (double s : exits_) samples.emplace_back(s, SampleEvent::kNeedleExit);
    samples.emplace_back(1.0, SampleEvent::kLineEnd);
    SortSamples(samples);
  }

  // One sample at fraction `at.first` of the line: the process state, the joints where they
  // are solved (and the collision world's answer there), sent to the sink.
  void EmitSample(const Pose& from, const Pose& to, const LinePlan& p,
                  const std::pair<double, SampleEvent>& at, bool first, bool last,
                  ExecutionSummary& summary) {
    const auto [s, tag] = at;
    const double l = p.stitch_length_mm;
    TraceSample t;
    t.time_s = time_s_ + s * p.rec.duration_s;
    t.source_line = p.rec.source_line;
    t.line_fraction = s;
    t.event =
        first ? SampleEvent::kLineStart
              : (last ? SampleEvent::kLineEnd
                      : (tag == SampleEvent::kLineEnd || tag == kCollisionProbe ? SampleEvent::kNone
                                                                                : tag));
    t.collision_probe = tag == kCollisionProbe && !first && !last;
    t.tool_part = process::InterpolatePose(from.tool, to.tool, s);
    t.drive_mm = from.drive + s * p.du;
    t.path_mm = from.path + s * (to.path - from.path);
    t.phase = process::CyclePhase(t.drive_mm, l);
    t.drive_advancing = p.advancing;
    if (tag == SampleEvent::kNeedleEntry) {
      t.needles_in = true;
      t.phase = process_.phase_in;
      ++summary.stitches;
    } else if (tag == SampleEvent::kNeedleExit) {
      t.needles_in = true;  // the exit sample is the last with the needles in
      t.phase = process_.phase_out;
    } else {
      t.needles_in = p.advancing && process::NeedlesIn(process_, t.phase) &&
                     !(first && t.phase == process_.phase_in);
    }
    t.stitch = static_cast<long>(std::floor(t.drive_mm / l - 1e-9)) + 1;
    if (t.stitch < 0) t.stitch = 0;
    // Joints on the coarse grid and at line ends; needle events and the fine in-preform
    // samples feed the process rules, which need only the tool pose.
    if (first || last || tag == SampleEvent::kLineEnd || tag == kCollisionProbe ||
        options_.solve_every_sample) {
      SolveSample(from, to, s, t);
      if (options_.collision != nullptr && trace::JointsUsable(t)) RecordCollision(t);
    }
    sink_.OnSample(t);
  }

  // Joints at the sample, continuous with the previous usable ones.
  void SolveSample(const Pose& from, const Pose& to, double s, TraceSample& t) {
    const ToolPoseSolution sol = Solved(from, to, s, have_joints_ ? &joints_ : nullptr);
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
        if (std::abs(d) > kPi) {
          t.joints[j] -= 2 * kPi * std::round(d / (2 * kPi));
          t.ik_status = IkStatus::kJointLimit;
        }
      }
    }
    if (trace::IkUsable(t.ik_status)) {
      joints_ = sol.ik.joints;
      have_joints_ = true;
      // Kinematic mode: the arm stands at the solved joints, and MuJoCo says where that puts
      // the tool (equal to the command to 1e-9 m where the IK solved it exactly).
      if (options_.mujoco != nullptr) {
        options_.mujoco->SetJoints(t.joints);
        t.tool_part = options_.mujoco->ToolInPartMm();
      }
    }
  }

  // The collision world's answer at the sample's joints, into the sample (bodies by index into
  // the trace's body table). The subdivision asked the same question a moment ago: the
  // world's query cache answers it without a second FCL query.
  void RecordCollision(TraceSample& t) {
    const CollisionResult r = options_.collision->Check(t.joints, CollisionOptions{});
    trace::SampleCollision& c = t.collision;
    c.checked = true;
    c.min_clearance_m = r.min_clearance_m;
    c.error = r.error;
    c.contacts.reserve(r.contacts.size());
    for (const Contact& k : r.contacts) {
      c.contacts.push_back({k.kind, BodyIndex(k.body_a), BodyIndex(k.body_b), k.depth_m,
                            k.depth_measured, k.point_world_m});
    }
    // "a|b": the split whose halves are both bodies (a name may hold '|').
    const std::string& pair = r.min_clearance_pair;
    for (std::size_t bar = pair.find('|'); bar != std::string::npos;
         bar = pair.find('|', bar + 1)) {
      const int a = BodyIndex(pair.substr(0, bar)), b = BodyIndex(pair.substr(bar + 1));
      if (a >= 0 && b >= 0) {
        c.clearance_body_a = a;
        c.clearance_body_b = b;
        break;
      }
    }
  }

  int BodyIndex(const std::string& name) const {
    const auto it = body_index_.find(name);
    return it == body_index_.end() ? -1 : it->second;
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
  void SubdivideForCollision(const Pose& from, const Pose& to, SampleList& samples) {
    memo_.clear();
    JointVector prev = joints_;
    bool have_prev = have_joints_ && have_pose_;
    double prev_s = 0.0;
    double clearance = have_prev ? ClearanceAt(prev) : -1.0;
    std::vector<double> extra;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const bool first = i == 0, last = i + 1 == samples.size();
      if (!(first || last || samples[i].second == SampleEvent::kLineEnd ||
            samples[i].second == kCollisionProbe)) {
        continue;
      }
      if (first && have_pose_) continue;
      const double s = samples[i].first;
      ToolPoseSolution sol = SolveAt(from, to, s, have_joints_ || have_prev ? &prev : nullptr);
      const bool sol_had_prev = have_joints_ || have_prev;
      JointVector sol_prev = prev;
      const auto usable = [](const ToolPoseSolution& x) { return trace::IkUsable(x.ik.status); };
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
        Memo(mid, &prev, m);
        if (!usable(m)) break;
        extra.push_back(mid);
        prev = m.ik.joints;
        prev_s = mid;
        clearance = ClearanceAt(prev);
        sol = SolveAt(from, to, s, &prev);
        sol_prev = prev;
      }
      Memo(s, sol_had_prev ? &sol_prev : nullptr, sol);
      if (usable(sol)) {
        prev = sol.ik.joints;
        have_prev = true;
        clearance = ClearanceAt(prev);
      }
      prev_s = s;
    }
    if (extra.empty()) return;
    for (double s : extra) samples.emplace_back(s, kCollisionProbe);
    SortSamples(samples);
  }

  // The subdivision solves the samples it walks; emitting them asks the same questions again
  // (same fraction, same previous joints, bit for bit): the answer is taken from it.
  struct Memoized {
    double s;
    bool has_previous;
    JointVector previous;
    ToolPoseSolution solution;
  };
  void Memo(double s, const JointVector* previous, const ToolPoseSolution& solution) {
    memo_.push_back(
        {s, previous != nullptr, previous != nullptr ? *previous : JointVector::Zero(), solution});
  }
  ToolPoseSolution Solved(const Pose& from, const Pose& to, double s, const JointVector* previous) {
    for (const Memoized& m : memo_) {
      if (m.s == s && m.has_previous == (previous != nullptr) &&
          (previous == nullptr ||
           std::memcmp(m.previous.data(), previous->data(), sizeof(double) * kNumJoints) == 0)) {
        return m.solution;
      }
    }
    return SolveAt(from, to, s, previous);
  }

  void SeedJoints(const JointVector& q) {
    joints_ = q;
    have_joints_ = true;
  }

  // The first pass: the line's clock only (the same arithmetic as Move), no samples.
  void Advance(const program::MachineState& after, const program::Step& step, int line) {
    const Pose to = PoseOf(after);
    const Pose from = have_pose_ ? current_ : to;
    time_s_ += PlanLine(from, to, after, step, line).rec.duration_s;
    current_ = to;
    have_pose_ = true;
  }

  // Resuming between two lines: the clock there, and the last move's end pose (the modal
  // state's axes) when a move came before.
  void Resume(double time_s, const program::MachineState& state, bool have_pose) {
    time_s_ = time_s;
    have_pose_ = have_pose;
    if (have_pose) current_ = PoseOf(state);
  }

  // What the executor carries into the next line, as bytes (chunk.h).
  void AppendCarry(std::string& out) const {
    const auto put = [&out](const void* p, std::size_t n) {
      out.append(static_cast<const char*>(p), n);
    };
    put(joints_.data(), sizeof(double) * kNumJoints);
    put(&have_joints_, sizeof have_joints_);
    put(&have_pose_, sizeof have_pose_);
    put(&time_s_, sizeof time_s_);
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
  SampleList samples_;
  std::vector<Memoized> memo_;  ///< this line's solutions from the collision subdivision
  std::unordered_map<std::string, int> body_index_;  ///< CollisionWorld::BodyNames() order
};

/// `T<n> M6` must mount the cell's head (else exec-head-mismatch).
bool HeadMatches(const program::Dialect& dialect, const program::MachineState& st,
                 const program::Block& block, const ExecuteOptions& options,
                 const std::string& file_name, DiagnosticSink& diagnostics);

/// What RunBlocks asks its caller around each block.
struct BlockHooks {
  /// Before a block is applied: false stops the run there (the block is not applied).
  std::function<bool(const program::Block&)> before;
  /// After a block was applied (and its move executed or, dry, its clock advanced).
  std::function<void(const program::Block&, const program::Step&)> after;
  bool dry = false;  ///< the clock only (the first pass): no samples, nothing sent to the sink
};

/// The executor's loop: reads blocks, applies them to the modal state, checks them (incomplete
/// pose, U backwards, a head the cell does not carry) and executes the moves. Returns false when
/// a hook stopped it; errors go to `diagnostics` (the run stops at the first).
bool RunBlocks(program::ProgramReader& reader, program::ModalState& state, Executor& exec,
               const program::Dialect& dialect, const std::string& file_name,
               const ExecuteOptions& options, DiagnosticSink& diagnostics,
               ExecutionSummary& summary, const BlockHooks& hooks);

}  // namespace stitchsim::sim::detail
