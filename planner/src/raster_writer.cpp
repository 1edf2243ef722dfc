// A raster plan as programme text: the opening, per head section M60 P<head>, per pass its
// transit (needles out; retract, fly and lower for a jump), M10 and one coupled G1 per
// stitch, user code blocks at their events, the ending.
#include <algorithm>
#include <cstdio>
#include <ostream>

#include "detail/program_text.h"
#include "detail/raster_rows.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/raster_planner.h"
#include "stitchsim/program/identity.h"

namespace stitchsim::planner {
namespace {

using detail::Num;

// Traverse speed and retract / lower time for the time estimate (the head spec has none).
constexpr double kTraverseMmPerMin = 20000.0;
constexpr double kRetractLowerS = 0.5;

class RasterWriter {
 public:
  RasterWriter(const RasterPlan& plan, const scene::Scene& scene, const program::Dialect& dialect,
               std::ostream& out, const PlanProgress& progress)
      : plan_(plan),
        scene_(scene),
        surface_(*scene.surface),
        dialect_(dialect),
        stepper_(surface_, plan.pitch_mm),
        w_(out, dialect),
        pose_words_(dialect),
        progress_(progress) {
    const auto& st = scene.head.stitch;
    feed_mm_min_ = st.stitch_rate_per_min * plan.pitch_mm;
    stitch_time_s_ = 60.0 / st.stitch_rate_per_min;
    sum_.head_stitches.assign(static_cast<std::size_t>(plan.heads), 0);
  }

  RasterSummary Write() {
    program::ProgramIdentity id;
    id.scene = scene_.name;
    id.head = scene_.head.name;
    id.raster = std::string(ToString(plan_.strategy));
    id.stitch_length_mm = plan_.pitch_mm;
    id.row_spacing_mm = plan_.row_spacing_mm;
    id.heads = plan_.heads;
    id.stitches = plan_.stitches;
    detail::WriteOpening(w_, b_, dialect_, program::WriteIdentity(id), scene_.head.tool_number);
    for (const RasterSection& section : plan_.sections) {
      if (plan_.head_sections) {
        StitchingOff();
        b_.Clear();
        b_.m_codes = {dialect_.m.head_section};
        b_.param = section.head;
        b_.comment = "head " + std::to_string(section.head);
        w_.Write(b_);
      }
      sum_.bays += static_cast<long>(section.regions);
      for (const RasterPass& pass : section.passes) Pass(pass, section.head);
    }
    StitchingOff();
    detail::WriteEnding(w_, b_, dialect_);
    if (progress_) progress_(rows_, rows_);
    return sum_;
  }

