// The laid material as ribbons on the overview (detail/afp_ribbons.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "stitchsim/run/laid_ribbons.h"

namespace stitchsim::run {
namespace {

// The laid tows of `mask` in group [first, last] (1-based head tows): the first and last laid
// one, or {0, 0} when none is.
std::pair<int, int> LaidSpan(std::uint64_t mask, int first, int last) {
  int a = 0, b = 0;
  for (int t = first; t <= last; ++t) {
    if (((mask >> (t - 1)) & 1U) == 0) continue;
    if (a == 0) a = t;
    b = t;
  }
  return {a, b};
}

// Ribbon segments of every line (but those of the plies in `hidden`) with tows merged `k` at a
// time, all stations drawn.
std::size_t SegmentsAt(const verify::LaidMaterial& laid, int k, const std::set<int>& hidden) {
  std::size_t n = 0;
  for (const verify::LaidStrip& s : laid.strips) {
    if (s.station_count < 2 || hidden.count(s.ply) != 0) continue;
    for (int first = 1; first <= laid.tows; first += k) {
      if (LaidSpan(s.tows, first, std::min(laid.tows, first + k - 1)).first > 0) {
        n += s.station_count - 1;
      }
    }
  }
  return n;
}

bool Finite(const Eigen::Vector3f& p) { return p.allFinite(); }

// A ribbon being drawn: the group's laid span, the stations seen, the last one not kept.
struct RibbonRun {
  RenderRequest::PointSet set;
  int a = 0, b = 0;  // first and last laid tow (0: none)
  std::size_t seen = 0;
  Eigen::Vector3d pending = Eigen::Vector3d::Zero(), pending_normal = Eigen::Vector3d::UnitZ();
  bool have_pending = false;
};

void Keep(RibbonRun& r, const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  r.set.points_part_mm.push_back(point);
  r.set.normals_part.push_back(normal);
  r.have_pending = false;
}

}  // namespace

std::array<float, 4> PlyColour(int ply) {
  // 12 colours told apart in print and from the grey part (8-bit RGB), repeated past 12 plies.
  static constexpr std::array<unsigned char, 36> kPalette = {
      31, 119, 180, 255, 127, 14, 44, 160, 44,  148, 103, 189, 140, 86,  75,  227, 119, 194,
      0,  128, 128, 188, 189, 34, 23, 190, 207, 0,   51,  140, 153, 230, 102, 128, 0,   64};
  const std::size_t i = 3 * (static_cast<std::size_t>(std::max(0, ply - 1)) % 12);
  return {kPalette[i] / 255.0F, kPalette[i + 1] / 255.0F, kPalette[i + 2] / 255.0F, 1.0F};
}

LaidRibbons MakeLaidRibbons(const verify::LaidMaterial& laid, std::size_t budget, double base_mm) {
  LaidRibbons out;
  if (laid.strips.empty() || laid.tows <= 0) return out;
  std::map<int, std::size_t> ply_order;  // ply -> order of first appearance
  std::vector<int> stack;                // the plies in that order
  for (const verify::LaidStrip& s : laid.strips) {
    if (ply_order.emplace(s.ply, ply_order.size()).second) stack.push_back(s.ply);
  }
  std::set<int> hidden;
  int k = 1;
  while (k < laid.tows && SegmentsAt(laid, k, hidden) > budget) k *= 2;
  k = std::min(k, laid.tows);
  out.tows_per_ribbon = k;
  // Still over: the lowest plies, under the later ones, are left out before any station is
  // (a ribbon thinned along a curved part cuts chords through the plies round it).
  for (std::size_t i = 0; i + 1 < stack.size() && SegmentsAt(laid, k, hidden) > budget; ++i) {
    hidden.insert(stack[i]);
    out.hidden_plies.push_back(stack[i]);
  }
  const std::size_t at_k = SegmentsAt(laid, k, hidden);
  out.station_step =
      at_k > budget ? static_cast<int>((at_k + budget - 1) / std::max<std::size_t>(1, budget)) : 1;
  // One ribbon per run of lines of a course that join (a line starting on the station the
  // previous one ended on) with the same laid span in the group; every station_step-th
  // station of the run drawn, and its last.
  const std::size_t groups = static_cast<std::size_t>((laid.tows + k - 1) / k);
  std::vector<RibbonRun> runs(groups);
  auto close = [&](RibbonRun& r) {
    if (r.have_pending) Keep(r, r.pending, r.pending_normal);
    if (r.set.points_part_mm.size() >= 2) {
      out.segments += r.set.points_part_mm.size() - 1;
      out.sets.push_back(std::move(r.set));
    }
    r = RibbonRun{};
  };
  const verify::LaidStrip* prev = nullptr;
  for (const verify::LaidStrip& s : laid.strips) {
    const bool joins = prev != nullptr && prev->ply == s.ply && prev->course == s.course &&
                       prev->station_count > 0 &&
                       s.first_station == prev->first_station + prev->station_count - 1;
    prev = &s;
    if (hidden.count(s.ply) != 0) continue;
    const double lift =
        base_mm + kRibbonLiftMm + kRibbonPlyStepMm * static_cast<double>(ply_order[s.ply]);
    for (std::size_t g = 0; g < groups; ++g) {
      const int first = 1 + static_cast<int>(g) * k;
      const auto [a, b] = LaidSpan(s.tows, first, std::min(laid.tows, first + k - 1));
      RibbonRun& r = runs[g];
      if (!joins || a != r.a || b != r.b) close(r);
      if (a == 0) continue;
      if (r.a == 0) {
        r.a = a;
        r.b = b;
        r.set.label = "afp_ply_" + std::to_string(s.ply);
        r.set.rgba = PlyColour(s.ply);
        r.set.polyline = true;
        r.set.radius_mm = 0.5 * (b - a + 1) * laid.tow_width_mm;
      }
      for (std::uint32_t j = (joins && r.seen > 0) ? 1 : 0; j < s.station_count; ++j) {
        const std::size_t i = s.first_station + j;
        const verify::LaidStation& st = laid.stations[i];
        const Eigen::Vector3f& left = laid.Boundary(i, a - 1);
        const Eigen::Vector3f& right = laid.Boundary(i, b);
        if (!st.on_surface || !Finite(left) || !Finite(right)) continue;  // off the surface
        const Eigen::Vector3d n = st.normal.cast<double>().normalized();
        const Eigen::Vector3d c = 0.5 * (left + right).cast<double>() + lift * n;
        if (r.seen++ % static_cast<std::size_t>(out.station_step) == 0) {
          Keep(r, c, n);
        } else {
          r.pending = c;
          r.pending_normal = n;
          r.have_pending = true;
        }
      }
    }
  }
  for (RibbonRun& r : runs) close(r);
  // The drawn plies, the top ones first.
  std::size_t listed = 0;
  for (auto ply = stack.rbegin(); ply != stack.rend(); ++ply) {
    if (hidden.count(*ply) != 0) continue;
    if (listed++ == kMaxPlyEntries) {
      out.legend.push_back({{0, 0, 0}, "..."});
      break;
    }
    out.legend.push_back({render::ToRgb(PlyColour(*ply)), "ply " + std::to_string(*ply)});
  }
  if (!out.hidden_plies.empty()) {
    const std::size_t n = out.hidden_plies.size();
    out.legend.push_back(
        {{0, 0, 0},
         (n == 1 ? "ply " + std::to_string(out.hidden_plies.front())
                 : std::to_string(n) + " plies (" + std::to_string(out.hidden_plies.front()) +
                       " to " + std::to_string(out.hidden_plies.back()) + ")") +
             " under these: not drawn"});
  }
  return out;
}

}  // namespace stitchsim::run
