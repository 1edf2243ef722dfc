// Drawing on a (u, v) map (detail/uv_canvas.h).
#include "detail/uv_canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stitchsim::run::uv {

double NiceStep(double span, int count) {
  const double raw = std::max(span, 1e-12) / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10.0 * p;
}

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

void Fill(render::Image& img, int x0, int y0, int x1, int y1, const render::Rgb& c) {
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) {
      const auto k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) +
                      static_cast<std::size_t>(x)) *
                     3;
      std::copy(c.begin(), c.end(), img.rgb.begin() + static_cast<std::ptrdiff_t>(k));
    }
  }
}

void Line(render::Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, int width,
          const render::Rgb& c) {
  if (!a.allFinite() || !b.allFinite()) return;
  const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() * 2.0)));
  const int lo = (width - 1) / 2;
  for (int i = 0; i <= steps; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / steps);
    const int x = static_cast<int>(std::floor(p.x())) - lo;
    const int y = static_cast<int>(std::floor(p.y())) - lo;
    Fill(img, x, y, x + width, y + width, c);
  }
}

void Arrow(render::Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double head,
           const render::Rgb& c) {
  const Eigen::Vector2d d = b - a;
  if (!(d.norm() > 1e-9)) return;
  const Eigen::Vector2d t = d.normalized(), n(-t.y(), t.x());
  Line(img, a, b, 2, c);
  Line(img, b, b - head * t + 0.5 * head * n, 2, c);
  Line(img, b, b - head * t - 0.5 * head * n, 2, c);
}

void Disc(render::Image& img, const Eigen::Vector2d& p, double radius, const render::Rgb& c) {
  if (!p.allFinite()) return;
  const int r = static_cast<int>(std::ceil(radius));
  const int cx = static_cast<int>(std::floor(p.x())), cy = static_cast<int>(std::floor(p.y()));
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (dx * dx + dy * dy <= radius * radius)
        Fill(img, cx + dx, cy + dy, cx + dx + 1, cy + dy + 1, c);
    }
  }
}

void Cross(render::Image& img, const Eigen::Vector2d& p, int half, const render::Rgb& c) {
  const Eigen::Vector2d d1(half, half), d2(half, -half);
  Line(img, p - d1, p + d1, 2, c);
  Line(img, p - d2, p + d2, 2, c);
}

Eigen::Vector2d UvFrame::ToPixel(const Eigen::Vector2d& uv) const {
  const Eigen::Vector2d span = hi_uv - lo_uv;
  return {x0 + (uv.x() - lo_uv.x()) / span.x() * width,
          top + height - (uv.y() - lo_uv.y()) / span.y() * height};
}

namespace {

// Ticks at multiples of NiceStep within [lo, hi], at least two (a finer step where `count`
// would leave one: a scale needs two marks); `place(value)` gives the pixel.
template <typename PlaceFn>
void EachTick(double lo, double hi, int count, PlaceFn&& place) {
  double step = NiceStep(hi - lo, count);
  for (int more = count + 1; more <= count + 8; ++more) {
    if (std::floor(hi / step + 1e-9) - std::ceil(lo / step - 1e-9) >= 1.0) break;
    step = NiceStep(hi - lo, more);
  }
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) place(v);
}

}  // namespace

AxisTicks DrawAxes(render::Image& img, const render::Font& f, const UvFrame& fr, int v_count) {
  const int x0 = fr.x0, top = fr.top, mw = fr.width, mh = fr.height;
  Fill(img, x0 - 1, top - 1, x0 + mw + 1, top, kInk);
  Fill(img, x0 - 1, top + mh, x0 + mw + 1, top + mh + 1, kInk);
  Fill(img, x0 - 1, top, x0, top + mh, kInk);
  Fill(img, x0 + mw, top, x0 + mw + 1, top + mh, kInk);
  const Eigen::Vector2d span = fr.hi_uv - fr.lo_uv;
  AxisTicks ticks;
  // As many u ticks as their labels have room for side by side (a narrow part: two or three).
  const int u_label_room = render::TextWidth(f, Number(fr.hi_uv.x())) + 24;
  EachTick(fr.lo_uv.x(), fr.hi_uv.x(), std::clamp(mw / u_label_room, 2, 6), [&](double u) {
    const int x = x0 + static_cast<int>(std::lround((u - fr.lo_uv.x()) / span.x() * mw));
    Fill(img, x, top + mh, x + 1, top + mh + 6, kInk);
    const std::string s = Number(u);
    render::DrawText(img, f, x - render::TextWidth(f, s) / 2, top + mh + 8 + f.Ascender(), s, kInk);
    ticks.u.push_back({u, x});
  });
  EachTick(fr.lo_uv.y(), fr.hi_uv.y(), v_count, [&](double v) {
    const int y = top + mh - static_cast<int>(std::lround((v - fr.lo_uv.y()) / span.y() * mh));
    Fill(img, x0 - 6, y, x0, y + 1, kInk);
    const std::string s = Number(v);
    render::DrawText(img, f, x0 - 9 - render::TextWidth(f, s), y + f.Ascender() / 2, s, kInk);
    ticks.v.push_back({v, y});
  });
  const std::string u_label = "u (mm)";
  render::DrawText(img, f, x0 + mw / 2 - render::TextWidth(f, u_label) / 2,
                   top + mh + 14 + 2 * f.Ascender() + f.Descender(), u_label, kInk);
  render::DrawText(img, f, std::max(4, x0 - 80), top - 10, "v (mm)", kInk);
  return ticks;
}

