// A planned stitch path as programme text, streaming: per stitch its moves (MovesOf), their
// time (AddStitchTime), then their lines. The opening, the start line, M10 ... M11, the ending.
#include <algorithm>
#include <ostream>

#include "detail/program_text.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::planner {
namespace {

using program::Axis;

// The lines of a stitch programme; the feed is written on the first feed line only.
class StitchTextWriter {
 public:
  StitchTextWriter(std::ostream& out, const program::Dialect& dialect, double feed_mm_min)
      : dialect_(dialect), w_(out, dialect), pose_words_(dialect), feed_mm_min_(feed_mm_min) {}

  // The opening, then the first stitch's pose with both cumulative axes at zero, stitching on.
  void Open(const program::ProgramHeader& header, int tool_number, const Eigen::Isometry3d& start) {
    detail::WriteOpening(w_, b_, dialect_, header, tool_number);
    b_.Clear();
    b_.motion = program::Motion::kRapid;
    pose_words_.Set(b_, start);
    b_[Axis::kDrive] = 0.0;
    b_[Axis::kPathLength] = 0.0;
    b_.comment = "start";
    w_.Write(b_);
    b_.Clear();
    b_.m_codes = {dialect_.m.stitch_on};
    w_.Write(b_);
  }
  void Write(const StitchMoves& m) {
    if (m.decoupled) {
      Line(program::Motion::kFeed, m.translate, m.drive_mm);
      Line(program::Motion::kNone, m.end, m.drive_mm);  // modal: still a feed
    } else {
      Line(program::Motion::kFeed, m.end, m.drive_mm);
    }
  }
  void Close() {
    b_.Clear();
    b_.m_codes = {dialect_.m.stitch_off};
    w_.Write(b_);
    detail::WriteEnding(w_, b_, dialect_);
  }

 private:
  void Line(program::Motion motion, const Eigen::Isometry3d& pose, double drive) {
    b_.Clear();
    b_.motion = motion;
    pose_words_.Set(b_, pose);
    b_[Axis::kDrive] = drive;
    b_[Axis::kPathLength] = drive;
    if (motion == program::Motion::kFeed && !feed_written_) {
      b_.feed = feed_mm_min_;
      feed_written_ = true;
    }
    w_.Write(b_);
  }

  const program::Dialect& dialect_;
  program::ProgramWriter w_;
  program::Block b_;
  detail::PoseWords pose_words_;
  double feed_mm_min_ = 0.0;
  bool feed_written_ = false;
};

}  // namespace

StitchMoves MovesOf(const PlannedStitch& stitch, double stitch_length_mm) {
  StitchMoves m;
  m.decoupled = stitch.decoupled;
  m.end = stitch.end;
  if (m.decoupled) {
    m.translate = stitch.start;
    m.translate.translation() = stitch.end.translation();
  }
  m.drive_mm = stitch.index * stitch_length_mm;
  m.rotation_rad = stitch.rotation_rad;
  return m;
}

StitchTiming StitchTimingOf(const scene::StitchProcessSpec& spec) {
  StitchTiming t;
  t.stitch_time_s = 60.0 / spec.stitch_rate_per_min;
  t.rotation_speed_rad_s = spec.rotation_speed_deg_s / kRadToDeg;
  t.settle_time_s = spec.settle_time_s;
  return t;
}

void AddStitchTime(const StitchMoves& moves, const StitchTiming& timing, CycleTime& time) {
  const double rotation_s = moves.rotation_rad / timing.rotation_speed_rad_s;
  if (moves.decoupled) {
    time.stitching_s += timing.stitch_time_s;
    time.rotation_s += rotation_s + timing.settle_time_s;
  } else {
    time.stitching_s += std::max(timing.stitch_time_s, rotation_s);
  }
}

ProgramSummary WriteStitchProgram(StitchPathPlanner& planner, const scene::Scene& scene,
                                  const std::string& path_name, const program::Dialect& dialect,
                                  std::ostream& out) {
  const double l = planner.StitchLengthMm();
  ProgramSummary summary;
  summary.mode = planner.GetMode();
  summary.stitch_length_mm = l;
  summary.nominal_stitch_length_mm = planner.NominalStitchLengthMm();
  summary.path_length_mm = planner.PathLengthMm();

  program::ProgramIdentity id;
  id.scene = scene.name;
  id.head = scene.head.name;
  id.path = path_name;
  id.mode = std::string(ToString(planner.GetMode()));
  id.stitch_length_mm = l;
  id.stitches = planner.StitchCount();
  const StitchTiming timing = StitchTimingOf(scene.head.stitch);
  StitchTextWriter text(out, dialect, scene.head.stitch.stitch_rate_per_min * l);
  text.Open(program::WriteIdentity(id), scene.head.tool_number, planner.StartPose());
  summary.motion_lines = 1;  // the start line
  PlannedStitch s;
  while (planner.Next(s)) {
    const StitchMoves moves = MovesOf(s, l);
    AddStitchTime(moves, timing, summary.time);
    text.Write(moves);
    ++summary.stitches;
    if (moves.decoupled) ++summary.decoupled;
    summary.motion_lines += moves.Lines();
  }
  text.Close();
  return summary;
}

}  // namespace stitchsim::planner
