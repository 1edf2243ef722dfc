#include "stitchsim/render/text.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace stitchsim::render {

struct Font::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~Impl() {
    if (face != nullptr) FT_Done_Face(face);
    if (library != nullptr) FT_Done_FreeType(library);
  }
};

namespace {

// Decodes the next code point of `s` at `i` (advancing `i`); U+FFFD for a malformed byte.
char32_t NextCodePoint(std::string_view s, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  int extra = 0;
  char32_t cp = 0;
  if (c < 0x80) {
    ++i;
    return c;
  } else if ((c & 0xE0) == 0xC0) {
    extra = 1;
    cp = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    extra = 2;
    cp = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    extra = 3;
    cp = c & 0x07;
  } else {
    ++i;
    return 0xFFFD;
  }
  if (i + static_cast<std::size_t>(extra) >= s.size()) {  // cut short
    i = s.size();
    return 0xFFFD;
  }
  for (int k = 1; k <= extra; ++k) {
    const unsigned char b = byte(i + static_cast<std::size_t>(k));
    if ((b & 0xC0) != 0x80) {
      ++i;
      return 0xFFFD;
    }
    cp = (cp << 6) | (b & 0x3F);
  }
  i += static_cast<std::size_t>(extra) + 1;
  return cp;
}

void Blend(Image& image, int x, int y, const Rgb& colour, double alpha) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height || alpha <= 0.0) return;
  std::uint8_t* p = image.rgb.data() + (static_cast<std::size_t>(y) * image.width + x) * 3;
  for (int c = 0; c < 3; ++c) {
    p[c] = static_cast<std::uint8_t>(std::lround(p[c] * (1.0 - alpha) + colour[c] * alpha));
  }
}

void FillRect(Image& image, int x0, int y0, int x1, int y1, const Rgb& colour, double alpha) {
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
      Blend(image, x, y, colour, alpha);
    }
  }
}

// Shortens `text` with a trailing "..." until it fits `max_width` pixels.
std::string Fit(const Font& font, std::string text, int max_width) {
  if (TextWidth(font, text) <= max_width) return text;
  while (!text.empty() && TextWidth(font, text + "...") > max_width) {
    text.pop_back();
    while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80) {
      text.pop_back();  // a whole UTF-8 sequence at a time
    }
    if (!text.empty() && static_cast<unsigned char>(text.back()) >= 0xC0) text.pop_back();
  }
  return text + "...";
}

}  // namespace

std::unique_ptr<Font> Font::Open(const std::filesystem::path& file, int pixel_height,
                                 std::string& error) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    error = "font file " + file.string() + " not found (Debian package fonts-dejavu-core)";
    return nullptr;
  }
  std::unique_ptr<Font> font(new Font());
  font->impl_ = std::make_unique<Impl>();
  font->pixel_height_ = pixel_height;
  if (FT_Init_FreeType(&font->impl_->library) != 0) {
    error = "FreeType could not be initialised";
    return nullptr;
  }
  if (FT_New_Face(font->impl_->library, file.c_str(), 0, &font->impl_->face) != 0) {
    error = "font file " + file.string() + " is not a font FreeType can read";
    return nullptr;
  }
  if (FT_Set_Pixel_Sizes(font->impl_->face, 0, static_cast<FT_UInt>(pixel_height)) != 0) {
    error = "font " + file.string() + " has no size " + std::to_string(pixel_height);
    return nullptr;
  }
  return font;
}

Font::~Font() = default;

int Font::Ascender() const { return static_cast<int>(impl_->face->size->metrics.ascender >> 6); }

int Font::Descender() const {
  return static_cast<int>(std::abs(impl_->face->size->metrics.descender) >> 6);
}

int TextWidth(const Font& font, std::string_view utf8) {
  FT_Face face = font.impl_->face;
  long advance = 0;
  for (std::size_t i = 0; i < utf8.size();) {
    const char32_t cp = NextCodePoint(utf8, i);
    if (FT_Load_Char(face, cp, FT_LOAD_DEFAULT) != 0) continue;
    advance += face->glyph->advance.x;
  }
  return static_cast<int>(advance >> 6);
}

int DrawText(Image& image, const Font& font, int x, int baseline_y, std::string_view utf8,
             const Rgb& colour) {
  FT_Face face = font.impl_->face;
  long pen = static_cast<long>(x) << 6;
  for (std::size_t i = 0; i < utf8.size();) {
    const char32_t cp = NextCodePoint(utf8, i);
    if (FT_Load_Char(face, cp, FT_LOAD_RENDER) != 0) continue;
    const FT_GlyphSlot g = face->glyph;
    const FT_Bitmap& bm = g->bitmap;
    const int left = static_cast<int>(pen >> 6) + g->bitmap_left;
    const int top = baseline_y - g->bitmap_top;
    for (unsigned r = 0; r < bm.rows; ++r) {
      for (unsigned c = 0; c < bm.width; ++c) {
        const unsigned char cov = bm.buffer[static_cast<long>(r) * bm.pitch + c];
        Blend(image, left + static_cast<int>(c), top + static_cast<int>(r), colour, cov / 255.0);
      }
    }
    pen += g->advance.x;
  }
  return static_cast<int>(pen >> 6) - x;
}

