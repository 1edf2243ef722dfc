#pragma once
// The robot's pose at the end of programme lines, for the HTML report's slider: a thinned
// set (every line whose number is a multiple of a power-of-two stride) plus every line the
// report points at (findings, worst values), so "go to this finding" poses the robot exactly.

#include <array>
#include <cstddef>
#include <set>
#include <vector>

#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

struct LinePose {
  int line = 0;                 ///< programme line (the pose at its end)
  std::array<float, 8> q{};     ///< joints, model order (rail m, angles rad)
  float time_s = 0.0f;          ///< programme time at the line's end (the executor's clock)
  std::array<float, 3> tool{};  ///< tool point, part frame, mm
};

class PoseTrack {
 public:
  /// Poses kept at most (about: lines the report points at are always kept).
  explicit PoseTrack(std::size_t max_poses) : max_(max_poses) {}

  /// Adds a line's end pose; lines ascending (a line given again replaces its pose).
  void Add(const LinePose& pose);
  /// Doubles the stride until at most max_poses remain, keeping `keep` lines and every line
  /// from `from_line` on (a serial run thins only what no later finding can point at).
  void Thin(const std::set<int>& keep, int from_line);
  /// Appends a track of later lines.
  void Append(const PoseTrack& later);
  const std::vector<LinePose>& Poses() const { return poses_; }
  std::size_t MaxPoses() const { return max_; }
  void SetMaxPoses(std::size_t max_poses) { max_ = max_poses; }

 private:
  std::size_t max_;
  long stride_ = 1;
  std::vector<LinePose> poses_;
};

/// The lines a verifier's report points at: every kept finding's and every rule's worst.
std::set<int> PointedLines(const verify::Verifier& verifier);

/// A trace sink that records line-end poses (samples at a line's end with usable joints).
class PoseRecorder : public trace::TraceSink {
 public:
  /// `verifier` (may be null): a serial run thins as it goes, keeping the lines it points at.
  PoseRecorder(PoseTrack& track, const verify::Verifier* verifier)
      : track_(track), verifier_(verifier) {}
  void OnLine(const trace::LineRecord&) override {}
  void OnSample(const trace::TraceSample& s) override;

 private:
  PoseTrack& track_;
  const verify::Verifier* verifier_;
};

}  // namespace stitchsim::run
