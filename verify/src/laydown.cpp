#include "stitchsim/verify/laydown.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "afp_laid.h"

namespace stitchsim::verify {
namespace {

constexpr double kJoinToleranceMm = 1e-3;    // a line starting farther from the last end: a jump
constexpr double kKgPerGramMm2PerM2 = 1e-9;  // mm^2 x g/m^2 -> kg

// Seconds for one piece from `v_in` to `v_out` at most `v_max`, accelerating at `a`.
double PieceTime(double d, double v_in, double v_out, double v_max, double a) {
  const double peak = std::sqrt((2.0 * a * d + v_in * v_in + v_out * v_out) / 2.0);
  if (peak <= v_max) return (2.0 * peak - v_in - v_out) / a;
  const double ramps_mm = (2.0 * v_max * v_max - v_in * v_in - v_out * v_out) / (2.0 * a);
  return (2.0 * v_max - v_in - v_out) / a + (d - ramps_mm) / v_max;
}

std::vector<FeedPiece> MovingPieces(const std::vector<FeedPiece>& pieces) {
  std::vector<FeedPiece> out;
  for (const FeedPiece& p : pieces)
    if (p.length_mm > 0.0 && p.feed_mm_s > 0.0) out.push_back(p);
  return out;
}

}  // namespace

double FeedTime(const std::vector<FeedPiece>& pieces) {
  double t = 0.0;
  for (const FeedPiece& p : MovingPieces(pieces)) t += p.length_mm / p.feed_mm_s;
  return t;
}

double RampedTime(const std::vector<FeedPiece>& all, double ramp_time_s) {
  if (ramp_time_s <= 0.0) return FeedTime(all);
  const std::vector<FeedPiece> p = MovingPieces(all);
  const std::size_t n = p.size();
  if (n == 0) return 0.0;
  // Node speeds (mm/s) at the pieces' ends: at rest at both ends, at most the slower
  // neighbour's feed between them; then what the ramps reach forwards and backwards.
  std::vector<double> v(n + 1, 0.0);
  for (std::size_t i = 1; i < n; ++i) v[i] = std::min(p[i - 1].feed_mm_s, p[i].feed_mm_s);
  auto reach = [&](double from, std::size_t i) {
    const double a = p[i].feed_mm_s / ramp_time_s;
    return std::sqrt(from * from + 2.0 * a * p[i].length_mm);
  };
  for (std::size_t i = 0; i < n; ++i) v[i + 1] = std::min(v[i + 1], reach(v[i], i));
  for (std::size_t i = n; i-- > 0;) v[i] = std::min(v[i], reach(v[i + 1], i));
  double t = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    t += PieceTime(p[i].length_mm, v[i], v[i + 1], p[i].feed_mm_s, p[i].feed_mm_s / ramp_time_s);
  }
  return t;
}

std::vector<FeedPiece> SlowZonePieces(const std::vector<FeedPiece>& lines,
                                      const std::vector<double>& events_mm, double zone_mm,
                                      double zone_feed_mm_s) {
  if (zone_mm <= 0.0 || zone_feed_mm_s <= 0.0 || events_mm.empty()) return lines;
  std::vector<double> line_ends;  // x at each line's end
  double total = 0.0;
  for (const FeedPiece& l : lines) line_ends.push_back(total += l.length_mm);
  std::vector<double> cuts{0.0, total};
  for (double e : line_ends) cuts.push_back(e);
  for (double e : events_mm) {
    cuts.push_back(std::clamp(e - zone_mm, 0.0, total));
    cuts.push_back(std::clamp(e + zone_mm, 0.0, total));
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<FeedPiece> out;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double mid = 0.5 * (cuts[k] + cuts[k + 1]);
    const auto line = std::upper_bound(line_ends.begin(), line_ends.end(), mid);
    if (line == line_ends.end()) break;
    double feed = lines[static_cast<std::size_t>(line - line_ends.begin())].feed_mm_s;
    const bool in_zone = std::any_of(events_mm.begin(), events_mm.end(),
                                     [&](double e) { return std::abs(mid - e) < zone_mm; });
    if (in_zone) feed = std::min(feed, zone_feed_mm_s);
    out.push_back({cuts[k + 1] - cuts[k], feed});
  }
  return out;
}

LaydownParams LaydownFor(const RuleContext& ctx) {
  const scene::Scene& scene = *ctx.scene;
  LaydownParams p;
  p.tows = scene.head.afp.tows;
  p.tow_width_mm = scene.head.afp.tow_width_mm;
  p.cut_add_feed_mm_s = scene.head.afp.cut_add_feed_mm_s;
  p.cut_add_zone_mm = scene.head.afp.cut_add_zone_mm;
  p.ramp_time_s = ctx.ramp_time_s;
  for (const scene::PlySpec& ply : scene.plies)
    p.areal_weight_g_m2.push_back(ply.areal_weight_g_m2);
  p.default_areal_weight_g_m2 = scene::kDefaultArealWeightGM2;
  return p;
}

