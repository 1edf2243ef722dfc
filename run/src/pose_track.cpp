#include "stitchsim/run/pose_track.h"

#include <algorithm>
#include <limits>

namespace stitchsim::run {

void PoseTrack::Add(const LinePose& pose) {
  if (!poses_.empty() && poses_.back().line == pose.line) {
    poses_.back() = pose;
    return;
  }
  poses_.push_back(pose);
}

void PoseTrack::Thin(const std::set<int>& keep, int from_line) {
  while (poses_.size() > max_) {
    const std::size_t before = poses_.size();
    stride_ *= 2;
    std::erase_if(poses_, [&](const LinePose& p) {
      return p.line < from_line && p.line % stride_ != 0 && keep.count(p.line) == 0;
    });
    if (poses_.size() == before && stride_ > (1L << 40)) break;  // all kept on purpose
  }
}

void PoseTrack::Append(const PoseTrack& later) {
  for (const LinePose& p : later.poses_) {
    if (poses_.empty() || p.line > poses_.back().line) poses_.push_back(p);
  }
  stride_ = std::max(stride_, later.stride_);
}

std::set<int> PointedLines(const verify::Verifier& verifier) {
  std::set<int> lines;
  for (const auto& rule : verifier.Rules()) {
    const verify::RuleSummary& s = rule->Summary();
    if (s.worst_line > 0) lines.insert(s.worst_line);
    for (const verify::Finding& f : s.findings) lines.insert(f.line);
  }
  return lines;
}

void PoseRecorder::OnSample(const trace::TraceSample& s) {
  if (s.event != trace::SampleEvent::kLineEnd || !trace::JointsUsable(s)) return;
  LinePose p;
  p.line = s.source_line;
  for (int j = 0; j < 8; ++j) p.q[static_cast<std::size_t>(j)] = static_cast<float>(s.joints[j]);
  p.time_s = static_cast<float>(s.time_s);
  const Eigen::Vector3d& t = s.tool_part.translation();
  p.tool = {static_cast<float>(t.x()), static_cast<float>(t.y()), static_cast<float>(t.z())};
  track_.Add(p);
  // A serial run: thin now and then, never the last lines (a needle window's finding may
  // still come for them).
  if (verifier_ != nullptr && track_.Poses().size() > 2 * track_.MaxPoses()) {
    constexpr int kRecentLines = 4096;
    track_.Thin(PointedLines(*verifier_), s.source_line - kRecentLines);
  }
}

}  // namespace stitchsim::run
