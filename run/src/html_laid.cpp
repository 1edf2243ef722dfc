// The HTML report's laid tows (run/html_laid.h): verify::LaidMaterial's strips as typed
// arrays, stations merged where the tow edges run straight and, past the budget, each strip
// drawn as one ribbon between its outermost laid tows.
#include "stitchsim/run/html_laid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "stitchsim/common/base64.h"

namespace stitchsim::run {
namespace {

using nlohmann::json;
using verify::LaidMaterial;
using verify::LaidStrip;

constexpr std::size_t kMaxMergedSpan = 64;  // stations one chord may replace at most

// The first and last laid tow's outer boundaries (0 .. k), or {-1, -1} when the strip lays
// no tow the head has.
std::pair<int, int> OuterBoundaries(const LaidStrip& s, int tows) {
  int lo = -1, hi = -1;
  for (int t = 1; t <= tows && t <= 64; ++t) {
    if (((s.tows >> (t - 1)) & 1U) == 0) continue;
    if (lo < 0) lo = t - 1;
    hi = t;
  }
  return {lo, hi};
}

// A strip's stations' share of its line (0 .. 1) by the tool's path length.
std::vector<float> Fractions(const LaidMaterial& m, const LaidStrip& s) {
  std::vector<float> f(s.station_count, 0.0F);
  for (std::uint32_t j = 1; j < s.station_count; ++j) {
    f[j] = f[j - 1] +
           (m.stations[s.first_station + j].tool - m.stations[s.first_station + j - 1].tool).norm();
  }
  const float total = f.empty() ? 0.0F : f.back();
  for (float& x : f) x = total > 0.0F ? x / total : 0.0F;
  if (!f.empty()) f.back() = 1.0F;
  return f;
}

// Kept stations of one strip (indices into the strip): both ends, and every interior station
// whose tool point or outer tow edges would move more than `tol_mm` off the chord between its
// kept neighbours if it were dropped; a station off the surface and its neighbours always.
std::vector<std::uint32_t> KeptStations(const LaidMaterial& m, const LaidStrip& s,
                                        const std::vector<float>& fraction, double tol_mm,
                                        std::size_t stride) {
  std::vector<std::uint32_t> kept;
  const std::size_t n = s.station_count;
  if (n == 0) return kept;
  const auto [lo, hi] = OuterBoundaries(s, m.tows);
  const auto point = [&](std::size_t j, int which) -> Eigen::Vector3f {
    const std::size_t g = s.first_station + j;
    const int b = which == 0 ? lo : hi;
    return which < 0 || b < 0 ? m.stations[g].tool : m.Boundary(g, b);
  };
  const auto usable = [&](std::size_t j) {
    return m.stations[s.first_station + j].on_surface && point(j, -1).allFinite() &&
           point(j, 0).allFinite() && point(j, 1).allFinite();
  };
  const auto straight = [&](std::size_t a, std::size_t e) {
    const float span = fraction[e] - fraction[a];
    for (std::size_t j = a + 1; j < e; ++j) {
      if (!usable(j)) return false;
      const float f = span > 0.0F ? (fraction[j] - fraction[a]) / span : 0.5F;
      for (int which : {-1, 0, 1}) {
        const Eigen::Vector3f chord = point(a, which) + f * (point(e, which) - point(a, which));
        if ((point(j, which) - chord).norm() > tol_mm) return false;
      }
    }
    return true;
  };
  std::size_t a = 0;
  kept.push_back(0);
  while (a + 1 < n) {
    std::size_t j = a + 1;
    while (j + 1 < n && j + 1 - a <= kMaxMergedSpan && usable(a) && usable(j + 1) &&
           straight(a, j + 1)) {
      ++j;
    }
    kept.push_back(static_cast<std::uint32_t>(j));
    a = j;
  }
  if (stride > 1 && kept.size() > 2) {
    std::vector<std::uint32_t> fewer;
    for (std::size_t i = 0; i + 1 < kept.size(); i += stride) fewer.push_back(kept[i]);
    fewer.push_back(kept.back());
    kept.swap(fewer);
  }
  return kept;
}

std::size_t ValuesPerStation(int tows, bool outer_only) {
  return 7 + 3 * static_cast<std::size_t>(outer_only ? 2 : tows + 1);
}

// The kept stations of every strip under one thinning (a strip's stations are written for it
// alone, so `values` counts a station shared by two strips twice).
std::vector<std::vector<std::uint32_t>> KeepAll(const LaidMaterial& m,
                                                const std::vector<std::vector<float>>& fractions,
                                                LaidThinning& t) {
  std::vector<std::vector<std::uint32_t>> kept;
  t.stations_in = t.stations_kept = 0;
  for (std::size_t i = 0; i < m.strips.size(); ++i) {
    kept.push_back(KeptStations(m, m.strips[i], fractions[i], t.tolerance_mm, t.stride));
    t.stations_in += m.strips[i].station_count;
    t.stations_kept += kept.back().size();
  }
  t.values = t.stations_kept * ValuesPerStation(m.tows, t.outer_only);
  return kept;
}

std::string ThinningNote(const LaidThinning& t, std::size_t max_values) {
  std::string note;
  if (t.stations_kept != t.stations_in || t.outer_only) {
    char tol[32];
    std::snprintf(tol, sizeof tol, "%g", t.tolerance_mm);
    note = "Laid tows thinned for size: " + std::to_string(t.stations_kept) + " of " +
           std::to_string(t.stations_in) +
           " stations drawn (a line's ends always; an interior station only where the tool "
           "point or the outer tow edges leave the straight chord by more than " +
           tol + " mm";
    if (t.stride > 1 && t.stations_kept < t.stations_in) {
      note += ", then one in " + std::to_string(t.stride);
    }
    note += ").";
  }
  if (t.outer_only) {
    note += " Past the page's budget (" + std::to_string(max_values) +
            " values) each laying line's strip is drawn as one ribbon between its outermost "
            "laid tows' edges, not tow by tow: a picked tow is read from its share of the "
            "strip's width.";
  }
  if (!t.per_tow_figures) {
    note += std::string(note.empty() ? "" : " ") +
            "Steering radius and fibre angle are given per line (the smallest radius and the "
            "largest angle over the line's tows), not per tow.";
  }
  return note;
}

}  // namespace

json PageLaidJson(const LaidMaterial& laid, std::size_t max_values, LaidThinning* thinning) {
  if (laid.strips.empty() || laid.tows < 1 || laid.tows > 64) return nullptr;
  const std::size_t k = static_cast<std::size_t>(laid.tows);
  const std::size_t n = laid.strips.size();
  // Per-tow steering radius and fibre angle while they take at most a quarter of the budget;
  // past it one figure a line (the smallest radius, the largest angle over its tows).
  const bool per_tow = n * 2 * k <= max_values / 4;
  const std::size_t strip_values = n * (7 + (per_tow ? 2 * k : 2));
  const std::size_t station_budget = max_values > strip_values ? max_values - strip_values : 0;
  std::vector<std::vector<float>> fractions;
  for (const LaidStrip& s : laid.strips) fractions.push_back(Fractions(laid, s));
  // Finest first; the first that fits is used, else the last with a stride.
  const LaidThinning tries[] = {
      {0.05, false}, {0.25, false}, {0.25, true}, {1.0, true}, {4.0, true}};
  LaidThinning t;
  std::vector<std::vector<std::uint32_t>> kept;
  for (const LaidThinning& candidate : tries) {
    t = candidate;
    kept = KeepAll(laid, fractions, t);
    if (t.values <= station_budget) break;
  }
  if (t.values > station_budget) {
    t.stride = (t.values + station_budget - 1) / std::max<std::size_t>(1, station_budget);
    kept = KeepAll(laid, fractions, t);
  }
  t.per_tow_figures = per_tow;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<std::int32_t> line, ply, course, first{0};
  std::vector<std::uint32_t> mask_lo, mask_hi;
  std::vector<float> feed, steer, angle, fraction, tool, normal, boundary;
  for (std::size_t i = 0; i < n; ++i) {
    const LaidStrip& s = laid.strips[i];
    line.push_back(s.line);
    ply.push_back(s.ply);
    course.push_back(s.course);
    mask_lo.push_back(static_cast<std::uint32_t>(s.tows & 0xffffffffU));
    mask_hi.push_back(static_cast<std::uint32_t>(s.tows >> 32));
    feed.push_back(s.feed_mm_s);
    float radius = nan, deviation = nan;  // fmin / fmax pass NaN over
    for (std::size_t tw = 1; tw <= k; ++tw) {
      const float r = laid.SteeringRadiusMm(i, static_cast<int>(tw));
      const float a = laid.FiberAngleDeg(i, static_cast<int>(tw));
      if (per_tow) {
        steer.push_back(r);
        angle.push_back(a);
      }
      radius = std::fmin(radius, r);
      deviation = std::fmax(deviation, a);
    }
    if (!per_tow) {
      steer.push_back(radius);
      angle.push_back(deviation);
    }
    const auto [lo, hi] = OuterBoundaries(s, laid.tows);
    for (std::uint32_t j : kept[i]) {
      const std::size_t g = s.first_station + j;
      const verify::LaidStation& st = laid.stations[g];
      fraction.push_back(fractions[i][j]);
      tool.insert(tool.end(), st.tool.data(), st.tool.data() + 3);
      normal.insert(normal.end(), st.normal.data(), st.normal.data() + 3);
      const auto put = [&](int b) {
        const Eigen::Vector3f p =
            b >= 0 && st.on_surface ? laid.Boundary(g, b) : Eigen::Vector3f::Constant(nan);
        boundary.insert(boundary.end(), p.data(), p.data() + 3);
      };
      if (t.outer_only) {
        put(lo);
        put(hi);
      } else {
        for (std::size_t b = 0; b <= k; ++b) put(static_cast<int>(b));
      }
    }
    first.push_back(static_cast<std::int32_t>(fraction.size()));
  }
  if (thinning) *thinning = t;
  return json{{"tows", laid.tows},
              {"tow_width_mm", laid.tow_width_mm},
              {"bounds_per_station", t.outer_only ? 2 : laid.tows + 1},
              {"figures_per_tow", per_tow},
              {"note", ThinningNote(t, max_values)},
              {"strips",
               {{"line", Base64Of(line)},
                {"ply", Base64Of(ply)},
                {"course", Base64Of(course)},
                {"mask_lo", Base64Of(mask_lo)},
                {"mask_hi", Base64Of(mask_hi)},
                {"feed", Base64Of(feed)},
                {"first", Base64Of(first)},
                {"steer", Base64Of(steer)},
                {"angle", Base64Of(angle)}}},
              {"stations",
               {{"fraction", Base64Of(fraction)},
                {"tool", Base64Of(tool)},
                {"normal", Base64Of(normal)},
                {"boundary", Base64Of(boundary)}}}};
}

}  // namespace stitchsim::run
