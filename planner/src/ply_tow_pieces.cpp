// Short tow pieces and close restarts (docs/afp.md, "Short pieces and restarts"; issue 29): a
// head cannot lay a piece shorter than its cutter-to-roller distance, nor add a tow again
// right after cutting it. Under a coverage of 0.5 or more the planner lays more material (a
// short piece is extended past the ply boundary, a close restart is laid through); below it,
// less (a short piece is left bare, a restart is moved on). Lengths are the tow's centre line
// on the surface, as afp.min_tow_length and afp.restart_distance measure them.

#include <algorithm>
#include <cmath>

#include "ply_course.h"

namespace stitchsim::planner {
namespace {

// Pieces and restarts are made this much longer than the minimum: the rules sample the
// centre line at other points (chords a little shorter or longer than these).
constexpr double kTowPieceMarginMm = 0.1;
// A stretch of course this many times the limit is long enough for any tow without measuring
// it: a tow's centre line is shorter than the course's only by its offset d across the course
// times the course's geodesic curvature, below half only on a radius under 2 d (100 mm for
// the 16-tow head), far under any head's steering limit (a ply-steering-radius finding).
constexpr double kSurelyLongEnough = 2.0;
// Rounds of mending one tow (each either changes nothing, and ends, or shortens the list or
// a gap's shortfall).
constexpr int kMendRounds = 64;

/// A piece's length, 0 when it cannot be measured (the tows leave the surface on it).
double PieceLength(const TowRuler& ruler, int tow, const TowSegment& g) {
  return TowLength(ruler, tow, g.start_mm, g.end_mm).value_or(0.0);
}

/// Gap between consecutive pieces a and b along tow `tow`; nullopt: not measurable.
std::optional<double> GapLength(const TowRuler& ruler, int tow, const TowSegment& a,
                                const TowSegment& b) {
  if (b.start_mm <= a.end_mm) return 0.0;
  return TowLength(ruler, tow, a.end_mm, b.start_mm);
}

class TowMender {
 public:
  TowMender(const CourseContext& ctx, const TowRuler& ruler, int tow, bool curve_can_grow,
            TowPieceFixes& fixes, double& need_mm)
      : ctx_(ctx),
        ruler_(ruler),
        tow_(tow),
        grow_(curve_can_grow),
        fixes_(fixes),
        need_mm_(need_mm) {}

  /// Cuts and restarts closer than the minimum: laid through when `bridge`, else the restart
  /// moved on (a gap where the tows leave the surface is left as it is: the rule bridges it by
  /// chords). True when anything changed.
  bool Restarts(std::vector<TowSegment>& g, bool bridge) {
    const double limit = ctx_.min_restart_mm;
    if (limit <= 0.0) return false;
    bool changed = false;
    for (std::size_t i = 1; i < g.size();) {
      if (g[i].start_mm - g[i - 1].end_mm >= kSurelyLongEnough * limit) {
        ++i;
        continue;
      }
      const std::optional<double> gap = GapLength(ruler_, tow_, g[i - 1], g[i]);
      if (!gap || *gap >= limit) {
        ++i;
        continue;
      }
      changed = true;
      if (bridge) {
        g[i - 1].end_mm = std::max(g[i - 1].end_mm, g[i].end_mm);
        g.erase(g.begin() + static_cast<long>(i));
        ++fixes_.restarts_bridged;
        continue;
      }
      ++fixes_.restarts_moved;
      const TowReach r = WalkTow(ruler_, tow_, g[i - 1].end_mm, 1, limit + kTowPieceMarginMm);
      if (r.ok && r.s < g[i].end_mm) {
        g[i].start_mm = r.s;
        ++i;
      } else {  // nothing of the piece is left past the restart distance
        g.erase(g.begin() + static_cast<long>(i));
        ++fixes_.pieces_dropped;
      }
    }
    return changed;
  }

  /// Pieces shorter than the minimum: extended past the ply boundary when `extend` (both ends
  /// by half what the piece lacks; one end takes all where the other cannot go), else dropped.
  /// True when anything changed.
  bool ShortPieces(std::vector<TowSegment>& g, bool extend) {
    const double limit = ctx_.min_piece_mm;
    if (limit <= 0.0) return false;
    bool changed = false;
    for (std::size_t i = 0; i < g.size();) {
      if (g[i].end_mm - g[i].start_mm >= kSurelyLongEnough * limit) {
        ++i;
        continue;
      }
      const double length = PieceLength(ruler_, tow_, g[i]);
      if (length >= limit) {
        ++i;
        continue;
      }
      if (extend) {
        bool wait = false;
        if (Extend(g[i], limit + kTowPieceMarginMm - length, wait)) {
          ++fixes_.pieces_extended;
          changed = true;
          ++i;
          continue;
        }
        if (wait) {  // the course is planned again on a longer curve
          ++i;
          continue;
        }
      }
      g.erase(g.begin() + static_cast<long>(i));
      ++fixes_.pieces_dropped;
      changed = true;
    }
    return changed;
  }

