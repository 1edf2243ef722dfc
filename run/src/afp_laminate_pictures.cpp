// The AFP laminate snapshots (docs/report-format.md, "AFP laminate snapshots"): the stack
// thickness and the worst fibre-angle deviation over the surface's (u, v), each a colour map
// with mm axes, a title bar and a colour scale with its numbers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "stitchsim/render/renderer.h"
#include "stitchsim/render/text.h"
#include "stitchsim/run/snapshots.h"
#include "stitchsim/verify/afp_laminate_maps.h"

namespace stitchsim::run {
namespace {

constexpr int kMapSide = 900;  // the map's longer side on the picture, pixels
constexpr int kLeft = 90, kRight = 170, kBottom = 70, kGap = 40;
constexpr int kMinWidth = 1000;  // the title bar needs this much
constexpr render::Rgb kInk = {30, 30, 30};

// A perceptually ordered ramp (viridis' ends and three stops between), t in [0, 1].
render::Rgb Ramp(double t) {
  constexpr std::array<std::array<double, 3>, 5> kStops = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  const double x = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(i);
  render::Rgb out;
  for (std::size_t c = 0; c < 3; ++c) {
    out[c] = static_cast<std::uint8_t>(std::lround(kStops[i][c] * (1 - f) + kStops[i + 1][c] * f));
  }
  return out;
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

// A tick step of 1, 2 or 5 times a power of ten giving about `count` ticks over `span`.
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

// Ticks at multiples of NiceStep within [lo, hi]; `place(value)` gives the pixel.
template <typename PlaceFn>
void Ticks(double lo, double hi, int count, PlaceFn&& place) {
  const double step = NiceStep(hi - lo, count);
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) place(v);
}

// The picture of `map`: the map (white where nothing was laid) in a frame, u to the right and
// v up with mm ticks, the colour scale on the right, the title bar on top.
render::Image Picture(const verify::LaminateMap& map, const render::SnapshotFonts& fonts,
                      const render::TitleBar& title) {
  const int scale = std::max(1, kMapSide / std::max(map.width, map.height));
  const int mw = map.width * scale, mh = map.height * scale;
  render::Image img;
  img.width = std::max(kMinWidth, kLeft + mw + kRight);
  img.height = 0;
  {  // the title bar's height first, on a scratch picture as wide
    render::Image probe{img.width, 200, std::vector<std::uint8_t>(img.width * 600, 255)};
    img.height = render::DrawTitleBar(probe, fonts, title) + kGap + mh + kBottom;
  }
  img.rgb.assign(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3,
                 255);
  const int top = render::DrawTitleBar(img, fonts, title) + kGap, x0 = kLeft;
  const double lo = map.min_value;
  const double hi = map.max_value > lo ? map.max_value : lo + std::max(1e-3, std::abs(lo) * 0.1);
  for (int py = 0; py < map.height; ++py) {
    for (int px = 0; px < map.width; ++px) {
      const float v = map.values[static_cast<std::size_t>(py) * map.width + px];
      if (std::isnan(v)) continue;
      Fill(img, x0 + px * scale, top + py * scale, x0 + (px + 1) * scale, top + (py + 1) * scale,
           Ramp((v - lo) / (hi - lo)));
    }
  }
  const render::Font& f = *fonts.regular;
  // The frame and the axes' ticks: u along the bottom, v up the left side.
  Fill(img, x0 - 1, top - 1, x0 + mw + 1, top, kInk);
  Fill(img, x0 - 1, top + mh, x0 + mw + 1, top + mh + 1, kInk);
  Fill(img, x0 - 1, top, x0, top + mh, kInk);
  Fill(img, x0 + mw, top, x0 + mw + 1, top + mh, kInk);
  const Eigen::Vector2d span = map.hi_uv - map.lo_uv;
  // As many u ticks as their labels have room for side by side (a narrow part: two or three).
  const int u_label_room = render::TextWidth(f, Number(map.hi_uv.x())) + 24;
  Ticks(map.lo_uv.x(), map.hi_uv.x(), std::clamp(mw / u_label_room, 2, 6), [&](double u) {
    const int x = x0 + static_cast<int>(std::lround((u - map.lo_uv.x()) / span.x() * mw));
    Fill(img, x, top + mh, x + 1, top + mh + 6, kInk);
    const std::string s = Number(u);
    render::DrawText(img, f, x - render::TextWidth(f, s) / 2, top + mh + 8 + f.Ascender(), s, kInk);
  });
  Ticks(map.lo_uv.y(), map.hi_uv.y(), 6, [&](double v) {
    const int y = top + mh - static_cast<int>(std::lround((v - map.lo_uv.y()) / span.y() * mh));
    Fill(img, x0 - 6, y, x0, y + 1, kInk);
    const std::string s = Number(v);
    render::DrawText(img, f, x0 - 9 - render::TextWidth(f, s), y + f.Ascender() / 2, s, kInk);
  });
  const std::string u_label = "u (mm)";
  render::DrawText(img, f, x0 + mw / 2 - render::TextWidth(f, u_label) / 2,
                   top + mh + 14 + 2 * f.Ascender() + f.Descender(), u_label, kInk);
  render::DrawText(img, f, 4, top - kGap / 2 + f.Ascender() / 2, "v (mm)", kInk);
  // The colour scale: bottom lo, top hi, ticks and the unit.
  const int bx = x0 + mw + 30, bw = 22;
  const bool uniform = !(map.max_value > map.min_value);
  for (int y = 0; y < mh; ++y) {
    Fill(img, bx, top + y, bx + bw, top + y + 1, Ramp(uniform ? 0.0 : 1.0 - (y + 0.5) / mh));
  }
  Fill(img, bx - 1, top - 1, bx + bw + 1, top, kInk);
  Fill(img, bx - 1, top + mh, bx + bw + 1, top + mh + 1, kInk);
  auto bar_label = [&](double v, int y) {
    Fill(img, bx + bw, y, bx + bw + 6, y + 1, kInk);
    render::DrawText(img, f, bx + bw + 9, y + f.Ascender() / 2, Number(v), kInk);
  };
  if (uniform) {
    bar_label(lo, top + mh / 2);  // one value everywhere: one colour, one number
  } else {
    Ticks(lo, hi, 6, [&](double v) {
      bar_label(v, top + mh - static_cast<int>(std::lround((v - lo) / (hi - lo) * mh)));
    });
  }
  render::DrawText(img, f, bx, top - kGap / 2 + f.Ascender() / 2, map.unit, kInk);
  return img;
}

}  // namespace

Status WriteAfpLaminateSnapshots(const verify::Verifier& verifier, const std::string& dir) {
  for (const verify::LaminateMap& map : verify::LaminateMaps(verifier, kMapSide)) {
    render::SnapshotFonts fonts;
    std::string error;
    if (!render::OpenSnapshotFonts(kLeft + kMapSide + kRight, fonts, error)) {
      return Status::Error("io-missing-file", "snapshots: " + error);
    }
    render::TitleBar title;
    title.line1 = map.title + " (" + map.unit + "), the programme's plies";
    title.line2 = "min " + Number(map.min_value) + " " + map.unit + ", max " +
                  Number(map.max_value) + " " + map.unit + " over the area laid; (u, v) in mm" +
                  (map.coarsened ? "; grid coarsened past 2 mm cells" : "");
    title.accent = {60, 110, 200};
    const render::Image img = Picture(map, fonts, title);
    const auto path = std::filesystem::path(dir) / ("laminate_" + map.name + ".png");
    if (std::string err = render::WritePng(path, img); !err.empty()) {
      return Status::Error("io-write", "cannot write " + path.string() + ": " + err);
    }
  }
  return Status::Ok();
}

}  // namespace stitchsim::run
