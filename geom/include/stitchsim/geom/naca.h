#pragma once
// NACA 4-digit (MPXX) and 5-digit (LPQTT) wing sections and a wing lofted linearly between a
// root and a tip section (seed 002). Pure math: sections in chord fractions, the wing in mm.
// Formulas: Abbott and von Doenhoff, "Theory of Wing Sections" (1959), section 6.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace stitchsim::geom {

/// The last coefficient of the thickness polynomial: -0.1015 leaves the published open
/// trailing edge (0.0021 * 5 t thick), -0.1036 closes it to a point.
enum class TrailingEdge { kOpen, kClosed };

/// A parsed NACA code. All lengths are fractions of the chord.
struct NacaSection {
  std::string code;              ///< as given, e.g. "23012"
  int digits = 4;                ///< 4 or 5
  double thickness = 0.0;        ///< t: maximum thickness / chord
  double max_camber = 0.0;       ///< 4-digit: m, maximum camber / chord (0 for 00xx)
  double camber_position = 0.0;  ///< 4-digit: p; 5-digit: nominal position of max camber
  bool reflexed = false;         ///< 5-digit Q = 1
  double m = 0.0;                ///< 5-digit: where the camber line's cubic ends (table)
  double k1 = 0.0;               ///< 5-digit: camber constant for design lift 0.3 (table)
  double k2_over_k1 = 0.0;       ///< 5-digit reflexed: ratio from the table
  double camber_scale = 1.0;     ///< 5-digit: design lift / 0.3 (= L / 2)
};

/// Parses "0012", "2412", "23012", "23112"...; nullopt and `error` set when the code is not
/// a supported NACA section (length, non-digits, zero thickness, reflexed P outside 2..5).
std::optional<NacaSection> ParseNaca(std::string_view code, std::string& error);

/// Half thickness y_t / chord at chord fraction x in [0, 1] (perpendicular to the camber).
double NacaHalfThickness(const NacaSection& section, double x, TrailingEdge trailing_edge);

/// Camber line height y_c / chord and its slope dy_c/dx at chord fraction x in [0, 1].
struct CamberPoint {
  double y = 0.0;
  double slope = 0.0;
  double slope_rate = 0.0;  ///< d^2 y_c / dx^2
};
CamberPoint NacaCamber(const NacaSection& section, double x);

/// Upper and lower surface points (chord fractions) at camber-line station x: the half
/// thickness laid off perpendicular to the camber line.
struct SurfacePair {
  Eigen::Vector2d upper = Eigen::Vector2d::Zero();
  Eigen::Vector2d lower = Eigen::Vector2d::Zero();
};
SurfacePair NacaSurfaceAt(const NacaSection& section, double x, TrailingEdge trailing_edge);

/// Leading-edge radius / chord: 1.1019 t^2.
double NacaLeadingEdgeRadius(const NacaSection& section);

/// Cosine spacing: n >= 2 stations x_i = (1 - cos(pi i / (n - 1))) / 2, from 0 to 1.
std::vector<double> CosineSpacing(int n);

/// Section coordinates in Selig order (chord fractions): the upper surface from the trailing
/// edge to the leading edge, then the lower back to the trailing edge, at `stations_per_side`
/// >= 2 cosine-spaced camber stations each (2 stations_per_side - 1 points, nose shared).
std::vector<Eigen::Vector2d> NacaCoordinates(const NacaSection& section, int stations_per_side,
                                             TrailingEdge trailing_edge);

/// The point of the closed contour at s in [0, 1] (chord fractions): s = 0 the upper
/// trailing edge, s = 0.5 the leading edge, s = 1 the lower trailing edge; the station is
/// x = (1 + cos(2 pi s)) / 2, so equal steps in s are cosine spaced in x.
Eigen::Vector2d NacaContourPoint(const NacaSection& section, double s, TrailingEdge trailing_edge);

/// A contour point (chord fractions) and its derivative with respect to s.
struct ContourPoint {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  Eigen::Vector2d derivative = Eigen::Vector2d::Zero();  ///< d point / ds; zero at s = 0, 1
};
/// NacaContourPoint with its s derivative (smooth through the leading edge).
ContourPoint NacaContour(const NacaSection& section, double s, TrailingEdge trailing_edge);

/// A point of the wing and its partial derivatives (mm per unit s or eta).
struct WingDerivatives {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d d_ds = Eigen::Vector3d::Zero();
  Eigen::Vector3d d_deta = Eigen::Vector3d::Zero();
};

/// The wing as given (lengths mm, angles rad). Frame: x aft along the root chord, y along
/// the span, z up; the root leading edge at the origin. Sections stay streamwise (parallel
/// to x-z); the span is measured along y.
struct WingSpec {
  std::string root_code;
  double root_chord_mm = 0.0;
  std::string tip_code;
  double tip_chord_mm = 0.0;
  double span_mm = 0.0;
  double sweep_rad = 0.0;     ///< leading-edge sweep: the tip leading edge at span tan(sweep) aft
  double dihedral_rad = 0.0;  ///< the tip section raised by span tan(dihedral)
  double washout_rad = 0.0;   ///< tip twist, positive nose down, about its quarter chord
  TrailingEdge trailing_edge = TrailingEdge::kClosed;
};

/// A validated wing: a ruled (linear) loft between the placed root and tip sections.
class Wing {
 public:
  /// nullopt and `error` set for a chord or span that is not positive and finite, a bad
  /// code or an angle outside (-90, 90) deg.
  static std::optional<Wing> Make(const WingSpec& spec, std::string& error);

  const WingSpec& Spec() const { return spec_; }
  const NacaSection& Root() const { return root_; }
  const NacaSection& Tip() const { return tip_; }
  /// The placed section at eta = 0 (root) or 1 (tip): the 2D contour scaled by its chord,
  /// twisted, then swept and raised; s as NacaContourPoint.
  Eigen::Vector3d SectionPoint(bool tip, double s) const;
  /// The loft at (s, eta): (1 - eta) root(s) + eta tip(s); s, eta in [0, 1].
  Eigen::Vector3d Point(double s, double eta) const;
  /// Point(s, eta) with its partial derivatives.
  WingDerivatives Derivatives(double s, double eta) const;
  /// Unit outward normal (d/deta x d/ds); s is kept 1e-6 inside (0, 1), where the trailing
  /// edge's crease leaves the normal undefined.
  Eigen::Vector3d Normal(double s, double eta) const;

 private:
  struct Placed {
    Eigen::Vector3d point;
    Eigen::Vector3d d_ds;
  };
  Placed PlacedSection(bool tip, double s) const;
  Wing(const WingSpec& spec, NacaSection root, NacaSection tip)
      : spec_(spec), root_(std::move(root)), tip_(std::move(tip)) {}
  WingSpec spec_;
  NacaSection root_;
  NacaSection tip_;
};

/// Points of the loft on a regular (s, eta) grid for surface fitting.
struct WingGrid {
  int count_s = 0;                      ///< samples around the contour, s = i / (count_s - 1)
  int count_eta = 0;                    ///< samples along the span, eta = j / (count_eta - 1)
  std::vector<Eigen::Vector3d> points;  ///< mm, index j * count_s + i
  const Eigen::Vector3d& At(int i, int j) const { return points[j * count_s + i]; }
};
/// The grid of `wing`; count_s, count_eta >= 2.
WingGrid SampleWing(const Wing& wing, int count_s, int count_eta);

}  // namespace stitchsim::geom
