#include "stitchsim/geom/naca.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <utility>

#include "stitchsim/common/units.h"

namespace stitchsim::geom {
namespace {

// Abbott and von Doenhoff, table of 5-digit mean lines for design lift 0.3, by P (1..5).
struct FiveDigitRow {
  double m;
  double k1;
  double k2_over_k1;  // reflexed only; 0 where the reflexed line is not published
};
constexpr std::array<FiveDigitRow, 5> kStandard = {{{0.0580, 361.400, 0.0},
                                                    {0.1260, 51.640, 0.0},
                                                    {0.2025, 15.957, 0.0},
                                                    {0.2900, 6.643, 0.0},
                                                    {0.3910, 3.230, 0.0}}};
constexpr std::array<FiveDigitRow, 5> kReflexed = {{{0.0, 0.0, 0.0},  // 211: not published
                                                    {0.1300, 51.990, 0.000764},
                                                    {0.2170, 15.793, 0.00677},
                                                    {0.3180, 6.520, 0.0303},
                                                    {0.4410, 3.191, 0.1355}}};

int Digit(char c) { return c - '0'; }

bool ParseFourDigit(std::string_view code, NacaSection& s, std::string& error) {
  const int m = Digit(code[0]);
  const int p = Digit(code[1]);
  if ((m == 0) != (p == 0)) {
    error = "NACA " + std::string(code) +
            ": camber and its position must both be zero or both non-zero";
    return false;
  }
  s.digits = 4;
  s.max_camber = m / 100.0;
  s.camber_position = p / 10.0;
  return true;
}

bool ParseFiveDigit(std::string_view code, NacaSection& s, std::string& error) {
  const int l = Digit(code[0]);
  const int p = Digit(code[1]);
  const int q = Digit(code[2]);
  const std::string prefix = "NACA " + std::string(code) + ": ";
  if (l == 0) {
    error = prefix + "design lift digit 0 (use a 4-digit 00xx code for a symmetric section)";
    return false;
  }
  if (p < 1 || p > 5) {
    error = prefix + "camber position digit must be 1..5";
    return false;
  }
  if (q > 1) {
    error = prefix + "third digit must be 0 (standard) or 1 (reflexed)";
    return false;
  }
  const FiveDigitRow& row = (q == 1 ? kReflexed : kStandard)[p - 1];
  if (row.k1 == 0.0) {
    error = prefix + "reflexed camber line with P = " + std::to_string(p) +
            " is not published (P must be 2..5)";
    return false;
  }
  s.digits = 5;
  s.reflexed = q == 1;
  s.camber_position = p * 0.05;
  s.m = row.m;
  s.k1 = row.k1;
  s.k2_over_k1 = row.k2_over_k1;
  s.camber_scale = l / 2.0;  // design lift 0.15 L; the table is for 0.3
  return true;
}

// The thickness distribution is 5 t (0.2969 sqrt(x) + polynomial(x)).
constexpr double kSqrtCoefficient = 0.2969;
struct Polynomial {
  double value;
  double derivative;
};
Polynomial ThicknessPolynomial(double x, TrailingEdge trailing_edge) {
  const double a4 = trailing_edge == TrailingEdge::kClosed ? 0.1036 : 0.1015;
  return {x * (-0.1260 + x * (-0.3516 + x * (0.2843 - a4 * x))),
          -0.1260 + x * (-0.7032 + x * (0.8529 - 4.0 * a4 * x))};
}

CamberPoint FiveDigitCamber(const NacaSection& s, double x) {
  const double m = s.m;
  const double k = s.k1 / 6.0 * s.camber_scale;
  CamberPoint c;
  if (!s.reflexed) {
    if (x < m) {
      c.y = k * (x * x * x - 3 * m * x * x + m * m * (3 - m) * x);
      c.slope = k * (3 * x * x - 6 * m * x + m * m * (3 - m));
      c.slope_rate = k * (6 * x - 6 * m);
    } else {
      c.y = k * m * m * m * (1 - x);
      c.slope = -k * m * m * m;
    }
    return c;
  }
  const double r = s.k2_over_k1;
  const double tail = r * std::pow(1 - m, 3) + m * m * m;
  const double d = x - m;
  const double a = x < m ? 1.0 : r;  // the cubic's weight on each side of m
  c.y = k * (a * d * d * d - tail * x + m * m * m);
  c.slope = k * (3 * a * d * d - tail);
  c.slope_rate = k * 6 * a * d;
  return c;
}

}  // namespace

std::optional<NacaSection> ParseNaca(std::string_view code, std::string& error) {
  if (code.size() != 4 && code.size() != 5) {
    error = "NACA code '" + std::string(code) + "' must have 4 or 5 digits";
    return std::nullopt;
  }
  for (const char c : code) {
    if (c < '0' || c > '9') {
      error = "NACA code '" + std::string(code) + "' must be digits only";
      return std::nullopt;
    }
  }
  NacaSection s;
  s.code = std::string(code);
  const std::size_t n = code.size();
  const int tt = 10 * Digit(code[n - 2]) + Digit(code[n - 1]);
  if (tt == 0) {
    error = "NACA " + s.code + ": thickness must be greater than 0";
    return std::nullopt;
  }
  s.thickness = tt / 100.0;
  const bool ok = n == 4 ? ParseFourDigit(code, s, error) : ParseFiveDigit(code, s, error);
  if (!ok) return std::nullopt;
  return s;
}

double NacaHalfThickness(const NacaSection& section, double x, TrailingEdge trailing_edge) {
  x = std::clamp(x, 0.0, 1.0);
  return 5.0 * section.thickness *
         (kSqrtCoefficient * std::sqrt(x) + ThicknessPolynomial(x, trailing_edge).value);
}

CamberPoint NacaCamber(const NacaSection& section, double x) {
  x = std::clamp(x, 0.0, 1.0);
  if (section.digits == 5) return FiveDigitCamber(section, x);
  CamberPoint c;
  const double m = section.max_camber;
  const double p = section.camber_position;
  if (m == 0.0) return c;
  if (x < p) {
    c.y = m / (p * p) * (2 * p * x - x * x);
    c.slope = 2 * m / (p * p) * (p - x);
    c.slope_rate = -2 * m / (p * p);
  } else {
    const double q = (1 - p) * (1 - p);
    c.y = m / q * ((1 - 2 * p) + 2 * p * x - x * x);
    c.slope = 2 * m / q * (p - x);
    c.slope_rate = -2 * m / q;
  }
  return c;
}

SurfacePair NacaSurfaceAt(const NacaSection& section, double x, TrailingEdge trailing_edge) {
  const double t = NacaHalfThickness(section, x, trailing_edge);
  const CamberPoint c = NacaCamber(section, x);
  const double theta = std::atan(c.slope);
  const Eigen::Vector2d offset(-t * std::sin(theta), t * std::cos(theta));
  const Eigen::Vector2d on_camber(std::clamp(x, 0.0, 1.0), c.y);
  return {on_camber + offset, on_camber - offset};
}

double NacaLeadingEdgeRadius(const NacaSection& section) {
  return 1.1019 * section.thickness * section.thickness;
}

std::vector<double> CosineSpacing(int n) {
  assert(n >= 2);
  std::vector<double> x(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) x[i] = 0.5 * (1.0 - std::cos(kPi * i / (n - 1)));
  x.front() = 0.0;
  x.back() = 1.0;
  return x;
}

std::vector<Eigen::Vector2d> NacaCoordinates(const NacaSection& section, int stations_per_side,
                                             TrailingEdge trailing_edge) {
  const std::vector<double> x = CosineSpacing(stations_per_side);
  std::vector<Eigen::Vector2d> points;
  points.reserve(2 * x.size() - 1);
  for (auto it = x.rbegin(); it != x.rend(); ++it) {
    points.push_back(NacaSurfaceAt(section, *it, trailing_edge).upper);
  }
  for (std::size_t i = 1; i < x.size(); ++i) {
    points.push_back(NacaSurfaceAt(section, x[i], trailing_edge).lower);
  }
  return points;
}

Eigen::Vector2d NacaContourPoint(const NacaSection& section, double s, TrailingEdge trailing_edge) {
  return NacaContour(section, s, trailing_edge).point;
}

ContourPoint NacaContour(const NacaSection& section, double s, TrailingEdge trailing_edge) {
  // With x = cos^2(pi s), sqrt(x) = |cos(pi s)|: the signed half thickness
  // h = 5 t (0.2969 cos(pi s) +- polynomial(x)) (+ upper, - lower) is smooth at the nose.
  s = std::clamp(s, 0.0, 1.0);
  const double cos_s = std::cos(kPi * s);
  const double x = cos_s * cos_s;
  const double x_s = -kPi * std::sin(2.0 * kPi * s);
  const double side = s <= 0.5 ? 1.0 : -1.0;
  const Polynomial rest = ThicknessPolynomial(x, trailing_edge);
  const double five_t = 5.0 * section.thickness;
  const double h = five_t * (kSqrtCoefficient * cos_s + side * rest.value);
  const double h_s =
      five_t * (-kSqrtCoefficient * kPi * std::sin(kPi * s) + side * rest.derivative * x_s);
  const CamberPoint c = NacaCamber(section, x);
  const double theta = std::atan(c.slope);
  const double theta_s = c.slope_rate * x_s / (1.0 + c.slope * c.slope);
  const double sn = std::sin(theta);
  const double cs = std::cos(theta);
  ContourPoint out;
  out.point = {x - h * sn, c.y + h * cs};
  out.derivative = {x_s - h_s * sn - h * cs * theta_s, c.slope * x_s + h_s * cs - h * sn * theta_s};
  return out;
}

std::optional<Wing> Wing::Make(const WingSpec& spec, std::string& error) {
  const auto positive = [&](double v, const char* what) {
    if (std::isfinite(v) && v > 0.0) return true;
    error = std::string("wing ") + what + " must be positive and finite";
    return false;
  };
  const auto angle = [&](double v, const char* what) {
    if (std::isfinite(v) && std::abs(v) < 0.5 * kPi) return true;
    error = std::string("wing ") + what + " must lie strictly between -90 and 90 deg";
    return false;
  };
  if (!positive(spec.root_chord_mm, "root chord") || !positive(spec.tip_chord_mm, "tip chord") ||
      !positive(spec.span_mm, "span") || !angle(spec.sweep_rad, "sweep") ||
      !angle(spec.dihedral_rad, "dihedral") || !angle(spec.washout_rad, "twist")) {
    return std::nullopt;
  }
  std::string code_error;
  std::optional<NacaSection> root = ParseNaca(spec.root_code, code_error);
  if (!root) {
    error = "wing root section: " + code_error;
    return std::nullopt;
  }
  std::optional<NacaSection> tip = ParseNaca(spec.tip_code, code_error);
  if (!tip) {
    error = "wing tip section: " + code_error;
    return std::nullopt;
  }
  return Wing(spec, std::move(*root), std::move(*tip));
}

Eigen::Vector3d Wing::SectionPoint(bool tip, double s) const { return PlacedSection(tip, s).point; }

Wing::Placed Wing::PlacedSection(bool tip, double s) const {
  const NacaSection& section = tip ? tip_ : root_;
  const double chord = tip ? spec_.tip_chord_mm : spec_.root_chord_mm;
  const ContourPoint contour = NacaContour(section, s, spec_.trailing_edge);
  // Washout about the quarter chord: (x - c/4, z) turned by +washout in the (x, z) plane,
  // which lowers the leading edge (x < c/4) and raises the trailing edge: nose down.
  const double twist = tip ? spec_.washout_rad : 0.0;
  const double c = std::cos(twist);
  const double sn = std::sin(twist);
  const auto turn = [&](const Eigen::Vector2d& v) {
    return Eigen::Vector3d(c * v.x() - sn * v.y(), 0.0, sn * v.x() + c * v.y());
  };
  const Eigen::Vector3d quarter(0.25 * chord, 0.0, 0.0);
  const double span = tip ? spec_.span_mm : 0.0;
  const Eigen::Vector3d offset(span * std::tan(spec_.sweep_rad), span,
                               span * std::tan(spec_.dihedral_rad));
  const Eigen::Vector2d p = chord * contour.point - Eigen::Vector2d(0.25 * chord, 0.0);
  return {offset + quarter + turn(p), chord * turn(contour.derivative)};
}

Eigen::Vector3d Wing::Point(double s, double eta) const {
  eta = std::clamp(eta, 0.0, 1.0);
  return (1.0 - eta) * SectionPoint(false, s) + eta * SectionPoint(true, s);
}

WingDerivatives Wing::Derivatives(double s, double eta) const {
  eta = std::clamp(eta, 0.0, 1.0);
  const Placed root = PlacedSection(false, s);
  const Placed tip = PlacedSection(true, s);
  WingDerivatives d;
  d.point = (1.0 - eta) * root.point + eta * tip.point;
  d.d_ds = (1.0 - eta) * root.d_ds + eta * tip.d_ds;
  d.d_deta = tip.point - root.point;
  return d;
}

Eigen::Vector3d Wing::Normal(double s, double eta) const {
  const WingDerivatives d = Derivatives(std::clamp(s, 1e-6, 1.0 - 1e-6), eta);
  return d.d_deta.cross(d.d_ds).normalized();
}

WingGrid SampleWing(const Wing& wing, int count_s, int count_eta) {
  assert(count_s >= 2 && count_eta >= 2);
  WingGrid grid;
  grid.count_s = count_s;
  grid.count_eta = count_eta;
  grid.points.reserve(static_cast<std::size_t>(count_s) * count_eta);
  for (int j = 0; j < count_eta; ++j) {
    const double eta = static_cast<double>(j) / (count_eta - 1);
    for (int i = 0; i < count_s; ++i) {
      grid.points.push_back(wing.Point(static_cast<double>(i) / (count_s - 1), eta));
    }
  }
  return grid;
}

}  // namespace stitchsim::geom
