#include "afp_laid.h"

#include <algorithm>
#include <cmath>

#include "stitchsim/process/stitch_cycle.h"

namespace stitchsim::verify::detail {
namespace {

// A line longer than this many samples is sampled at this count (a 10 m line at w = 6.35).
constexpr int kMaxPosesPerLine = 4000;

}  // namespace

bool IsLayingLine(const trace::LineRecord& line) {
  return line.course != 0 && !line.rapid && !line.head_retracted && line.tows != 0 &&
         !line.over_sample_limit;
}

LaidTows::LaidTows(const geom::Surface& surface, const process::TowLayout& layout)
    : surface_(&surface), layout_(layout), spacing_mm_(0.5 * layout.width_mm) {}

bool LaidTows::SameAsCached(const trace::LineRecord& line) const {
  const trace::LineRecord& c = cached_record_;
  return have_cached_ && c.source_line == line.source_line && c.tows == line.tows &&
         c.course == line.course && c.ply == line.ply && c.rapid == line.rapid &&
         c.head_retracted == line.head_retracted && c.from.matrix() == line.from.matrix() &&
         c.to.matrix() == line.to.matrix();
}

const LaidLine* LaidTows::Sample(const trace::LineRecord& line) {
  if (SameAsCached(line)) return cached_laying_ ? &cached_ : nullptr;
  have_cached_ = true;
  cached_record_ = line;
  cached_laying_ = IsLayingLine(line);
  if (!cached_laying_) {
    have_hint_ = false;
    return nullptr;
  }
  if (cached_.course != line.course || cached_.ply != line.ply) have_hint_ = false;
  SampleInto(line, cached_, have_hint_, hint_uv_);
  return &cached_;
}

void LaidTows::SamplePath(const trace::LineRecord& line, LaidLine& out) const {
  bool have_hint = false;
  Eigen::Vector2d hint = Eigen::Vector2d::Zero();
  SampleInto(line, out, have_hint, hint);
}

void LaidTows::SampleInto(const trace::LineRecord& line, LaidLine& out, bool& have_hint,
                          Eigen::Vector2d& hint_uv) const {
  const std::uint64_t head_tows = process::AllTows(layout_);
  out.source_line = line.source_line;
  out.ply = line.ply;
  out.course = line.course;
  out.tows = line.tows & head_tows;
  // M62 P0 sets every bit (the modal state does not know the head): all bits beyond the
  // head's tows set is "every tow", not a mistake.
  const std::uint64_t beyond = line.tows & ~head_tows;
  out.extra_tows = beyond == ~head_tows ? 0 : beyond;
  out.poses.clear();
  const double length = (line.to.translation() - line.from.translation()).norm();
  const int steps =
      std::clamp(static_cast<int>(std::ceil(length / spacing_mm_)), 1, kMaxPosesPerLine - 1);
  out.poses.reserve(static_cast<std::size_t>(steps) + 1);
  for (int i = 0; i <= steps; ++i) {
    LaidPose p;
    p.fraction = static_cast<double>(i) / steps;
    p.tool = process::InterpolatePose(line.from, line.to, p.fraction);
    p.cross = process::TowsAt(*surface_, p.tool, layout_, have_hint ? &hint_uv : nullptr);
    have_hint = p.cross.ok;
    if (p.cross.ok) hint_uv = p.cross.centre_uv;
    out.poses.push_back(std::move(p));
  }
}

std::shared_ptr<LaidTows> MakeLaidTows(const RuleContext& ctx) {
  return std::make_shared<LaidTows>(*ctx.scene->surface, process::TowLayoutOf(ctx.scene->head));
}

Eigen::Vector2d TowCentreUv(const process::TowCross& cross, int tow) {
  const auto t = static_cast<std::size_t>(tow);
  return 0.5 * (cross.boundary_uv[t - 1] + cross.boundary_uv[t]);
}

void KeepSmallest(std::map<int, TowShortfall>& pending, int line, const TowShortfall& s) {
  auto [it, added] = pending.try_emplace(line, s);
  if (!added && s.value < it->second.value) it->second = s;
}

}  // namespace stitchsim::verify::detail
