#include "stitchsim/common/units.h"

#include <charconv>
#include <cmath>

namespace stitchsim {

std::optional<LengthUnit> ParseLengthUnit(std::string_view name) {
  if (name == "mm") return LengthUnit::kMillimetre;
  if (name == "in" || name == "inch") return LengthUnit::kInch;
  if (name == "m") return LengthUnit::kMetre;
  return std::nullopt;
}

double MmPer(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre:
      return 1.0;
    case LengthUnit::kInch:
      return kMmPerInch;
    case LengthUnit::kMetre:
      return 1000.0;
  }
  return 1.0;
}

std::string_view UnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre:
      return "mm";
    case LengthUnit::kInch:
      return "in";
    case LengthUnit::kMetre:
      return "m";
  }
  return "mm";
}

namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<double> ParseLengthMm(std::string_view text, LengthUnit default_unit) {
  text = Trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || !std::isfinite(value)) return std::nullopt;
  const std::string_view suffix = Trim(text.substr(static_cast<std::size_t>(end - text.data())));
  LengthUnit unit = default_unit;
  if (!suffix.empty()) {
    const std::optional<LengthUnit> named = ParseLengthUnit(suffix);
    if (!named) return std::nullopt;
    unit = *named;
  }
  const double mm = value * MmPer(unit);
  if (!std::isfinite(mm)) return std::nullopt;
  return mm;
}

}  // namespace stitchsim