std::filesystem::path FontDir() {
  const char* dir = std::getenv("STITCHSIM_FONT_DIR");
  return dir != nullptr && *dir != '\0' ? std::filesystem::path(dir)
                                        : std::filesystem::path("/usr/share/fonts/truetype/dejavu");
}

bool OpenSnapshotFonts(int image_width, SnapshotFonts& fonts, std::string& error) {
  // About 2 % of the width for the title, a little smaller for the rest.
  const int big = std::clamp(image_width / 48, 12, 40);
  const int small = std::clamp(image_width / 64, 10, 30);
  fonts.bold = Font::Open(FontDir() / "DejaVuSans-Bold.ttf", big, error);
  if (!fonts.bold) return false;
  fonts.regular = Font::Open(FontDir() / "DejaVuSans.ttf", small, error);
  return fonts.regular != nullptr;
}

int DrawTitleBar(Image& image, const SnapshotFonts& fonts, const TitleBar& title) {
  return DrawTitleBand(&image, fonts, {{title.line1, title.line2}, title.accent});
}

int DrawTitleBand(Image* image, const SnapshotFonts& fonts, const TitleBand& band) {
  const Font& b = *fonts.bold;
  const Font& r = *fonts.regular;
  const int pad = std::max(4, r.PixelHeight() / 2);
  const int bold_row = b.Ascender() + b.Descender();
  const int row = r.Ascender() + r.Descender() + band.row_gap;
  const int rows = static_cast<int>(band.lines.size() > 1 ? band.lines.size() - 1 : 0);
  const int height = pad + bold_row + pad / 2 + rows * row + pad;
  if (image == nullptr) return height;
  FillRect(*image, 0, 0, image->width, height, band.background, band.opacity);
  const int stripe = std::max(4, pad);
  FillRect(*image, 0, 0, stripe, height, band.accent, 1.0);
  const int x = stripe + pad;
  const int width = image->width - x - pad;
  for (std::size_t i = 0; i < band.lines.size(); ++i) {
    const Font& f = i == 0 ? b : r;
    const int y = i == 0 ? pad + b.Ascender()
                         : pad + bold_row + pad / 2 + r.Ascender() + static_cast<int>(i - 1) * row;
    DrawText(*image, f, x, y, Fit(f, band.lines[i], width),
             i == 0 ? Rgb{255, 255, 255} : Rgb{225, 228, 232});
  }
  return height;
}

void DrawLegend(Image& image, const SnapshotFonts& fonts, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) return;
  const Font& f = *fonts.regular;
  const int pad = std::max(4, f.PixelHeight() / 2);
  const int row = f.Ascender() + f.Descender() + pad / 2;
  const int swatch = f.Ascender();
  int text_width = 0;
  for (const auto& e : entries) text_width = std::max(text_width, TextWidth(f, e.label));
  text_width = std::min(text_width, image.width / 2);
  const int box_w = pad + swatch + pad + text_width + pad;
  const int box_h = pad + static_cast<int>(entries.size()) * row + pad / 2;
  const int x0 = pad, y0 = image.height - pad - box_h;
  FillRect(image, x0, y0, x0 + box_w, y0 + box_h, {255, 255, 255}, 0.85);
  FillRect(image, x0, y0, x0 + box_w, y0 + 1, {90, 90, 90}, 1.0);
  FillRect(image, x0, y0 + box_h - 1, x0 + box_w, y0 + box_h, {90, 90, 90}, 1.0);
  FillRect(image, x0, y0, x0 + 1, y0 + box_h, {90, 90, 90}, 1.0);
  FillRect(image, x0 + box_w - 1, y0, x0 + box_w, y0 + box_h, {90, 90, 90}, 1.0);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int top = y0 + pad + static_cast<int>(i) * row;
    const int sx = x0 + pad;
    FillRect(image, sx, top, sx + swatch, top + swatch, {40, 40, 40}, 1.0);
    FillRect(image, sx + 1, top + 1, sx + swatch - 1, top + swatch - 1, entries[i].colour, 1.0);
    DrawText(image, f, sx + swatch + pad, top + f.Ascender() - 1,
             Fit(f, entries[i].label, text_width), {20, 20, 20});
  }
}

Rgb ToRgb(const std::array<float, 4>& rgba) {
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(rgba[c], 0.0f, 1.0f) * 255.0f));
  }
  return out;
}

}  // namespace stitchsim::render