 private:
  void MLine(std::initializer_list<int> codes) {
    b_.Clear();
    b_.m_codes = codes;
    w_.Write(b_);
  }
  void StitchingOff() {
    if (!stitching_) return;
    MLine({dialect_.m.stitch_off});
    stitching_ = false;
  }
  void UserBlock(const UserCodeBlock& u) {
    b_.Clear();
    b_.m_codes = u.m_codes;
    b_.param = u.param;
    w_.Write(b_);
    ++sum_.user_blocks;
  }
  void UserBlocksAt(UserCodeBlock::Event event) {
    for (const UserCodeBlock& u : plan_.library.blocks) {
      if (u.event == event) UserBlock(u);
    }
  }
  void Rapid(const Eigen::Vector3d& p, const Eigen::Matrix3d& rotation) {
    b_.Clear();
    b_.motion = program::Motion::kRapid;
    pose_words_.Set(b_, p, rotation);
    b_[program::Axis::kDrive] = drive_;
    b_[program::Axis::kPathLength] = drive_;
    w_.Write(b_);
    ++sum_.motion_lines;
  }
  // A half turn (the row direction reverses) in two quarter turns about the tool z axis,
  // alternating sense, so the wrist unwinds instead of winding up and the interpolation
  // between the end orientations is never ambiguous.
  void QuarterTurnAt(const Eigen::Vector3d& p, const RasterTransit& t) {
    if (!t.quarter_turn) return;
    Rapid(p, pose_words_.Rotation() *
                 Eigen::AngleAxisd(0.5 * t.turn_sign * kPi, Eigen::Vector3d::UnitZ())
                     .toRotationMatrix());
  }
  // To the start `to` of a pass (tool frame `r`), the needles out.
  void Transit(const std::optional<RasterTransit>& t, const Eigen::Vector3d& to,
               const Eigen::Matrix3d& r) {
    StitchingOff();
    if (t && t->jump) {
      UserBlocksAt(UserCodeBlock::Event::kBeforeJump);
      MLine({dialect_.m.head_retract});
      ++sum_.jumps;
      sum_.traverse_s += kRetractLowerS;
      // Up along the normals, across, down.
      const Eigen::Vector3d up = pos_ + t->lift_mm * pose_words_.Rotation().col(2);
      const Eigen::Vector3d over = to + t->lift_mm * r.col(2);
      Rapid(up, pose_words_.Rotation());
      QuarterTurnAt(up, *t);
      Rapid(over, r);
      Rapid(to, r);
      sum_.traverse_s += (2 * t->lift_mm + (over - up).norm()) / kTraverseMmPerMin * 60.0;
      MLine({dialect_.m.head_lower});
    } else {
      if (t) {
        ++sum_.turns;
        QuarterTurnAt(pos_, *t);
      }
      Rapid(to, r);
      if (t) sum_.traverse_s += (to - pos_).norm() / kTraverseMmPerMin * 60.0;
    }
    pos_ = to;
  }
  void Stitch(double u, double v, double dir, int head) {
    drive_ += plan_.pitch_mm;
    const Eigen::Vector3d p = surface_.Point({u, v});
    b_.Clear();
    b_.motion = program::Motion::kFeed;
    pose_words_.Set(b_, p, detail::StitchFrame(surface_, u, v, dir));
    b_[program::Axis::kDrive] = drive_;
    b_[program::Axis::kPathLength] = drive_;
    if (!feed_written_) b_.feed = feed_mm_min_;
    feed_written_ = true;
    w_.Write(b_);
    ++sum_.motion_lines;
    ++sum_.stitches;
    ++sum_.head_stitches[static_cast<std::size_t>(head - 1)];
    sum_.stitching_s += stitch_time_s_;
    pos_ = p;
    for (const UserCodeBlock& ub : plan_.library.blocks) {
      if (ub.event == UserCodeBlock::Event::kEveryStitches &&
          sum_.stitches % ub.every_stitches == 0) {
        UserBlock(ub);
      }
    }
  }
  void Pass(const RasterPass& pass, int head) {
    const double dir = pass.direction;
    const double v = pass.piece.v_mm;
    double u = dir > 0 ? pass.piece.u_begin_mm : pass.piece.u_end_mm;
    Transit(pass.transit, surface_.Point({u, v}), detail::StitchFrame(surface_, u, v, dir));
    if (pass.row_start) {
      ++sum_.rows;
      UserBlocksAt(UserCodeBlock::Event::kRowStart);
    }
    MLine({dialect_.m.stitch_on});
    stitching_ = true;
    for (long k = 0; k < pass.stitches; ++k) {
      u = stepper_.Next(u, v, dir);
      Stitch(u, v, dir, head);
    }
    if (progress_) {
      rows_done_ += detail::kProgressWriteShare;
      progress_(std::min(rows_done_, rows_), rows_);
    }
  }

  const RasterPlan& plan_;
  const scene::Scene& scene_;
  const geom::Surface& surface_;
  const program::Dialect& dialect_;
  const detail::RowStepper stepper_;
  program::ProgramWriter w_;
  program::Block b_;
  detail::PoseWords pose_words_;
  const PlanProgress& progress_;
  const double rows_ = static_cast<double>(plan_.row_pieces);  // progress: all row pieces
  // Rows done when writing starts: PlanRaster counted and passed every piece.
  double rows_done_ = rows_ * (detail::kProgressCountShare + detail::kProgressPassShare);
  RasterSummary sum_;
  double feed_mm_min_ = 0.0;
  double stitch_time_s_ = 0.0;
  double drive_ = 0.0;  // U = V: stitched length so far
  bool stitching_ = false;
  bool feed_written_ = false;
  Eigen::Vector3d pos_ = Eigen::Vector3d::Zero();
};

}  // namespace

RasterSummary WriteRasterProgram(const RasterPlan& plan, const scene::Scene& scene,
                                 const program::Dialect& dialect, std::ostream& out,
                                 const PlanProgress& progress) {
  return RasterWriter(plan, scene, dialect, out, progress).Write();
}

std::optional<RasterSummary> WriteRasterProgram(const scene::Scene& scene,
                                                const RasterOptions& options,
                                                const program::Dialect& dialect, std::ostream& out,
                                                DiagnosticSink& sink) {
  const std::optional<RasterPlan> plan = PlanRaster(scene, options, sink);
  if (!plan) return std::nullopt;
  return WriteRasterProgram(*plan, scene, dialect, out, options.progress);
}

}  // namespace stitchsim::planner
