#include "stitchsim/program/identity.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string_view>
#include <variant>

#include "codes.h"

namespace stitchsim::program {
namespace {

struct TextKey {
  std::optional<std::string> ProgramIdentity::*field;
};
struct RealKey {
  std::optional<double> ProgramIdentity::*field;
  int decimals;    // written with this many
  double min;      // read: at least this,
  bool exclusive;  // or more than it
  std::string_view why;
};
struct CountKey {
  std::optional<long> ProgramIdentity::*field;
  std::string_view why;
};

constexpr double kAny = -std::numeric_limits<double>::infinity();
constexpr std::string_view kFinite = "must be a finite number";
constexpr std::string_view kWhole = "must be a whole number >= 0";

/// Every key the planners write, in written order: the one place a key is spelled.
struct Key {
  std::string_view name;
  std::variant<TextKey, RealKey, CountKey> kind;
};
const Key kKeys[] = {
    {"scene", TextKey{&ProgramIdentity::scene}},
    {"head", TextKey{&ProgramIdentity::head}},
    {"path", TextKey{&ProgramIdentity::path}},
    {"mode", TextKey{&ProgramIdentity::mode}},
    {"raster", TextKey{&ProgramIdentity::raster}},
    {"ply", TextKey{&ProgramIdentity::ply}},
    {"plies", TextKey{&ProgramIdentity::plies}},
    {"laminate", TextKey{&ProgramIdentity::laminate}},
    {"course", TextKey{&ProgramIdentity::course}},
    {"lay_angle_deg", RealKey{&ProgramIdentity::lay_angle_deg, 6, kAny, false, kFinite}},
    {"angle_deg", RealKey{&ProgramIdentity::angle_deg, 6, kAny, false, kFinite}},
    {"coverage_pct", RealKey{&ProgramIdentity::coverage_pct, 0, kAny, false, kFinite}},
    {"incline_deg", RealKey{&ProgramIdentity::incline_deg, 6, kAny, false, kFinite}},
    {"points", CountKey{&ProgramIdentity::points, kWhole}},
    {"course_length_mm", RealKey{&ProgramIdentity::course_length_mm, 6, 0.0, false,
                                 "the course length must be a number of millimetres >= 0"}},
    {"stitch_length_mm", RealKey{&ProgramIdentity::stitch_length_mm, 6, 0.0, true,
                                 "the stitch length must be a positive number of millimetres"}},
    {"row_spacing_mm", RealKey{&ProgramIdentity::row_spacing_mm, 6, 0.0, true,
                               "the row spacing must be a positive number of millimetres"}},
    {"heads", CountKey{&ProgramIdentity::heads, kWhole}},
    {"courses", CountKey{&ProgramIdentity::courses, kWhole}},
    {"tows", CountKey{&ProgramIdentity::tows, kWhole}},
    {"stitches",
     CountKey{&ProgramIdentity::stitches, "the stitch count must be a whole number >= 0"}},
};

template <typename T>
std::optional<T> Parse(std::string_view text) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::string Fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  std::string text = buf;
  // A value that prints as zero prints as "0.000000", never "-0.000000".
  if (text.front() == '-' && text.find_first_not_of("0.", 1) == std::string::npos) text.erase(0, 1);
  return text;
}

}  // namespace

std::optional<ProgramIdentity> ReadIdentity(const ProgramHeader& header,
                                            const std::string& file_name, DiagnosticSink& sink) {
  ProgramIdentity id;
  bool ok = true;
  auto bad = [&](std::string_view key, std::string_view value, std::string_view why) {
    sink.Error(codes::kBadHeader, {file_name, header.LineOf(key), 1},
               "header " + std::string(key) + "=" + std::string(value) + ": " + std::string(why));
    ok = false;
  };
  for (const Key& key : kKeys) {
    const std::optional<std::string_view> v = header.Find(key.name);
    if (!v) continue;
    if (const auto* text = std::get_if<TextKey>(&key.kind)) {
      id.*text->field = std::string(*v);
    } else if (const auto* real = std::get_if<RealKey>(&key.kind)) {
      const auto x = Parse<double>(*v);
      if (!x || !std::isfinite(*x) || *x < real->min || (real->exclusive && *x <= real->min)) {
        bad(key.name, *v, real->why);
      } else {
        id.*real->field = *x;
      }
    } else {
      const auto& count = std::get<CountKey>(key.kind);
      const auto n = Parse<long>(*v);
      if (!n || *n < 0) {
        bad(key.name, *v, count.why);
      } else {
        id.*count.field = *n;
      }
    }
  }
  if (!ok) return std::nullopt;
  return id;
}

ProgramHeader WriteIdentity(const ProgramIdentity& id) {
  ProgramHeader header;
  for (const Key& key : kKeys) {
    std::optional<std::string> value;
    if (const auto* text = std::get_if<TextKey>(&key.kind)) {
      value = id.*text->field;
    } else if (const auto* real = std::get_if<RealKey>(&key.kind)) {
      if (const auto& x = id.*real->field) value = Fixed(*x, real->decimals);
    } else if (const auto& n = id.*std::get<CountKey>(key.kind).field) {
      value = std::to_string(*n);
    }
    if (value) header.entries.emplace_back(std::string(key.name), std::move(*value));
  }
  return header;
}

}  // namespace stitchsim::program
