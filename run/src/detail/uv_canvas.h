#pragma once
// Drawing on a map of a surface's (u, v) plane (mm), shared by the AFP snapshots
// (afp_coverage_pictures.cpp, afp_laminate_pictures.cpp): a pixel rectangle showing a (u, v)
// box, u to the right and v up; its frame, mm axes with ticks and a scale bar; a title block;
// a legend box; fills, lines, arrows and marks in pixels.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "stitchsim/render/renderer.h"
#include "stitchsim/render/text.h"
#include "stitchsim/run/afp_coverage_picture.h"

namespace stitchsim::run::uv {

inline constexpr render::Rgb kInk = {30, 30, 30};

/// A tick step of 1, 2 or 5 times a power of ten giving about `count` ticks over `span`.
double NiceStep(double span, int count);
/// `v` with four significant digits ("%.4g"), -0 as 0.
std::string Number(double v);
/// Fills the pixels [x0, x1) x [y0, y1), clipped to the image.
void Fill(render::Image& img, int x0, int y0, int x1, int y1, const render::Rgb& c);
/// A segment from `a` to `b` (pixels, continuous: pixel (x, y) covers [x, x + 1) x [y, y + 1))
/// `width` pixels wide (square pen).
void Line(render::Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, int width,
          const render::Rgb& c);
/// An arrow from `a` to `b` (pixels) with a head `head` pixels long.
void Arrow(render::Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double head,
           const render::Rgb& c);
/// A filled disc of `radius` pixels at `p`.
void Disc(render::Image& img, const Eigen::Vector2d& p, double radius, const render::Rgb& c);
/// A diagonal cross (x) `half` pixels from its centre `p` to each tip, 2 px thick.
void Cross(render::Image& img, const Eigen::Vector2d& p, int half, const render::Rgb& c);

/// A (u, v) box in mm shown in a pixel rectangle of a picture, u to the right, v up.
struct UvFrame {
  int x0 = 0, top = 0;                              ///< the rectangle's top-left pixel
  int width = 0, height = 0;                        ///< its size, pixels
  Eigen::Vector2d lo_uv = Eigen::Vector2d::Zero();  ///< (u, v) at its bottom-left corner, mm
  Eigen::Vector2d hi_uv = Eigen::Vector2d::Zero();  ///< (u, v) at its top-right corner, mm
  /// Where (u, v) (mm) falls (pixels, continuous, y down).
  Eigen::Vector2d ToPixel(const Eigen::Vector2d& uv) const;
};

/// The ticks DrawAxes drew (AxisTick: afp_coverage_picture.h).
struct AxisTicks {
  std::vector<AxisTick> u, v;
};
/// The frame around `f`, u ticks and labels along its bottom (as many as their labels have
/// room for), `v_count` v ticks up its left side, "u (mm)" below and "v (mm)" above the left
/// side. Returns the ticks drawn.
AxisTicks DrawAxes(render::Image& img, const render::Font& font, const UvFrame& f, int v_count);
/// A scale bar of a round length (1, 2 or 5 times a power of ten mm, at most `max_px` pixels
/// at `px_per_mm`) with its length printed, its left end at (x, baseline y). Returns its
/// length, mm.
double DrawScaleBar(render::Image& img, const render::Font& font, int x, int y, double px_per_mm,
                    int max_px);

/// One legend row: a swatch (a filled square, a line, an arrow, a disc or a cross) and its text.
struct LegendRow {
  enum class Swatch { kFill, kLine, kThinLine, kArrow, kDisc, kCross, kNone };
  Swatch swatch = Swatch::kFill;
  render::Rgb colour = kInk;
  std::string label;
};
/// The width (pixels) of the legend box of `rows` (its widest row).
int LegendWidth(const render::Font& font, const std::vector<LegendRow>& rows);
/// The legend box with its top-left corner at (x, y), `width` pixels wide (LegendWidth fits
/// the text). Returns its height; with a null `img` only measures.
int DrawLegendBox(render::Image* img, const render::Font& font, int x, int y, int width,
                  const std::vector<LegendRow>& rows);

}  // namespace stitchsim::run::uv
