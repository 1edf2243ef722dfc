#include "stitchsim/common/units.h"

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

}  // namespace stitchsim