 private:
  /// `g` lengthened by `lacking` of tow centre line; false (and `g` untouched) when it cannot
  /// be, with `wait` set when a longer curve would do.
  bool Extend(TowSegment& g, double lacking, bool& wait) {
    const TowReach back = WalkTow(ruler_, tow_, g.start_mm, -1, 0.5 * lacking);
    const TowReach ahead = WalkTow(ruler_, tow_, g.end_mm, 1, 0.5 * lacking);
    if (grow_ && (back.short_mm > 0.0 || ahead.short_mm > 0.0)) {
      need_mm_ = std::max({need_mm_, back.short_mm, ahead.short_mm});
      wait = true;
      return false;
    }
    TowSegment out = g;
    if (back.ok && ahead.ok) {
      out = {back.s, ahead.s};
    } else if (back.ok || ahead.ok) {  // the one end that can go takes it all
      const TowReach all = back.ok ? WalkTow(ruler_, tow_, g.start_mm, -1, lacking)
                                   : WalkTow(ruler_, tow_, g.end_mm, 1, lacking);
      if (!all.ok) return false;
      (back.ok ? out.start_mm : out.end_mm) = all.s;
    } else {
      return false;
    }
    if (PieceLength(ruler_, tow_, out) < ctx_.min_piece_mm) return false;
    g = out;
    return true;
  }

  const CourseContext& ctx_;
  const TowRuler& ruler_;
  int tow_;
  bool grow_;
  TowPieceFixes& fixes_;
  double& need_mm_;
};

}  // namespace

std::optional<double> TowLength(const TowRuler& ruler, int tow, double s0, double s1) {
  const int n = std::max(1, static_cast<int>(std::ceil((s1 - s0) / ruler.Step() - 1e-9)));
  double sum = 0.0;
  Eigen::Vector3d last = Eigen::Vector3d::Zero();
  for (int i = 0; i <= n; ++i) {
    const std::optional<Eigen::Vector3d> p = ruler.Centre(tow, s0 + (s1 - s0) * i / n);
    if (!p) return std::nullopt;
    if (i > 0) sum += (*p - last).norm();
    last = *p;
  }
  return sum;
}

TowReach WalkTow(const TowRuler& ruler, int tow, double from, int dir, double length) {
  TowReach r;
  const double end = dir > 0 ? ruler.End() : 0.0;
  std::optional<Eigen::Vector3d> last = ruler.Centre(tow, from);
  if (!last) return r;
  double s = from, walked = 0.0;
  while (walked < length) {
    if (dir * (end - s) <= 0.0) {  // the curve ends here
      r.short_mm = length - walked;
      return r;
    }
    const double next = dir > 0 ? std::min(s + ruler.Step(), end) : std::max(s - ruler.Step(), end);
    const std::optional<Eigen::Vector3d> p = ruler.Centre(tow, next);
    if (!p) return r;
    const double chord = (*p - *last).norm();
    if (walked + chord >= length && chord > 0.0) {
      r.ok = true;
      r.s = s + (next - s) * (length - walked) / chord;
      return r;
    }
    walked += chord;
    s = next;
    last = p;
  }
  r.ok = true;
  r.s = s;
  return r;
}

void AlignExtendedEnds(const CourseContext& ctx, const TowRuler& ruler,
                       const std::vector<double>& boundary_ends,
                       std::vector<std::vector<TowSegment>>& laid) {
  if (ctx.ply.coverage < 0.5) return;
  struct End {
    double s;
    std::size_t tow, piece;
  };
  // Tow `t`'s piece `i` with the end (adds: its start) at `s`, the restart distance kept.
  auto keeps_restart = [&](std::size_t t, std::size_t i, bool adds, double s) {
    const auto& g = laid[t];
    const bool has_other = adds ? i > 0 : i + 1 < g.size();
    if (!has_other || ctx.min_restart_mm <= 0.0) return true;
    const double a = adds ? g[i - 1].end_mm : s, b = adds ? s : g[i + 1].start_mm;
    return b > a &&
           TowLength(ruler, static_cast<int>(t) + 1, a, b).value_or(0.0) >= ctx.min_restart_mm;
  };
  for (const bool adds : {true, false}) {
    std::vector<End> ends;
    for (std::size_t t = 0; t < laid.size(); ++t) {
      for (std::size_t i = 0; i < laid[t].size(); ++i) {
        const double s = adds ? laid[t][i].start_mm : laid[t][i].end_mm;
        if (!std::binary_search(boundary_ends.begin(), boundary_ends.end(), s))
          ends.push_back({s, t, i});
      }
    }
    std::sort(ends.begin(), ends.end(), [&](const End& x, const End& y) {
      return adds ? x.s < y.s : x.s > y.s;  // the outermost first
    });
    for (std::size_t a = 0; a < ends.size();) {
      std::size_t b = a;
      for (; b < ends.size() && std::abs(ends[b].s - ends[a].s) < ctx.layout.width_mm; ++b) {
        const End& e = ends[b];
        if (!keeps_restart(e.tow, e.piece, adds, ends[a].s)) continue;
        (adds ? laid[e.tow][e.piece].start_mm : laid[e.tow][e.piece].end_mm) = ends[a].s;
      }
      a = b;
    }
  }
}

void MendTowPieces(const CourseContext& ctx, const TowRuler& ruler, int tow,
                   std::vector<TowSegment>& segments, bool curve_can_grow, TowPieceFixes& fixes,
                   double& need_mm) {
  const bool more = ctx.ply.coverage >= 0.5;
  TowMender m(ctx, ruler, tow, curve_can_grow, fixes, need_mm);
  for (int round = 0; round < kMendRounds; ++round) {
    // More material: join close restarts first (a joined piece is longer). Less: drop short
    // pieces first (a dropped piece restarts nothing).
    const bool first = more ? m.Restarts(segments, true) : m.ShortPieces(segments, false);
    const bool second = more ? m.ShortPieces(segments, true) : m.Restarts(segments, false);
    if (!first && !second) return;
  }
}

}  // namespace stitchsim::planner