double DrawScaleBar(render::Image& img, const render::Font& f, int x, int y, double px_per_mm,
                    int max_px) {
  double mm = std::pow(10.0, std::floor(std::log10(max_px / px_per_mm)));
  for (double m : {5.0, 2.0}) {
    if (m * mm * px_per_mm <= max_px) {
      mm *= m;
      break;
    }
  }
  const int len = static_cast<int>(std::lround(mm * px_per_mm));
  Fill(img, x, y - 3, x + len, y, kInk);
  Fill(img, x, y - 9, x + 2, y, kInk);
  Fill(img, x + len - 2, y - 9, x + len, y, kInk);
  render::DrawText(img, f, x + len + 8, y, Number(mm) + " mm (same scale on u and v)", kInk);
  return mm;
}

int LegendWidth(const render::Font& f, const std::vector<LegendRow>& rows) {
  const int pad = std::max(4, f.PixelHeight() / 2);
  int text = 0;
  for (const LegendRow& e : rows) {
    const int indent = e.swatch == LegendRow::Swatch::kNone ? 0 : f.Ascender() + pad;
    text = std::max(text, indent + render::TextWidth(f, e.label));
  }
  return pad + text + pad;
}

int DrawLegendBox(render::Image* img, const render::Font& f, int x, int y, int width,
                  const std::vector<LegendRow>& rows) {
  const int pad = std::max(4, f.PixelHeight() / 2);
  const int row = f.Ascender() + f.Descender() + pad / 2;
  const int height = pad + static_cast<int>(rows.size()) * row + pad / 2;
  if (img == nullptr) return height;
  Fill(*img, x, y, x + width, y + 1, kInk);
  Fill(*img, x, y + height - 1, x + width, y + height, kInk);
  Fill(*img, x, y, x + 1, y + height, kInk);
  Fill(*img, x + width - 1, y, x + width, y + height, kInk);
  const int sw = f.Ascender();
  int base = y + pad + f.Ascender();
  for (const LegendRow& e : rows) {
    const int sx = x + pad, sy = base - f.Ascender() + 1;
    const Eigen::Vector2d l(sx, sy + sw / 2.0), rgt(sx + sw, sy + sw / 2.0);
    switch (e.swatch) {
      case LegendRow::Swatch::kFill:
        Fill(*img, sx, sy, sx + sw, sy + sw, e.colour);
        break;
      case LegendRow::Swatch::kLine:
        Line(*img, l, rgt, 2, e.colour);
        break;
      case LegendRow::Swatch::kThinLine:
        Line(*img, l, rgt, 1, e.colour);
        break;
      case LegendRow::Swatch::kArrow:
        Arrow(*img, l, rgt, 5, e.colour);
        break;
      case LegendRow::Swatch::kDisc:
        Disc(*img, (l + rgt) / 2, 3.5, e.colour);
        break;
      case LegendRow::Swatch::kCross:
        Cross(*img, (l + rgt) / 2, 4, e.colour);
        break;
      case LegendRow::Swatch::kNone:
        break;
    }
    const int tx = e.swatch == LegendRow::Swatch::kNone ? sx : sx + sw + pad;
    render::DrawText(*img, f, tx, base, e.label, kInk);
    base += row;
  }
  return height;
}

}  // namespace stitchsim::run::uv
