#pragma once
// Length and angle units at the text boundary. Inside, lengths are millimetres in the part
// and process code, metres in the robot model; angles are radians.

#include <optional>
#include <string_view>

namespace stitchsim {

inline constexpr double kMmPerInch = 25.4;
inline constexpr double kPi = 3.14159265358979323846;
/// Radians in one degree, and degrees in one radian (`x * kDeg` is x degrees in radians).
inline constexpr double kDeg = kPi / 180.0;
inline constexpr double kRadToDeg = 180.0 / kPi;

inline constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
inline constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }

enum class LengthUnit { kMillimetre, kInch, kMetre };

/// "mm", "in", "m" -> unit; nullopt otherwise.
std::optional<LengthUnit> ParseLengthUnit(std::string_view name);

/// Millimetres per one `unit`.
double MmPer(LengthUnit unit);

/// "mm" / "in" / "m".
std::string_view UnitName(LengthUnit unit);

/// A length as text, in millimetres: a finite number with an optional unit suffix, spaces
/// allowed around it ("2.5", "2.5mm", "0.1in", "0.1 inch", "1e-3m"); a bare number is in
/// `default_unit`. nullopt for anything else (empty, no number, unknown unit, NaN, inf).
std::optional<double> ParseLengthMm(std::string_view text, LengthUnit default_unit);

}  // namespace stitchsim
