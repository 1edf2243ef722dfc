// The AFP laminate snapshots (docs/report-format.md, "AFP laminate snapshots"): the stack
// thickness and the worst fibre-angle deviation over the surface's (u, v), each a colour map
// with mm axes, a title bar and a colour scale with its numbers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "detail/uv_canvas.h"
#include "stitchsim/render/renderer.h"
#include "stitchsim/render/text.h"
#include "stitchsim/run/snapshots.h"
#include "stitchsim/verify/afp_laminate_maps.h"

namespace stitchsim::run {
namespace {

constexpr int kMapSide = 900;  // the map's longer side on the picture, pixels
constexpr int kLeft = 90, kRight = 170, kBottom = 70, kGap = 40;
constexpr int kMinWidth = 1000;  // the title bar needs this much
using uv::Fill;
using uv::kInk;
using uv::Number;

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
  uv::DrawAxes(img, f, uv::UvFrame{x0, top, mw, mh, map.lo_uv, map.hi_uv}, 6);
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
    const double step = uv::NiceStep(hi - lo, 6);
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) {
      bar_label(v, top + mh - static_cast<int>(std::lround((v - lo) / (hi - lo) * mh)));
    }
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