LaydownMeter::LaydownMeter(LaydownParams params) : params_(std::move(params)) {}

double LaydownMeter::ArealWeight(int ply) const {
  const auto& w = params_.areal_weight_g_m2;
  return ply >= 1 && ply <= static_cast<int>(w.size()) ? w[static_cast<std::size_t>(ply) - 1]
                                                       : params_.default_areal_weight_g_m2;
}

void LaydownMeter::OnLine(const trace::LineRecord& line) {
  const std::uint64_t head_mask =
      params_.tows >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << params_.tows) - 1;
  const std::uint64_t mask = line.tows & head_mask;
  if (!detail::IsLayingLine(line) || mask == 0) {
    CloseRun();
    LaydownFigures& f = plies_[line.ply];
    f.off_part_s += line.duration_s;
    f.off_part_timed_s += line.timed_duration_s > 0.0 ? line.timed_duration_s : line.duration_s;
    return;
  }
  if (open_ && (line.course != course_ || line.ply != ply_ ||
                (line.from.translation() - end_).norm() > kJoinToleranceMm)) {
    CloseRun();
  }
  if (!open_) {
    open_ = true;
    ply_ = line.ply;
    course_ = line.course;
    mask_ = 0;
    x_ = 0.0;
    lines_.clear();
    events_.clear();
    tow_start_.assign(static_cast<std::size_t>(params_.tows), 0.0);
    plies_[ply_];
  }
  for (int t = 1; t <= params_.tows; ++t) {
    const bool was = detail::TowLaid(mask_, t), now = detail::TowLaid(mask, t);
    if (was != now) Event(x_, now, t);
  }
  mask_ = mask;
  const double length = (line.to.translation() - line.from.translation()).norm();
  lines_.push_back({length, line.feed_mm_per_min / 60.0});
  x_ += length;
  end_ = line.to.translation();
}

void LaydownMeter::Event(double x, bool add, int tow) {
  events_.push_back(x);
  LaydownFigures& f = plies_[ply_];
  double& start = tow_start_[static_cast<std::size_t>(tow) - 1];
  if (add) {
    ++f.tows_added;
    start = x;
    return;
  }
  ++f.tows_cut;
  const double length = x - start;
  f.tow_length_mm += length;
  f.material_kg += length * params_.tow_width_mm * ArealWeight(ply_) * kKgPerGramMm2PerM2;
  f.shortest_tow_mm = std::min(f.shortest_tow_mm.value_or(length), length);
}

void LaydownMeter::CloseRun() {
  if (!open_) return;
  for (int t = 1; t <= params_.tows; ++t)
    if (detail::TowLaid(mask_, t)) Event(x_, false, t);
  const std::vector<FeedPiece> pieces =
      SlowZonePieces(lines_, events_, params_.cut_add_zone_mm, params_.cut_add_feed_mm_s);
  LaydownFigures& f = plies_[ply_];
  f.laid_path_mm += x_;
  f.laydown_s += FeedTime(pieces);
  f.laydown_timed_s += RampedTime(pieces, params_.ramp_time_s);
  open_ = false;
}

void LaydownMeter::Finish() { CloseRun(); }

std::vector<LaydownFigures> LaydownMeter::Figures() const {
  std::vector<LaydownFigures> out;
  LaydownFigures whole;
  for (const auto& [ply, f] : plies_) {
    if (ply != 0) {
      out.push_back(f);
      out.back().ply = ply;
    }
    whole.laid_path_mm += f.laid_path_mm;
    whole.laydown_s += f.laydown_s;
    whole.laydown_timed_s += f.laydown_timed_s;
    whole.off_part_s += f.off_part_s;
    whole.off_part_timed_s += f.off_part_timed_s;
    whole.tow_length_mm += f.tow_length_mm;
    whole.material_kg += f.material_kg;
    whole.tows_added += f.tows_added;
    whole.tows_cut += f.tows_cut;
    if (f.shortest_tow_mm) {
      whole.shortest_tow_mm =
          std::min(whole.shortest_tow_mm.value_or(*f.shortest_tow_mm), *f.shortest_tow_mm);
    }
  }
  out.push_back(whole);
  for (LaydownFigures& f : out) {
    const double hours = (f.laydown_timed_s + f.off_part_timed_s) / 3600.0;
    f.rate_kg_h = hours > 0.0 ? f.material_kg / hours : 0.0;
  }
  return out;
}

}  // namespace stitchsim::verify
