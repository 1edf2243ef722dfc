#include "text_format.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace stitchsim::verify::detail {

char32_t NextCodePoint(std::string_view s, std::size_t& pos) {
  const auto lead = static_cast<unsigned char>(s[pos]);
  if (lead < 0x80) {
    ++pos;
    return lead;
  }
  std::size_t length = 0;
  char32_t cp = 0;
  char32_t smallest = 0;
  if ((lead & 0xE0) == 0xC0) {
    length = 2, cp = lead & 0x1F, smallest = 0x80;
  } else if ((lead & 0xF0) == 0xE0) {
    length = 3, cp = lead & 0x0F, smallest = 0x800;
  } else if ((lead & 0xF8) == 0xF0) {
    length = 4, cp = lead & 0x07, smallest = 0x10000;
  } else {
    ++pos;
    return kInvalidCodePoint;
  }
  if (s.size() - pos < length) {
    ++pos;
    return kInvalidCodePoint;
  }
  for (std::size_t k = 1; k < length; ++k) {
    const auto byte = static_cast<unsigned char>(s[pos + k]);
    if ((byte & 0xC0) != 0x80) {
      ++pos;
      return kInvalidCodePoint;
    }
    cp = (cp << 6) | (byte & 0x3F);
  }
  if (cp < smallest || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
    ++pos;
    return kInvalidCodePoint;
  }
  pos += length;
  return cp;
}

void AppendUtf8(std::string& out, char32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

std::string FormatNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (v == 0.0) return "0";  // also -0
  std::array<char, 64> buffer{};
  char* const first = buffer.data();
  char* const last = buffer.data() + buffer.size();
  const double magnitude = std::fabs(v);
  if (magnitude < 1e-4 || magnitude >= 1e9) {
    const auto result = std::to_chars(first, last, v, std::chars_format::general, 4);
    return std::string(first, result.ptr);
  }
  int decimals = 0;
  for (double bound = 1000.0; magnitude < bound && decimals < 7; bound /= 10.0) ++decimals;
  const auto result = std::to_chars(first, last, v, std::chars_format::fixed, decimals);
  std::string text(first, result.ptr);
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  return text;
}

std::string Count(long n, std::string_view singular, std::string_view plural) {
  return std::to_string(n) + " " + std::string(n == 1 ? singular : plural);
}

std::string Location(int line, long stitch) {
  std::string where;
  if (line > 0) where = "line " + std::to_string(line);
  if (stitch > 0) where += (where.empty() ? "" : " ") + ("stitch " + std::to_string(stitch));
  return where.empty() ? "programme" : where;
}

std::string Fmt(const char* format, double a, double b, double c) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), format, a, b, c);
  return buf;
}

std::string Printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t pos = 0; pos < s.size();) {
    const char32_t cp = NextCodePoint(s, pos);
    if (cp == U'\t' || cp == U'\n' || cp == U'\r' || cp == U'\v' || cp == U'\f') {
      out += ' ';
    } else if (cp == kInvalidCodePoint || cp < 0x20 || (cp >= 0x7F && cp < 0xA0)) {
      AppendUtf8(out, kReplacementChar);
    } else {
      AppendUtf8(out, cp);
    }
  }
  return out;
}

namespace {

// XML 1.0 "Char": tab, newline, carriage return, and U+0020 and up except the surrogates
// (never decoded) and U+FFFE / U+FFFF.
bool IsXmlChar(char32_t cp) {
  if (cp < 0x20) return cp == U'\t' || cp == U'\n' || cp == U'\r';
  return cp != 0xFFFE && cp != 0xFFFF && cp <= 0x10FFFF;
}

}  // namespace

std::string XmlEscape(std::string_view s, XmlContext context) {
  std::string out;
  out.reserve(s.size() + s.size() / 8);
  for (std::size_t pos = 0; pos < s.size();) {
    const char32_t cp = NextCodePoint(s, pos);
    switch (cp) {
      case U'&':
        out += "&amp;";
        break;
      case U'<':
        out += "&lt;";
        break;
      case U'>':
        out += "&gt;";
        break;
      case U'"':
        out += "&quot;";
        break;
      case U'\'':
        out += "&apos;";
        break;
      case U'\r':
        out += "&#13;";
        break;
      case U'\n':
        out += context == XmlContext::kAttribute ? "&#10;" : "\n";
        break;
      case U'\t':
        out += context == XmlContext::kAttribute ? "&#9;" : "\t";
        break;
      default:
        AppendUtf8(out, IsXmlChar(cp) ? cp : kReplacementChar);
        break;
    }
  }
  return out;
}

}  // namespace stitchsim::verify::detail
