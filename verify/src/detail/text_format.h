#pragma once
// Private text helpers shared by the report writers: UTF-8 decoding and encoding, terminal-safe
// and XML-escaped text, and the locale-independent number format of the text and JUnit reports.

#include <cstddef>
#include <string>
#include <string_view>

#include "stitchsim/common/units.h"

namespace stitchsim::verify::detail {

inline constexpr char32_t kInvalidCodePoint = 0xFFFFFFFF;
inline constexpr char32_t kReplacementChar = 0xFFFD;

/// Decodes the UTF-8 code point at `pos` and advances past it. A malformed sequence (bad lead
/// or continuation byte, overlong form, surrogate, > U+10FFFF, cut short) consumes one byte
/// and yields kInvalidCodePoint.
char32_t NextCodePoint(std::string_view s, std::size_t& pos);
/// Appends `cp` as UTF-8.
void AppendUtf8(std::string& out, char32_t cp);
/// Up to four significant digits, no exponent for 1e-4 <= |v| < 1e9, no trailing zeros.
std::string FormatNumber(double v);
/// "1 error" / "3 errors".
std::string Count(long n, std::string_view singular, std::string_view plural);
/// "line L stitch S" (parts that are 0 left out).
std::string Location(int line, long stitch);
/// One line of valid UTF-8 that cannot upset a terminal: whitespace controls become spaces,
/// other controls (C0, DEL, C1) and malformed bytes become U+FFFD.
std::string Printable(std::string_view s);

enum class XmlContext { kText, kAttribute };
/// Escapes markup characters and quotes; characters XML 1.0 cannot carry at all (most
/// controls, malformed UTF-8) become U+FFFD. In attributes, whitespace controls are written
/// as character references so a parser's attribute normalisation keeps them.
std::string XmlEscape(std::string_view s, XmlContext context);
/// printf of up to three numbers into a string (the rules' messages).
std::string Fmt(const char* format, double a, double b = 0.0, double c = 0.0);

/// "12.5 mm": a formatted number and its unit (printable), or the number alone.
inline std::string WithUnit(const std::string& number, const std::string& unit) {
  return unit.empty() ? number : number + " " + Printable(unit);
}

/// ` name="value"`, the value escaped for an XML attribute.
inline std::string XmlAttribute(std::string_view name, std::string_view value) {
  return " " + std::string(name) + "=\"" + XmlEscape(value, XmlContext::kAttribute) + "\"";
}

}  // namespace stitchsim::verify::detail
