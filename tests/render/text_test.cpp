// render/text.h: glyphs drawn with FreeType (DejaVu). Widths measured from the inked pixels
// agree with the font's advances; twice the size is twice as wide; the title bar and legend
// change the picture where they are and nowhere else; a missing font is an error, not a crash.
#include "stitchsim/render/text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace stitchsim::render {
namespace {

Image Blank(int w, int h, std::uint8_t v) {
  Image img;
  img.width = w;
  img.height = h;
  img.rgb.assign(static_cast<std::size_t>(w) * h * 3, v);
  return img;
}

// Leftmost and rightmost columns with a pixel different from `v`; -1, -1 when none.
std::pair<int, int> InkedColumns(const Image& img, std::uint8_t v) {
  int lo = -1, hi = -1;
  for (int x = 0; x < img.width; ++x) {
    for (int y = 0; y < img.height; ++y) {
      const auto* p = &img.rgb[(static_cast<std::size_t>(y) * img.width + x) * 3];
      if (p[0] != v || p[1] != v || p[2] != v) {
        if (lo < 0) lo = x;
        hi = x;
        break;
      }
    }
  }
  return {lo, hi};
}

std::unique_ptr<Font> Sans(int px) {
  std::string error;
  auto f = Font::Open(FontDir() / "DejaVuSans.ttf", px, error);
  EXPECT_NE(f, nullptr) << error;
  return f;
}

TEST(Text, InkSpansTheMeasuredWidth) {
  const auto font = Sans(20);
  ASSERT_NE(font, nullptr);
  const std::string text = "HEAD_BODY|RAIL 16.3 mm";
  Image img = Blank(600, 60, 255);
  const int advance = DrawText(img, *font, 10, 40, text, {0, 0, 0});
  EXPECT_EQ(advance, TextWidth(*font, text));
  const auto [lo, hi] = InkedColumns(img, 255);
  ASSERT_GE(lo, 0);
  // The ink starts near the pen and ends within a glyph's side bearing of the advance.
  EXPECT_NEAR(lo, 10, 3);
  EXPECT_NEAR(hi - 10, advance, 4);
  EXPECT_GT(advance, 150);  // 22 glyphs of a 20 px font
}

TEST(Text, TwiceTheSizeIsTwiceAsWideAndTwiceTheTextToo) {
  const auto small = Sans(16), big = Sans(32);
  ASSERT_TRUE(small && big);
  const std::string text = "collision.robot_cell";
  const int w1 = TextWidth(*small, text), w2 = TextWidth(*big, text);
  EXPECT_NEAR(static_cast<double>(w2) / w1, 2.0, 0.08) << w1 << " " << w2;
  // Drawn, the inked extents say the same.
  Image a = Blank(800, 80, 255), b = Blank(800, 80, 255);
  DrawText(a, *small, 0, 50, text, {0, 0, 0});
  DrawText(b, *big, 0, 50, text, {0, 0, 0});
  const auto ea = InkedColumns(a, 255), eb = InkedColumns(b, 255);
  EXPECT_NEAR(static_cast<double>(eb.second - eb.first) / (ea.second - ea.first), 2.0, 0.1);
  // No kerning: a text written twice is exactly twice as wide.
  EXPECT_EQ(TextWidth(*small, text + text), 2 * w1);
}

TEST(Text, Utf8AndBadBytesDraw) {
  const auto font = Sans(18);
  ASSERT_NE(font, nullptr);
  EXPECT_GT(TextWidth(*font, "\xC2\xB7"), 2);                               // U+00B7 middle dot
  EXPECT_EQ(TextWidth(*font, "a\xC2"), TextWidth(*font, "a\xEF\xBF\xBD"));  // cut short: U+FFFD
  Image img = Blank(100, 40, 0);
  DrawText(img, *font, -50, 30, "\xFF\xFEwide text past both borders", {255, 255, 255});
  EXPECT_NE(InkedColumns(img, 0).first, -1);
}

TEST(Text, MissingFontIsAnError) {
  std::string error;
  EXPECT_EQ(Font::Open("/nonexistent/DejaVuSans.ttf", 12, error), nullptr);
  EXPECT_NE(error.find("/nonexistent/DejaVuSans.ttf"), std::string::npos) << error;
  error.clear();
  EXPECT_EQ(Font::Open("/etc/hostname", 12, error), nullptr);  // a file, not a font
  EXPECT_FALSE(error.empty());
}

TEST(Text, TitleBarAndLegendChangeOnlyTheirPlace) {
  SnapshotFonts fonts;
  std::string error;
  ASSERT_TRUE(OpenSnapshotFonts(1024, fonts, error)) << error;
  Image scene = Blank(1024, 768, 0);
  for (std::size_t i = 0; i < scene.rgb.size(); ++i) scene.rgb[i] = static_cast<std::uint8_t>(i);
  Image out = scene;
  TitleBar t;
  t.line1 = "collision.robot_cell \xC2\xB7 ERROR";
  t.line2 = "line 5 \xC2\xB7 stitch 0 \xC2\xB7 16.3 mm (limit 0 mm) \xC2\xB7 rail_hit.nc";
  const int bar = DrawTitleBar(out, fonts, t);
  EXPECT_GT(bar, 30);
  EXPECT_LT(bar, 768 / 8);
  const std::size_t row = 1024 * 3;
  long changed_in_bar = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(bar) * row; ++i) {
    changed_in_bar += out.rgb[i] != scene.rgb[i];
  }
  EXPECT_GT(changed_in_bar, static_cast<long>(bar) * 1024 * 3 * 9 / 10);
  EXPECT_TRUE(std::equal(out.rgb.begin() + static_cast<long>(bar * row), out.rgb.end(),
                         scene.rgb.begin() + static_cast<long>(bar * row)));
  // The legend: in the bottom left corner, with its swatch colour drawn as given.
  Image legend = scene;
  DrawLegend(legend, fonts, {{{250, 10, 200}, "depth 16.3 mm"}, {{10, 120, 240}, "rail"}});
  long swatch = 0, changed_top_right = 0;
  for (int y = 0; y < 768; ++y) {
    for (int x = 0; x < 1024; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * 1024 + x) * 3;
      if (legend.rgb[i] == 250 && legend.rgb[i + 1] == 10 && legend.rgb[i + 2] == 200) {
        ++swatch;
        EXPECT_LT(x, 200);
        EXPECT_GT(y, 600);
      }
      if ((y < 400 || x > 512) && legend.rgb[i] != scene.rgb[i]) ++changed_top_right;
    }
  }
  EXPECT_GT(swatch, 50);
  EXPECT_EQ(changed_top_right, 0);
}

}  // namespace
}  // namespace stitchsim::render
