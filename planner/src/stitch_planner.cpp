#include "stitchsim/planner/stitch_planner.h"

#include <cmath>

#include "stitchsim/common/limits.h"
#include "stitchsim/geom/rotation.h"

namespace stitchsim::planner {

std::optional<Mode> ParseMode(std::string_view text) {
  if (text == "coupled") return Mode::kCoupled;
  if (text == "decoupled") return Mode::kDecoupled;
  if (text == "auto") return Mode::kAuto;
  return std::nullopt;
}

std::string_view ToString(Mode mode) {
  switch (mode) {
    case Mode::kCoupled:
      return "coupled";
    case Mode::kDecoupled:
      return "decoupled";
    case Mode::kAuto:
      return "auto";
  }
  return "auto";
}

StitchPathPlanner::StitchPathPlanner(const scene::Scene& scene, const scene::PathSpec& path)
    : scene_(&scene), spec_(&path), path_(*scene.surface, *path.curve) {}

std::optional<StitchPathPlanner> StitchPathPlanner::Create(const scene::Scene& scene,
                                                           const scene::PathSpec& path,
                                                           const StitchPlanOptions& options,
                                                           DiagnosticSink& sink) {
  StitchPathPlanner p(scene, path);
  const double nominal = scene.StitchLengthMm(options.nominal_stitch_length_mm);
  if (!(nominal > 0.0) || !std::isfinite(nominal)) {
    sink.Error("plan-bad-stitch-length", path.where,
               "nominal stitch length must be a positive finite number");
    return std::nullopt;
  }
  if (p.path_.Length() / nominal > static_cast<double>(limits::kMaxStitchesPerPath) + 1.0) {
    sink.Error("plan-too-many-stitches", path.where,
               "path '" + path.name + "' (" + std::to_string(p.path_.Length()) +
                   " mm) would take more than " + std::to_string(limits::kMaxStitchesPerPath) +
                   " stitches of " + std::to_string(nominal) +
                   " mm, the limit for one path (docs/limits.md)");
    return std::nullopt;
  }
  const auto n = geom::StitchCount(p.path_.Length(), nominal);
  if (!n) {
    sink.Error("plan-path-too-short", path.where,
               "path '" + path.name + "' is " + std::to_string(p.path_.Length()) +
                   " mm long, shorter than one stitch of " + std::to_string(nominal) + " mm");
    return std::nullopt;
  }
  p.mode_ = options.mode;
  p.evaluate_coupled_ = options.mode == Mode::kAuto || options.evaluate_coupled;
  p.progress_ = options.progress;
  p.count_ = *n;
  p.stitch_length_mm_ = p.path_.Length() / *n;
  p.nominal_stitch_length_mm_ = nominal;
  p.process_ = process::MakeProcessModel(scene, p.stitch_length_mm_);
  p.limits_ = process::NeedleLimitsFrom(scene.limits);
  p.current_ = p.path_.AtArcLength(0.0);
  p.following_ = p.path_.AtArcLengthFrom(p.current_, p.stitch_length_mm_);
  p.current_frame_ = p.FrameAt(p.current_, p.following_);
  if (!p.current_frame_.matrix().allFinite()) {
    sink.Error("plan-degenerate-frame", path.where,
               "path '" + path.name + "': the first stitch runs along the surface normal");
    return std::nullopt;
  }
  p.start_pose_ = p.current_frame_;
  return p;
}

Eigen::Isometry3d StitchPathPlanner::FrameAt(const geom::PathPoint& at,
                                             const geom::PathPoint& next) const {
  Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
  f.translation() = at.position;
  const auto r = geom::FrameFromNormalAndDirection(at.normal, next.position - at.position);
  if (!r) {
    f.matrix().setConstant(std::nan(""));
    return f;
  }
  f.linear() = *r;
  return f;
}

Eigen::Isometry3d StitchPathPlanner::EndFrame() const {
  // After the last stitch: a closed path turns back to its first frame. An open one takes
  // the frame the next stitch would have if the path went on (its last segment extended by
  // one stitch), so the last stitch is judged like the ones before it.
  if (path_.Closed()) {
    Eigen::Isometry3d f = start_pose_;
    f.translation() = following_.position;
    return f;
  }
  const std::size_t last = spec_->curve->SegmentCount() - 1;
  const geom::CurveSegment& seg = spec_->curve->Segment(last);
  const geom::Surface& surface = *scene_->surface;
  const double speed = (surface.Jacobian(seg.At(1.0)) * seg.Derivative(1.0)).norm();
  geom::PathPoint virtual_next = following_;
  if (speed > 0) {
    const Eigen::Vector2d uv = seg.At(1.0 + stitch_length_mm_ / speed);
    virtual_next.uv = uv;
    virtual_next.position = surface.Point(uv);
  }
  Eigen::Isometry3d f = FrameAt(following_, virtual_next);
  if (!f.matrix().allFinite()) {
    f = current_frame_;
    f.translation() = following_.position;
  }
  return f;
}

bool StitchPathPlanner::Next(PlannedStitch& out) {
  if (next_index_ > count_) return false;
  const int i = next_index_++;
  out.index = i;
  out.start = current_frame_;
  out.arc_length_end_mm = i * stitch_length_mm_;
  // Frame of the next stitch at this stitch's end point.
  geom::PathPoint after;
  Eigen::Isometry3d end_frame;
  if (i < count_) {
    // Sequential: searched from this stitch's end point, one stitch back.
    after =
        path_.AtArcLengthFrom(following_, std::min((i + 1) * stitch_length_mm_, path_.Length()));
    end_frame = FrameAt(following_, after);
    if (!end_frame.matrix().allFinite()) end_frame = EndFrame();
  } else {
    end_frame = EndFrame();
  }
  if (i == count_ && path_.Closed()) end_frame.translation() = start_pose_.translation();
  out.end = end_frame;
  out.segment_label = spec_->curve->Label(path_.SegmentAtArcLength((i - 0.5) * stitch_length_mm_));
  if (evaluate_coupled_) {
    // The drift of a linear + slerp window grows with the phase: 8 samples, the window end
    // included, decide exactly as the verifier's fine sampling would.
    out.coupled = process::EvaluateCoupledStitch(process_, out.start, out.end, 8);
    out.exceeded_limit = process::FirstExceededLimit(out.coupled, limits_);
  } else {
    out.coupled = process::WindowMetrics{};
    out.exceeded_limit.clear();
  }
  out.rotation_rad = geom::AngleBetween(out.start.linear(), out.end.linear());
  switch (mode_) {
    case Mode::kCoupled:
      out.decoupled = false;
      break;
    case Mode::kDecoupled:
      out.decoupled = true;
      break;
    case Mode::kAuto:
      out.decoupled = !out.exceeded_limit.empty();
      break;
  }
  current_ = following_;
  current_frame_ = end_frame;
  if (i < count_) following_ = after;
  if (progress_) progress_(i, count_);
  return true;
}

std::vector<PlannedStitch> CollectStitches(StitchPathPlanner& planner) {
  std::vector<PlannedStitch> out;
  out.reserve(static_cast<std::size_t>(planner.StitchCount()));
  PlannedStitch s;
  while (planner.Next(s)) out.push_back(s);
  return out;
}

}  // namespace stitchsim::planner
