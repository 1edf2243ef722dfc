#pragma once
// Text burned into snapshots: UTF-8 strings drawn antialiased with FreeType (DejaVu fonts from
// Debian's fonts-dejavu-core), a title bar on top of a picture and a colour legend box.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/render/renderer.h"

namespace stitchsim::render {

/// 8-bit RGB colour.
using Rgb = std::array<std::uint8_t, 3>;

/// One typeface at one pixel size (FreeType face). Not copyable; cheap to draw with.
class Font {
 public:
  /// Opens a TrueType file at `pixel_height` (em size, pixels). nullptr with `error` set when
  /// the file is missing or not a font.
  static std::unique_ptr<Font> Open(const std::filesystem::path& file, int pixel_height,
                                    std::string& error);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  int PixelHeight() const { return pixel_height_; }
  /// Distance from the baseline up to the top of the tallest glyph, and down to the bottom
  /// of the lowest (pixels, both >= 0).
  int Ascender() const;
  int Descender() const;

 private:
  friend int TextWidth(const Font& font, std::string_view utf8);
  friend int DrawText(Image& image, const Font& font, int x, int baseline_y, std::string_view utf8,
                      const Rgb& colour);
  Font() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int pixel_height_ = 0;
};

/// Advance width of `utf8` in pixels (what DrawText moves the pen by).
int TextWidth(const Font& font, std::string_view utf8);
/// Draws `utf8` with its baseline at `baseline_y`, starting at `x` (pixels, image rows top
/// down), blending the glyph coverage over the image; clipped at the image border. Returns
/// the advance width. Invalid UTF-8 bytes draw as U+FFFD.
int DrawText(Image& image, const Font& font, int x, int baseline_y, std::string_view utf8,
             const Rgb& colour);

/// The regular and bold DejaVu Sans faces at the snapshot sizes.
struct SnapshotFonts {
  std::unique_ptr<Font> bold;     ///< title line 1
  std::unique_ptr<Font> regular;  ///< title line 2, legend
};
/// The folder the fonts are read from: $STITCHSIM_FONT_DIR when set, else Debian's
/// /usr/share/fonts/truetype/dejavu.
std::filesystem::path FontDir();
/// Opens DejaVuSans-Bold.ttf and DejaVuSans.ttf from FontDir() for an image `image_width`
/// pixels wide. False with `error` naming the missing file.
bool OpenSnapshotFonts(int image_width, SnapshotFonts& fonts, std::string& error);

/// The two lines of a snapshot's title bar (line 1 bold).
struct TitleBar {
  std::string line1;           ///< e.g. "collision.robot_cell  error"
  std::string line2;           ///< e.g. "line 5 · stitch 0 · 16.3 mm (limit 0 mm) · rail_hit.nc"
  Rgb accent = {200, 30, 30};  ///< the severity stripe at the bar's left
};
/// Burns the title bar over the top of `image` (dark band, white text). Returns the bar's
/// height in pixels.
int DrawTitleBar(Image& image, const SnapshotFonts& fonts, const TitleBar& title);

/// A title band of any number of lines (the title bar's layout): `lines[0]` bold, the others
/// regular, `row_gap` pixels between them, each cut to the image's width.
struct TitleBand {
  std::vector<std::string> lines;
  Rgb accent = {200, 30, 30};     ///< the stripe at the band's left
  Rgb background = {24, 26, 30};  ///< the band, over the picture at `opacity`
  double opacity = 0.88;
  int row_gap = 0;
};
/// Burns `band` over the top of `image` and returns its height in pixels; with a null `image`
/// only measures.
int DrawTitleBand(Image* image, const SnapshotFonts& fonts, const TitleBand& band);

/// One row of a legend: a colour swatch and what it means.
struct LegendEntry {
  Rgb colour = {0, 0, 0};
  std::string label;  ///< e.g. "depth 16.3 mm"
};
/// Draws the legend box in the bottom left corner of `image` (nothing for no entries).
void DrawLegend(Image& image, const SnapshotFonts& fonts, const std::vector<LegendEntry>& entries);

/// An RGBA colour in [0, 1] (MuJoCo's) as 8-bit RGB.
Rgb ToRgb(const std::array<float, 4>& rgba);

}  // namespace stitchsim::render
