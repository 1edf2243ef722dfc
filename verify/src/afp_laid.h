#pragma once
// Private to verify: the material an AFP programme lays, line by line (docs/afp.md, "Tows";
// docs/report-format.md, the afp.* rules). A line lays tow t from its `from` pose to its `to`
// pose when it belongs to a course (`course != 0`), is a feed move and the head is lowered,
// and bit t - 1 of its tow mask is set. Its tool poses are interpolated as the executor moves
// (process::InterpolatePose) at most half a tow width apart, and the tow boundaries at each
// pose come from process::TowsAt, the model the ply planner places them with. One line is
// held at a time: memory does not grow with the programme. Shared by every afp.* rule; the
// first rule to ask for a line samples it, the others reuse it.

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/thinned.h"
#include "stitchsim/process/afp_tows.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/rule.h"

namespace stitchsim::verify::detail {

/// One tool pose along a laying line and the tow boundaries under it.
struct LaidPose {
  double fraction = 0.0;                                   ///< 0..1 along the line
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< part frame, mm
  process::TowCross cross;  ///< cross.ok false: the roller is off the surface here
};

/// One laying line as sampled.
struct LaidLine {
  int source_line = 0;
  int ply = 0;
  int course = 0;
  std::uint64_t tows = 0;  ///< the line's mask, limited to the head's tows
  /// Bits set beyond the head's tows (they lay nothing); 0 when all of them are set (M62 P0).
  std::uint64_t extra_tows = 0;
  std::vector<LaidPose> poses;  ///< fraction 0 .. 1, at most w / 2 apart
};

/// True when `line` lays material (course, feed move, head down, some tow set).
bool IsLayingLine(const trace::LineRecord& line);

/// True when tow `tow` (1-based) is set in `mask`.
inline bool TowLaid(std::uint64_t mask, int tow) { return ((mask >> (tow - 1)) & 1U) != 0; }

/// Receives the figures the afp.* rules measure per line and tow, as they measure them (the
/// verifier's laid material, Verifier::Laid()); set on the shared sampler, read by the rules.
class LaidFigures {
 public:
  virtual ~LaidFigures() = default;
  /// afp.steering_radius measured `radius_mm` at a vertex it reports on `line` for `tow`.
  virtual void SteeringRadius(int line, int tow, double radius_mm) = 0;
  /// afp.fiber_angle measured `deg` as the worst deviation of `tow` along `line`.
  virtual void FiberAngle(int line, int tow, double deg) = 0;
};

class LaidTows {
 public:
  LaidTows(const geom::Surface& surface, const process::TowLayout& layout);
  /// The sampled line when `line` lays material, else nullptr (and the pose chain resets).
  /// Asking again for the same line record returns the same sampling.
  const LaidLine* Sample(const trace::LineRecord& line);
  /// Samples `line`'s tool path as Sample does (poses at most w / 2 apart, the tow
  /// boundaries at each), whether or not it lays, into `out`; the held line is untouched.
  /// For rules that follow the path between laying lines (afp.restart_distance).
  void SamplePath(const trace::LineRecord& line, LaidLine& out) const;
  const process::TowLayout& Layout() const { return layout_; }
  const geom::Surface& Surface() const { return *surface_; }
  /// Where the rules hand their per-tow figures (nullptr: nowhere, the default).
  void SetFigures(LaidFigures* figures) { figures_ = figures; }
  LaidFigures* Figures() const { return figures_; }

 private:
  bool SameAsCached(const trace::LineRecord& line) const;
  // Fills `out` from `line`; `have_hint` / `hint_uv`: the previous pose's foot, carried on.
  void SampleInto(const trace::LineRecord& line, LaidLine& out, bool& have_hint,
                  Eigen::Vector2d& hint_uv) const;

  const geom::Surface* surface_;
  process::TowLayout layout_;
  double spacing_mm_;
  bool have_cached_ = false;
  bool cached_laying_ = false;
  trace::LineRecord cached_record_;
  LaidLine cached_;
  bool have_hint_ = false;
  Eigen::Vector2d hint_uv_ = Eigen::Vector2d::Zero();  ///< the previous pose's foot
  LaidFigures* figures_ = nullptr;
};

/// At most kMaxDrawnPoints points spread evenly over all added: when full, every other one
/// is dropped and only every 2nd, 4th, ... later one is kept (for the overview snapshot).
class ThinnedPoints {
 public:
  static constexpr std::size_t kMaxDrawnPoints = 1000;
  void Add(const Eigen::Vector3d& p) { points_.Add(p); }
  DrawnPoints Drawn(std::string label) const { return {std::move(label), points_.Items()}; }

 private:
  Thinned<Eigen::Vector3d> points_{kMaxDrawnPoints};
};

/// A tow's figure under a rule's limit, waiting for its line to be complete (one finding per
/// line: the worst tow of the line).
struct TowShortfall {
  double value = 0.0;  ///< the rule's unit
  int tow = 0;         ///< 1-based
  /// A second line the finding names (afp.min_tow_length, afp.restart_distance: the last line
  /// that laid the tow before its cut).
  int other_line = 0;
  /// Where the figure was measured (the tow's centre on the surface, part frame, mm): the
  /// finding's position.
  std::optional<Eigen::Vector3d> position_mm;
};

/// Keeps `s` for `line` unless a smaller value is kept there already.
void KeepSmallest(std::map<int, TowShortfall>& pending, int line, const TowShortfall& s);

/// Hands the pending lines up to `last_line` to `record(line, shortfall)` in line order and
/// forgets them.
template <typename RecordFn>
void TakeLinesUpTo(std::map<int, TowShortfall>& pending, int last_line, RecordFn&& record) {
  while (!pending.empty() && pending.begin()->first <= last_line) {
    const auto [line, s] = *pending.begin();
    pending.erase(pending.begin());
    record(line, s);
  }
}

/// The sampler every afp.* rule of one verifier shares.
std::shared_ptr<LaidTows> MakeLaidTows(const RuleContext& ctx);

/// Tow `tow`'s (1-based) centre on the surface at a pose: the surface point midway (in
/// (u, v)) between its two boundaries.
Eigen::Vector2d TowCentreUv(const process::TowCross& cross, int tow);

}  // namespace stitchsim::verify::detail
