// The AFP coverage snapshots (run/afp_coverage_picture.h; docs/report-format.md, "AFP coverage
// snapshots"): per ply the afp.coverage map (verify/afp_coverage_image.h) drawn at one scale
// on u and v, the laid material (verify::LaidMaterial) over it, axes, a scale bar, a title
// block and a legend.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "detail/uv_canvas.h"
#include "stitchsim/common/units.h"
#include "stitchsim/run/afp_coverage_picture.h"
#include "stitchsim/run/snapshots.h"
#include "stitchsim/verify/afp_coverage_image.h"
#include "stitchsim/verify/afp_laid_material.h"

namespace stitchsim::run {
namespace {

using verify::CoverageState;

constexpr double kCovMaxPxPerMm = 4.0;  // a small ply is not blown up past this
constexpr double kCovMarginMm = 15.0;   // around what the map holds
constexpr int kCovLeft = 80, kCovGap = 40, kCovBottom = 75;
constexpr int kCovFontWidth = 1400;  // the width the fonts are sized for
constexpr int kMinFeaturePx = 3;     // gaps and overlaps thinner are drawn this wide

// The colour key, by verify::CoverageState.
constexpr render::Rgb kCoverageColours[] = {
    {255, 255, 255},  // nothing
    {60, 110, 200},   // laid tows: blue
    {220, 30, 30},    // gap (bare inside the ply): red
    {250, 190, 0},    // overlap (doubled): amber
    {160, 160, 160},  // laid outside the ply: grey
    {250, 170, 170},  // bare in the boundary band (the coverage policy's): pink
};
constexpr render::Rgb kOutline = {20, 20, 45}, kTowLine = {165, 190, 235}, kArrowInk = {0, 0, 0},
                      kAddMark = {0, 165, 60}, kCutMark = {190, 0, 190};

int Rank(CoverageState s) {
  constexpr int kRank[] = {0, 1, 4, 5, 2, 3};  // doubled > bare > band bare > outside > laid
  return kRank[static_cast<int>(s)];
}

// The map's states at the picture's pixels: each the worst of the coverage pixels it covers.
std::vector<CoverageState> Resample(const verify::CoverageImage& img, const uv::UvFrame& f) {
  std::vector<CoverageState> out(static_cast<std::size_t>(f.width) * f.height,
                                 CoverageState::kNone);
  const double cu = (img.hi_uv.x() - img.lo_uv.x()) / img.width;
  const double cv = (img.hi_uv.y() - img.lo_uv.y()) / img.height;
  const double mm_u = (f.hi_uv.x() - f.lo_uv.x()) / f.width;
  const double mm_v = (f.hi_uv.y() - f.lo_uv.y()) / f.height;
  auto cols = [](double a, double b, double lo, double cell, int n) {
    const int i0 = std::clamp(static_cast<int>(std::floor((a - lo) / cell)), 0, n);
    const int i1 = std::clamp(static_cast<int>(std::ceil((b - lo) / cell)), 0, n);
    return std::pair{i0, std::max(i0, i1)};
  };
  for (int y = 0; y < f.height; ++y) {
    const double v1 = f.hi_uv.y() - y * mm_v, v0 = v1 - mm_v;
    const auto [r0, r1] = cols(v0, v1, img.lo_uv.y(), cv, img.height);  // from the bottom
    for (int x = 0; x < f.width; ++x) {
      const double u0 = f.lo_uv.x() + x * mm_u;
      const auto [c0, c1] = cols(u0, u0 + mm_u, img.lo_uv.x(), cu, img.width);
      CoverageState& s = out[static_cast<std::size_t>(y) * f.width + x];
      for (int r = r0; r < r1; ++r) {
        const std::size_t row = static_cast<std::size_t>(img.height - 1 - r) * img.width;
        for (int c = c0; c < c1; ++c) {
          const CoverageState p = img.pixels[row + static_cast<std::size_t>(c)];
          if (Rank(p) > Rank(s)) s = p;
        }
      }
    }
  }
  return out;
}

// Gaps and overlaps thinner than kMinFeaturePx across a row or a column, widened to it about
// their middle; the others as they are (to scale). kNone where neither.
std::vector<CoverageState> Enlarged(const std::vector<CoverageState>& px, int w, int h) {
  std::vector<CoverageState> out(px.size(), CoverageState::kNone);
  auto mark = [&](int x, int y, CoverageState s) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    CoverageState& o = out[static_cast<std::size_t>(y) * w + x];
    if (Rank(s) > Rank(o)) o = s;
  };
  // Runs along a line of n pixels; at(i) the state, put(i, s) marks.
  auto runs = [&](int n, auto at, auto put) {
    for (int i = 0; i < n;) {
      const CoverageState s = at(i);
      int j = i + 1;
      while (j < n && at(j) == s) ++j;
      if (s == CoverageState::kBare || s == CoverageState::kDoubled) {
        const int len = j - i, extra = std::max(0, kMinFeaturePx - len);
        for (int k = i - extra / 2; k < j + (extra + 1) / 2; ++k) put(k, s);
      }
      i = j;
    }
  };
  for (int y = 0; y < h; ++y) {
    runs(
        w, [&](int x) { return px[static_cast<std::size_t>(y) * w + x]; },
        [&](int x, CoverageState s) { mark(x, y, s); });
  }
  for (int x = 0; x < w; ++x) {
    runs(
        h, [&](int y) { return px[static_cast<std::size_t>(y) * w + x]; },
        [&](int y, CoverageState s) { mark(x, y, s); });
  }
  return out;
}

// What the title block says about one ply.
struct PlyFacts {
  int first_line = 0, last_line = 0;  // the lines that lay it
  int courses = 0, tows_laid = 0;     // distinct courses; tow pieces (adds)
};

PlyFacts FactsOf(const verify::LaidMaterial& laid, int ply) {
  PlyFacts f;
  std::set<int> courses;
  for (const verify::LaidStrip& s : laid.strips) {
    if (s.ply != ply) continue;
    courses.insert(s.course);
    f.first_line = f.first_line == 0 ? s.line : std::min(f.first_line, s.line);
    f.last_line = std::max(f.last_line, s.line);
  }
  for (const verify::TowEvent& e : laid.events) {
    if (e.ply == ply && e.kind == verify::TowEvent::Kind::kAdd) ++f.tows_laid;
  }
  f.courses = static_cast<int>(courses.size());
  return f;
}

// One afp rule's worst figure for the ply: its subjects named after the ply, else the rule's
// worst, on this ply when its line lies among the ply's lines, else the programme's.
std::string RuleFigure(const verify::RuleSummary& r, const std::string& ply_name,
                       const PlyFacts& f) {
  const std::string id = r.id.substr(4);
  if (!r.Applies() || !r.worst_value) return id + " n/a";
  std::string out;
  for (const verify::SubjectFigure& s : r.subjects) {
    if (ply_name.empty() || s.subject.rfind(ply_name + " ", 0) != 0 || !s.worst_value) continue;
    out += (out.empty() ? id + " " : ", ") + s.subject.substr(ply_name.size() + 1) + " " +
           uv::Number(*s.worst_value) + " " + r.unit;
  }
  if (!out.empty()) return out + " (this ply)";
  const bool here = r.worst_line >= f.first_line && r.worst_line <= f.last_line;
  return id + " " + uv::Number(*r.worst_value) + " " + r.unit +
         (here ? " (this ply)" : " (programme)");
}

// PASS / FAIL of the afp rules on the ply: an error finding on one of its lines or subjects
// fails it; with findings left out (truncated) and none of the kept ones here, not known.
std::string Verdict(const verify::Verifier& v, const std::string& ply_name, const PlyFacts& f) {
  bool unknown = false;
  for (const auto& rule : v.Rules()) {
    const verify::RuleSummary& r = rule->Summary();
    if (r.id.rfind("afp.", 0) != 0) continue;
    for (const verify::Finding& x : r.findings) {
      if (x.severity != verify::FindingSeverity::kError) continue;
      const bool named = !ply_name.empty() && x.subject.rfind(ply_name + " ", 0) == 0;
      if (named || (x.line >= f.first_line && x.line <= f.last_line)) return "FAIL";
    }
    unknown = unknown || (r.truncated && r.errors > 0);
  }
  return unknown ? "verdict not known (findings truncated)" : "PASS";
}

// The title block: `lines` on an opaque band across the top, a blue stripe at its left.
render::TitleBand TitleBandOf(const std::vector<std::string>& lines) {
  return {lines, {60, 110, 200}, {36, 38, 44}, 1.0, 2};
}

// The title block's lines: the ply, then the afp rules' figures packed `width` pixels a line.
std::vector<std::string> TitleLines(const verify::Verifier& v, const scene::Scene& scene,
                                    const verify::CoverageImage& img, const PlyFacts& f,
                                    const render::SnapshotFonts& fonts, int width) {
  char angle[32] = "angle ?";
  if (img.ply >= 1 && img.ply <= static_cast<int>(scene.plies.size())) {
    std::snprintf(angle, sizeof(angle), "%.4g deg",
                  RadToDeg(scene.plies[static_cast<std::size_t>(img.ply) - 1].angle_rad));
  }
  std::vector<std::string> lines = {
      "coverage map, ply " + std::to_string(img.ply) + " " + img.name + ": " +
          Verdict(v, img.name, f) + " (afp rules on this ply)",
      std::string("fibre angle ") + angle + " · " + std::to_string(f.courses) + " courses · " +
          std::to_string(f.tows_laid) + " tows laid · (u, v) in mm, one scale on both",
      "worst figure of each afp rule, on this ply or (where the rule does not place it) the "
      "programme's:"};
  std::string line;
  for (const auto& rule : v.Rules()) {
    const verify::RuleSummary& r = rule->Summary();
    if (r.id.rfind("afp.", 0) != 0) continue;
    const std::string item = RuleFigure(r, img.name, f);
    if (!line.empty() && render::TextWidth(*fonts.regular, line + " · " + item) > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " · ") + item;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace

namespace {

// The laid material of ply `ply` over the map: tow boundaries (thin, light; when tows are at
// least 3 px wide), each strip's outer edges and each course's ends (dark).
void DrawLaid(render::Image& out, const uv::UvFrame& f, const verify::LaidMaterial& laid, int ply,
              double px_per_mm) {
  const bool tow_lines = laid.tow_width_mm * px_per_mm >= kMinFeaturePx;
  auto px = [&](std::size_t st, int b) { return f.ToPixel(laid.BoundaryUv(st, b).cast<double>()); };
  auto laid_tow = [](std::uint64_t tows, int t) { return t >= 1 && ((tows >> (t - 1)) & 1U) != 0; };
  for (std::size_t i = 0; i < laid.strips.size(); ++i) {
    const verify::LaidStrip& s = laid.strips[i];
    if (s.ply != ply || s.tows == 0) continue;
    const int left = std::countr_zero(s.tows), right = 64 - std::countl_zero(s.tows);
    const bool course_start =
        i == 0 || laid.strips[i - 1].course != s.course || laid.strips[i - 1].ply != s.ply;
    const bool course_end = i + 1 == laid.strips.size() || laid.strips[i + 1].course != s.course ||
                            laid.strips[i + 1].ply != s.ply;
    const std::size_t a = s.first_station, z = a + s.station_count - 1;
    for (std::size_t st = a; st < z; ++st) {
      for (int b = left + 1; tow_lines && b < right; ++b) {
        if (laid_tow(s.tows, b) || laid_tow(s.tows, b + 1)) {
          uv::Line(out, px(st, b), px(st + 1, b), 1, kTowLine);
        }
      }
      uv::Line(out, px(st, left), px(st + 1, left), 1, kOutline);
      uv::Line(out, px(st, right), px(st + 1, right), 1, kOutline);
    }
    if (course_start) uv::Line(out, px(a, left), px(a, right), 1, kOutline);
    if (course_end) uv::Line(out, px(z, left), px(z, right), 1, kOutline);
  }
}

// Fibre direction: three arrows a course, along its stations (the middle of the tows laid) at
// a quarter, half and three quarters of its length on the map (stations crowd where tows are
// cut and added: counted by station, the three would fall together there).
void DrawArrows(render::Image& out, const uv::UvFrame& f, const verify::LaidMaterial& laid,
                int ply) {
  std::vector<std::pair<std::size_t, int>> stations;  // station, boundary in the laid middle
  auto flush = [&] {
    std::vector<Eigen::Vector2d> at;  // the stations' middles, pixels
    std::vector<double> run{0.0};     // the length along them
    for (const auto& [st, b] : stations) {
      at.push_back(f.ToPixel(
          0.5 * (laid.BoundaryUv(st, b / 2) + laid.BoundaryUv(st, (b + 1) / 2)).cast<double>()));
      if (at.size() > 1) {
        const double step = (at.back() - at[at.size() - 2]).norm();
        run.push_back(run.back() + (std::isfinite(step) ? step : 0.0));
      }
    }
    for (double q : {0.25, 0.5, 0.75}) {
      if (at.size() < 2) break;
      const auto i = std::min<std::size_t>(
          static_cast<std::size_t>(std::upper_bound(run.begin(), run.end(), q * run.back()) -
                                   run.begin()),
          at.size() - 1);
      const Eigen::Vector2d a = at[i - 1], b = at[i];
      if (!a.allFinite() || !b.allFinite() || !((b - a).norm() > 1e-9)) continue;
      const Eigen::Vector2d d = (b - a).normalized() * 11.0;
      uv::Arrow(out, a - d, a + d, 6, kArrowInk);
    }
    stations.clear();
  };
  for (std::size_t i = 0; i < laid.strips.size(); ++i) {
    const verify::LaidStrip& s = laid.strips[i];
    if (i > 0 && (laid.strips[i - 1].course != s.course || laid.strips[i - 1].ply != s.ply))
      flush();
    if (s.ply != ply || s.tows == 0) continue;
    // Twice the middle boundary: the outer edges' sum (b / 2 and (b + 1) / 2 straddle it).
    const int twice_mid = std::countr_zero(s.tows) + 64 - std::countl_zero(s.tows);
    for (std::uint32_t k = 0; k < s.station_count; ++k) {
      stations.emplace_back(s.first_station + k, twice_mid);
    }
  }
  flush();
}

// The seams afp.gap and afp.overlap measured (their drawn course-edge points of 0.1 mm or
// more, projected onto the surface), red and amber lines 3 px wide: a seam narrower than the
// coverage map's cells shows here too. Called only when the programme lays one ply (the
// points do not name theirs).
void DrawRuleSeams(render::Image& out, const uv::UvFrame& f, const verify::Verifier& v,
                   const scene::Scene& scene) {
  for (const auto& rule : v.Rules()) {
    for (const verify::DrawnPoints& d : rule->Drawings()) {
      const bool gap = d.label == "afp_gap";
      if (!gap && d.label != "afp_overlap") continue;
      const render::Rgb c =
          kCoverageColours[static_cast<int>(gap ? CoverageState::kBare : CoverageState::kDoubled)];
      // Consecutive points less than two tows apart joined: the seam as a line, not dots.
      Eigen::Vector2d last(NAN, NAN);
      for (std::size_t i = 0; i < d.points_mm.size(); ++i) {
        const Eigen::Vector2d uv = scene.surface->Project(d.points_mm[i]).uv;
        const bool join = i > 0 && (uv - last).norm() < 2 * v.Laid().tow_width_mm;
        uv::Line(out, f.ToPixel(join ? last : uv), f.ToPixel(uv), 3, c);
        last = uv;
      }
    }
  }
}

std::vector<uv::LegendRow> LegendOf(bool tow_lines, bool seams) {
  using S = uv::LegendRow::Swatch;
  const auto c = [](CoverageState s) { return kCoverageColours[static_cast<int>(s)]; };
  return {
      {S::kFill, c(CoverageState::kLaid), "laid (once)"},
      {S::kLine, kOutline, "course outline (outer tow edges)"},
      {S::kThinLine, kTowLine,
       tow_lines ? "tow boundary" : "tow boundaries: tows < 3 px, not drawn"},
      {S::kArrow, kArrowInk, "fibre direction, the way laid (3 a course)"},
      {S::kDisc, kAddMark, "tow added (add point)"},
      {S::kCross, kCutMark, "tow cut (cut point)"},
      {S::kFill, c(CoverageState::kBare), "gap: bare inside the ply"},
      {S::kFill, c(CoverageState::kDoubled), "overlap: laid twice or more"},
      {S::kNone, uv::kInk, "  gaps and overlaps to scale; thinner than"},
      {S::kNone, uv::kInk, "  3 px: enlarged to 3 px to be seen"},
      {S::kNone, uv::kInk,
       seams ? "  red / amber lines: seams afp.gap / overlap measured"
             : "  afp.gap / overlap seams: not drawn (several plies)"},
      {S::kFill, c(CoverageState::kBoundaryBare), "bare in the boundary band (policy)"},
      {S::kFill, c(CoverageState::kOutside), "laid outside the ply"},
  };
}

// The (u, v) box the map shows: what the coverage map holds (any state but kNone) and a
// margin of kCovMarginMm, within the map's box.
std::pair<Eigen::Vector2d, Eigen::Vector2d> Extent(const verify::CoverageImage& cov) {
  int x0 = cov.width, x1 = -1, y0 = cov.height, y1 = -1;
  for (int y = 0; y < cov.height; ++y) {
    for (int x = 0; x < cov.width; ++x) {
      if (cov.pixels[static_cast<std::size_t>(y) * cov.width + x] == CoverageState::kNone) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return {cov.lo_uv, cov.hi_uv};
  const Eigen::Vector2d cell =
      (cov.hi_uv - cov.lo_uv).cwiseQuotient(Eigen::Vector2d(cov.width, cov.height));
  const Eigen::Vector2d lo(cov.lo_uv.x() + x0 * cell.x(), cov.hi_uv.y() - (y1 + 1) * cell.y());
  const Eigen::Vector2d hi(cov.lo_uv.x() + (x1 + 1) * cell.x(), cov.hi_uv.y() - y0 * cell.y());
  return {(lo.array() - kCovMarginMm).max(cov.lo_uv.array()).matrix(),
          (hi.array() + kCovMarginMm).min(cov.hi_uv.array()).matrix()};
}

CoveragePicture Picture(const verify::Verifier& v, const scene::Scene& scene,
                        const verify::CoverageImage& cov, const render::SnapshotFonts& fonts,
                        const Eigen::Vector2i& map_px) {
  const auto [lo, hi] = Extent(cov);
  const Eigen::Vector2d span = (hi - lo).cwiseMax(1e-6);
  const double s = std::min({map_px.x() / span.x(), map_px.y() / span.y(), kCovMaxPxPerMm});
  uv::UvFrame f;
  f.width = std::max(1, static_cast<int>(std::lround(span.x() * s)));
  f.height = std::max(1, static_cast<int>(std::lround(span.y() * s)));
  f.lo_uv = lo;
  f.hi_uv = lo + Eigen::Vector2d(f.width / s, f.height / s);  // one scale on u and v
  const verify::LaidMaterial& laid = v.Laid();
  const PlyFacts facts = FactsOf(laid, cov.ply);
  const bool tow_lines = laid.tow_width_mm * s >= kMinFeaturePx;
  const bool one_ply = std::all_of(laid.strips.begin(), laid.strips.end(),
                                   [&](const verify::LaidStrip& x) { return x.ply == cov.ply; });
  const std::vector<uv::LegendRow> legend = LegendOf(tow_lines, one_ply);
  const render::Font& font = *fonts.regular;
  CoveragePicture pic;
  pic.ply = cov.ply;
  pic.name = cov.name;
  pic.px_per_mm = s;
  render::Image& img = pic.image;
  const int legend_w = uv::LegendWidth(font, legend);
  const int legend_h = uv::DrawLegendBox(nullptr, font, 0, 0, legend_w, legend);
  // A map shorter than the legend (a long flat ply): the legend and the scale bar go under it
  // (the scale bar and its text need 520 px).
  const bool below = f.height + kCovBottom < legend_h + 60;
  img.width = below ? std::max({kCovLeft + f.width + kCovGap, legend_w + 3 * kCovGap + 520, 1100})
                    : std::max(kCovLeft + f.width + 2 * kCovGap + std::max(legend_w, 520), 1100);
  pic.title = TitleLines(v, scene, cov, facts, fonts, img.width - 40);
  const std::vector<std::string>& title = pic.title;
  const int title_h = render::DrawTitleBand(nullptr, fonts, TitleBandOf(title));
  f.x0 = kCovLeft;
  f.top = title_h + kCovGap;
  img.height = below ? f.top + f.height + kCovBottom + legend_h + 20
                     : f.top + std::max(f.height + kCovBottom, legend_h + 60);
  img.rgb.assign(static_cast<std::size_t>(img.width) * img.height * 3, 255);
  const std::vector<CoverageState> px = Resample(cov, f);
  for (int y = 0; y < f.height; ++y) {
    for (int x = 0; x < f.width; ++x) {
      const auto c =
          kCoverageColours[static_cast<int>(px[static_cast<std::size_t>(y) * f.width + x])];
      uv::Fill(img, f.x0 + x, f.top + y, f.x0 + x + 1, f.top + y + 1, c);
    }
  }
  DrawLaid(img, f, laid, cov.ply, s);
  // Gaps and overlaps over the lines (a seam lies between two course outlines), enlarged.
  const std::vector<CoverageState> big = Enlarged(px, f.width, f.height);
  for (int y = 0; y < f.height; ++y) {
    for (int x = 0; x < f.width; ++x) {
      const CoverageState st = big[static_cast<std::size_t>(y) * f.width + x];
      if (st == CoverageState::kNone) continue;
      uv::Fill(img, f.x0 + x, f.top + y, f.x0 + x + 1, f.top + y + 1,
               kCoverageColours[static_cast<int>(st)]);
    }
  }
  if (one_ply) DrawRuleSeams(img, f, v, scene);
  DrawArrows(img, f, laid, cov.ply);
  for (const verify::TowEvent& e : laid.events) {
    if (e.ply != cov.ply) continue;
    const Eigen::Vector2d p = f.ToPixel(e.uv.cast<double>());
    if (e.kind == verify::TowEvent::Kind::kAdd)
      uv::Disc(img, p, 3.0, kAddMark);
    else
      uv::Cross(img, p, 3, kCutMark);
  }
  render::DrawTitleBand(&img, fonts, TitleBandOf(title));
  const uv::AxisTicks ticks = uv::DrawAxes(img, font, f, 8);
  pic.u_ticks = ticks.u;
  pic.v_ticks = ticks.v;
  const int panel_x = below ? kCovGap : f.x0 + f.width + kCovGap;
  const int panel_y = below ? f.top + f.height + kCovBottom : f.top;
  uv::DrawLegendBox(&img, font, panel_x, panel_y, legend_w, legend);
  pic.scale_bar_mm =
      below ? uv::DrawScaleBar(img, font, panel_x + legend_w + kCovGap, panel_y + 30, s, 160)
            : uv::DrawScaleBar(img, font, panel_x, panel_y + legend_h + 40, s, 160);
  return pic;
}

}  // namespace

std::vector<CoveragePicture> AfpCoveragePictures(const verify::Verifier& verifier,
                                                 const scene::Scene& scene,
                                                 const render::SnapshotFonts& fonts,
                                                 const Eigen::Vector2i& map_px) {
  std::vector<CoveragePicture> out;
  for (const verify::CoverageImage& img : verify::CoverageImages(verifier)) {
    out.push_back(Picture(verifier, scene, img, fonts, map_px.cwiseMax(16)));
  }
  return out;
}

Status WriteAfpCoverageSnapshots(const verify::Verifier& verifier, const scene::Scene& scene,
                                 const std::string& dir) {
  render::SnapshotFonts fonts;
  std::string error;
  if (!render::OpenSnapshotFonts(kCovFontWidth, fonts, error)) {
    return Status::Error("io-missing-file", "snapshots: " + error);
  }
  for (const CoveragePicture& pic : AfpCoveragePictures(verifier, scene, fonts)) {
    const auto path =
        std::filesystem::path(dir) / ("coverage_ply" + std::to_string(pic.ply) + ".png");
    if (std::string err = render::WritePng(path, pic.image); !err.empty()) {
      return Status::Error("io-write", "cannot write " + path.string() + ": " + err);
    }
  }
  return Status::Ok();
}

}  // namespace stitchsim::run
