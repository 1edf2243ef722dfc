// NACA 4- and 5-digit sections against closed forms and published values, and the lofted wing
// (seed 002: root NACA 23014 chord 225.81 cm, tip NACA 23012 chord 113.03 cm, span 731.01 cm).
#include "stitchsim/geom/naca.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>

#include "seed_wing.h"
#include "stitchsim/common/units.h"

namespace stitchsim::geom {
namespace {

NacaSection Parse(const std::string& code) {
  std::string error;
  const std::optional<NacaSection> s = ParseNaca(code, error);
  EXPECT_TRUE(s.has_value()) << code << ": " << error;
  return s.value_or(NacaSection{});
}

// The x in [0, 1] of the camber line's highest point, by a fine scan.
double CamberPeak(const NacaSection& s) {
  double best_x = 0.0;
  double best_y = -1.0;
  for (int i = 0; i <= 200000; ++i) {
    const double x = i / 200000.0;
    const double y = NacaCamber(s, x).y;
    if (y > best_y) {
      best_y = y;
      best_x = x;
    }
  }
  return best_x;
}

TEST(NacaParse, ReadsFourAndFiveDigitCodes) {
  const NacaSection a = Parse("0012");
  EXPECT_EQ(a.digits, 4);
  EXPECT_DOUBLE_EQ(a.thickness, 0.12);
  EXPECT_DOUBLE_EQ(a.max_camber, 0.0);
  const NacaSection b = Parse("2412");
  EXPECT_DOUBLE_EQ(b.max_camber, 0.02);
  EXPECT_DOUBLE_EQ(b.camber_position, 0.4);
  const NacaSection c = Parse("23012");
  EXPECT_EQ(c.digits, 5);
  EXPECT_FALSE(c.reflexed);
  EXPECT_DOUBLE_EQ(c.m, 0.2025);
  EXPECT_DOUBLE_EQ(c.k1, 15.957);
  EXPECT_DOUBLE_EQ(c.camber_scale, 1.0);
  EXPECT_DOUBLE_EQ(Parse("23014").thickness, 0.14);
  const NacaSection r = Parse("23112");
  EXPECT_TRUE(r.reflexed);
  EXPECT_DOUBLE_EQ(r.m, 0.2170);
  EXPECT_DOUBLE_EQ(r.k1, 15.793);
  EXPECT_DOUBLE_EQ(r.k2_over_k1, 0.00677);
  EXPECT_DOUBLE_EQ(Parse("44012").camber_scale, 2.0);  // design lift 0.6
}

TEST(NacaParse, BadCodesAreMessagesNotThrows) {
  for (const char* code : {"123456789", "", "012", "00a2", "O012", "0000", "23000", "21112",
                           "23212", "26012", "03012", "2012", "0412", "-012"}) {
    std::string error;
    EXPECT_FALSE(ParseNaca(code, error).has_value()) << code;
    EXPECT_FALSE(error.empty()) << code;
  }
  std::string error;
  ParseNaca("21112", error);
  EXPECT_NE(error.find("reflexed"), std::string::npos) << error;
  ParseNaca("123456789", error);
  EXPECT_NE(error.find("4 or 5 digits"), std::string::npos) << error;
  ParseNaca("0000", error);
  EXPECT_NE(error.find("thickness"), std::string::npos) << error;
}

TEST(NacaThickness, PublishedValuesAndTrailingEdges) {
  const NacaSection s = Parse("0012");
  // Abbott and von Doenhoff, NACA 0012 ordinates: 6.002 % at 30 % chord.
  EXPECT_NEAR(NacaHalfThickness(s, 0.3, TrailingEdge::kOpen), 0.06002, 2e-5);
  EXPECT_NEAR(NacaHalfThickness(s, 0.3, TrailingEdge::kClosed), 0.06002, 2e-5);
  EXPECT_NEAR(NacaHalfThickness(s, 1.0, TrailingEdge::kClosed), 0.0, 1e-12);
  EXPECT_NEAR(NacaHalfThickness(s, 1.0, TrailingEdge::kOpen), 5 * 0.12 * 0.0021, 1e-12);
  EXPECT_DOUBLE_EQ(NacaHalfThickness(s, 0.0, TrailingEdge::kOpen), 0.0);
  // Maximum thickness t at about 30 % chord.
  double peak = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    peak = std::max(peak, NacaHalfThickness(s, i / 1000.0, TrailingEdge::kOpen));
  }
  EXPECT_NEAR(2 * peak, 0.12, 2e-4);
}

// The surface height at surface abscissa x (not camber station), by bisection on the station.
double OrdinateAt(const NacaSection& s, double x, bool upper) {
  double lo = 0.0;
  double hi = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    const SurfacePair p = NacaSurfaceAt(s, mid, TrailingEdge::kOpen);
    ((upper ? p.upper : p.lower).x() < x ? lo : hi) = mid;
  }
  const SurfacePair p = NacaSurfaceAt(s, lo, TrailingEdge::kOpen);
  return (upper ? p.upper : p.lower).y();
}

TEST(NacaSurface, Naca23012MatchesPublishedOrdinates) {
  // Abbott and von Doenhoff, Appendix I, NACA 23012, per cent chord (rounded to 0.01 %).
  struct Row {
    double x, upper, lower;
  };
  const Row rows[] = {{2.5, 3.61, -1.71}, {5, 4.91, -2.26},  {15, 7.19, -3.50}, {30, 7.55, -4.46},
                      {50, 6.41, -4.17},  {80, 3.08, -2.16}, {95, 0.92, -0.70}, {100, 0.13, -0.13}};
  const NacaSection s = Parse("23012");
  for (const Row& r : rows) {
    EXPECT_NEAR(100 * OrdinateAt(s, r.x / 100, true), r.upper, 0.03) << r.x;
    EXPECT_NEAR(100 * OrdinateAt(s, r.x / 100, false), r.lower, 0.03) << r.x;
  }
}

TEST(NacaThickness, LeadingEdgeRadiusMatchesTheSquareRootTerm) {
  // Near the nose y_t^2 ~ 2 r x: the osculating circle of radius r = 1.1019 t^2.
  for (const char* code : {"0012", "23014", "2406"}) {
    const NacaSection s = Parse(code);
    const double x = 1e-12;
    const double yt = NacaHalfThickness(s, x, TrailingEdge::kClosed);
    const double radius = yt * yt / (2 * x);
    EXPECT_NEAR(radius / NacaLeadingEdgeRadius(s), 1.0, 1e-4) << code;
    EXPECT_NEAR(NacaLeadingEdgeRadius(s), 1.1019 * s.thickness * s.thickness, 1e-15);
  }
}

TEST(NacaCamberLine, FourDigitMaxCamberAtP) {
  const NacaSection s = Parse("2412");
  EXPECT_NEAR(NacaCamber(s, 0.4).y, 0.02, 1e-15);
  EXPECT_NEAR(NacaCamber(s, 0.4).slope, 0.0, 1e-15);
  EXPECT_NEAR(CamberPeak(s), 0.4, 1e-5);
  EXPECT_NEAR(NacaCamber(s, 0.0).y, 0.0, 1e-15);
  EXPECT_NEAR(NacaCamber(s, 1.0).y, 0.0, 1e-15);
}

TEST(NacaCamberLine, FiveDigitPeakNearFifteenPercent) {
  const NacaSection s = Parse("23012");
  // dy/dx = 0 at x = m (1 - sqrt(m / 3)) = 0.1499 for m = 0.2025.
  EXPECT_NEAR(CamberPeak(s), 0.2025 * (1 - std::sqrt(0.2025 / 3)), 1e-5);
  EXPECT_NEAR(CamberPeak(s), 0.15, 2e-3);
  EXPECT_NEAR(NacaCamber(s, 0.0).y, 0.0, 1e-15);
  EXPECT_NEAR(NacaCamber(s, 1.0).y, 0.0, 1e-15);
  // Aft of m the mean line is straight: k1 m^3 / 6 (1 - x).
  EXPECT_NEAR(NacaCamber(s, 0.6).y, 15.957 * std::pow(0.2025, 3) / 6 * 0.4, 1e-15);
}

TEST(NacaCamberLine, FiveDigitDesignLiftScalesTheMeanLine) {
  // NACA 230xx: maximum camber 1.84 % (published: 1.8 % at 15 %); L = 4 doubles it.
  const NacaSection s = Parse("23012");
  EXPECT_NEAR(NacaCamber(s, CamberPeak(s)).y, 0.0184, 1e-4);
  const NacaSection doubled = Parse("43012");
  for (double x : {0.05, 0.15, 0.5, 0.9}) {
    EXPECT_NEAR(NacaCamber(doubled, x).y, 2 * NacaCamber(s, x).y, 1e-15);
  }
}

TEST(NacaCamberLine, SlopeIsTheDerivativeAndContinuous) {
  for (const char* code : {"2412", "4415", "23012", "25012", "23112", "22112", "25112", "43012"}) {
    const NacaSection s = Parse(code);
    const double h = 1e-6;
    for (int i = 1; i < 200; ++i) {
      const double x = i / 200.0;
      const double fd = (NacaCamber(s, x + h).y - NacaCamber(s, x - h).y) / (2 * h);
      EXPECT_NEAR(NacaCamber(s, x).slope, fd, 1e-6) << code << " x " << x;
    }
    const double joint = s.digits == 4 ? s.camber_position : s.m;
    EXPECT_NEAR(NacaCamber(s, joint - 1e-12).y, NacaCamber(s, joint + 1e-12).y, 1e-10) << code;
    EXPECT_NEAR(NacaCamber(s, joint - 1e-12).slope, NacaCamber(s, joint + 1e-12).slope, 1e-9)
        << code;
    EXPECT_NEAR(NacaCamber(s, 0.0).y, 0.0, 1e-14) << code;
    EXPECT_NEAR(NacaCamber(s, 1.0).y, 0.0, 1e-14) << code;
  }
}

TEST(NacaSurface, ThicknessLaidOffPerpendicularToTheCamberLine) {
  for (const char* code : {"2412", "23012", "23112"}) {
    const NacaSection s = Parse(code);
    for (double x : {0.01, 0.1, 0.2, 0.5, 0.9}) {
      const CamberPoint c = NacaCamber(s, x);
      const SurfacePair p = NacaSurfaceAt(s, x, TrailingEdge::kOpen);
      const Eigen::Vector2d on_camber(x, c.y);
      const Eigen::Vector2d tangent(1.0, c.slope);
      const double yt = NacaHalfThickness(s, x, TrailingEdge::kOpen);
      EXPECT_NEAR((p.upper - on_camber).norm(), yt, 1e-14);
      EXPECT_NEAR((p.lower - on_camber).norm(), yt, 1e-14);
      EXPECT_NEAR((p.upper - on_camber).dot(tangent), 0.0, 1e-14);
      EXPECT_NEAR((p.lower - on_camber).dot(tangent), 0.0, 1e-14);
      EXPECT_GT(p.upper.y(), p.lower.y());
    }
  }
}

TEST(NacaSurface, SymmetricSectionsMirror) {
  const NacaSection s = Parse("0012");
  for (double x : {0.0, 0.05, 0.3, 0.7, 1.0}) {
    const SurfacePair p = NacaSurfaceAt(s, x, TrailingEdge::kOpen);
    EXPECT_DOUBLE_EQ(p.upper.x(), x);
    EXPECT_DOUBLE_EQ(p.lower.x(), x);
    EXPECT_DOUBLE_EQ(p.upper.y(), -p.lower.y());
  }
  for (double u : {0.0, 0.1, 0.25, 0.4}) {
    const Eigen::Vector2d a = NacaContourPoint(s, u, TrailingEdge::kClosed);
    const Eigen::Vector2d b = NacaContourPoint(s, 1.0 - u, TrailingEdge::kClosed);
    EXPECT_NEAR(a.x(), b.x(), 1e-14);
    EXPECT_NEAR(a.y(), -b.y(), 1e-14);
  }
}

TEST(NacaSurface, ContourRunsUpperTrailingEdgeToNoseToLower) {
  const NacaSection s = Parse("23012");
  EXPECT_TRUE(NacaContourPoint(s, 0.5, TrailingEdge::kOpen).isZero(1e-15));
  const Eigen::Vector2d te_up = NacaContourPoint(s, 0.0, TrailingEdge::kClosed);
  const Eigen::Vector2d te_low = NacaContourPoint(s, 1.0, TrailingEdge::kClosed);
  EXPECT_TRUE(te_up.isApprox(te_low, 1e-12));
  EXPECT_NEAR(te_up.x(), 1.0, 1e-12);
  EXPECT_GT(NacaContourPoint(s, 0.0, TrailingEdge::kOpen).y(),
            NacaContourPoint(s, 1.0, TrailingEdge::kOpen).y());
  EXPECT_GT(NacaContourPoint(s, 0.3, TrailingEdge::kOpen).y(), 0.0);
  EXPECT_LT(NacaContourPoint(s, 0.7, TrailingEdge::kOpen).y(), 0.0);
}

TEST(NacaSurface, ContourIsSmoothThroughTheLeadingEdge) {
  // With x = sin^2(pi (s - 0.5)) the square-root nose becomes smooth in s: one-sided
  // difference quotients at s = 0.5 agree (the loft has no crease at the leading edge).
  for (const char* code : {"0012", "2412", "23014", "23112"}) {
    const NacaSection sec = Parse(code);
    const double h = 1e-6;
    const Eigen::Vector2d nose = NacaContourPoint(sec, 0.5, TrailingEdge::kClosed);
    const Eigen::Vector2d ahead =
        (NacaContourPoint(sec, 0.5 + h, TrailingEdge::kClosed) - nose) / h;
    const Eigen::Vector2d behind =
        (nose - NacaContourPoint(sec, 0.5 - h, TrailingEdge::kClosed)) / h;
    EXPECT_LT((ahead - behind).norm(), 1e-4 * ahead.norm()) << code;
    EXPECT_GT(ahead.norm(), 0.1) << code;  // a regular parametrisation, not a stall
  }
}

TEST(NacaSurface, ContourAgreesWithTheStationFormula) {
  // NacaContour works in s (sqrt(x) = |cos(pi s)|); NacaSurfaceAt in x: one answer.
  for (const char* code : {"0012", "2412", "23014", "23112"}) {
    const NacaSection sec = Parse(code);
    for (TrailingEdge te : {TrailingEdge::kOpen, TrailingEdge::kClosed}) {
      for (int i = 0; i <= 100; ++i) {
        const double s = i / 100.0;
        const SurfacePair pair = NacaSurfaceAt(sec, 0.5 * (1 + std::cos(2 * kPi * s)), te);
        const Eigen::Vector2d expected = s <= 0.5 ? pair.upper : pair.lower;
        EXPECT_LT((NacaContourPoint(sec, s, te) - expected).norm(), 1e-12) << code << " " << s;
      }
    }
  }
}

TEST(NacaSurface, ContourDerivativeMatchesDifferences) {
  for (const char* code : {"0012", "2412", "23014", "23112", "25012"}) {
    const NacaSection sec = Parse(code);
    const double h = 1e-6;
    for (int i = 1; i < 100; ++i) {
      const double s = i / 100.0;
      const Eigen::Vector2d fd = (NacaContourPoint(sec, s + h, TrailingEdge::kOpen) -
                                  NacaContourPoint(sec, s - h, TrailingEdge::kOpen)) /
                                 (2 * h);
      const Eigen::Vector2d d = NacaContour(sec, s, TrailingEdge::kOpen).derivative;
      EXPECT_LT((d - fd).norm(), 1e-6) << code << " s " << s;
    }
  }
}

TEST(NacaSpacing, CosineStations) {
  const std::vector<double> x = CosineSpacing(5);
  ASSERT_EQ(x.size(), 5u);
  EXPECT_DOUBLE_EQ(x[0], 0.0);
  EXPECT_NEAR(x[1], (1 - std::sqrt(0.5)) / 2, 1e-15);
  EXPECT_NEAR(x[2], 0.5, 1e-15);
  EXPECT_DOUBLE_EQ(x[4], 1.0);
  const std::vector<double> many = CosineSpacing(101);
  for (std::size_t i = 1; i < many.size(); ++i) EXPECT_GT(many[i], many[i - 1]);
  // Denser at the nose and the trailing edge than mid-chord.
  EXPECT_LT(many[1] - many[0], many[51] - many[50]);
}

TEST(NacaSpacing, SeligCoordinatesFollowTheContour) {
  const NacaSection s = Parse("23014");
  const std::vector<Eigen::Vector2d> points = NacaCoordinates(s, 41, TrailingEdge::kOpen);
  ASSERT_EQ(points.size(), 81u);
  EXPECT_TRUE(points[40].isZero(1e-15));  // the nose
  // Equal steps in s are the cosine stations: the coordinates are the contour at s = i / 80.
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d c = NacaContourPoint(s, i / 80.0, TrailingEdge::kOpen);
    EXPECT_LT((points[i] - c).norm(), 1e-12) << i;
  }
  EXPECT_GT(points.front().y(), points.back().y());  // open trailing edge, upper first
}

WingSpec SeedWing() { return testing::SeedWingSpec(); }

WingSpec SweptTwistedSeedWing() { return testing::SweptTwistedSeedWingSpec(); }

Wing MakeOrFail(const WingSpec& spec) {
  std::string error;
  std::optional<Wing> wing = Wing::Make(spec, error);
  EXPECT_TRUE(wing.has_value()) << error;
  return *wing;
}

TEST(NacaWing, SeedChordsAndSpanReproduced) {
  const Wing wing = MakeOrFail(SeedWing());
  const auto chord_at = [&](double eta) {
    return (wing.Point(0.0, eta) - wing.Point(0.5, eta)).norm();
  };
  EXPECT_NEAR(chord_at(0.0), 2258.1, 1e-9);
  EXPECT_NEAR(chord_at(1.0), 1130.3, 1e-9);
  EXPECT_NEAR(chord_at(0.5), (2258.1 + 1130.3) / 2, 1e-9);  // linear taper
  EXPECT_NEAR(wing.Point(0.3, 1.0).y() - wing.Point(0.3, 0.0).y(), 7310.1, 1e-9);
  // Root thickness 14 %, tip 12 % of the local chord.
  double root_top = 0.0;
  double tip_top = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double s = i / 2000.0;
    root_top = std::max(root_top, wing.Point(s, 0.0).z() - wing.Point(1.0 - s, 0.0).z());
    tip_top = std::max(tip_top, wing.Point(s, 1.0).z() - wing.Point(1.0 - s, 1.0).z());
  }
  EXPECT_NEAR(root_top / 2258.1, 0.14, 2e-3);
  EXPECT_NEAR(tip_top / 1130.3, 0.12, 2e-3);
}

TEST(NacaWing, EndSectionsAreTheScaledTwistedSweptSections) {
  const WingSpec spec = SweptTwistedSeedWing();
  const Wing wing = MakeOrFail(spec);
  const NacaSection root = Parse("23014");
  const NacaSection tip = Parse("23012");
  // Independent route: an Eigen rotation about -y (nose down) at the quarter chord.
  const Eigen::Vector3d quarter(0.25 * spec.tip_chord_mm, 0, 0);
  const Eigen::Matrix3d washout =
      Eigen::AngleAxisd(-spec.washout_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d offset(spec.span_mm * std::tan(spec.sweep_rad), spec.span_mm,
                               spec.span_mm * std::tan(spec.dihedral_rad));
  for (int i = 0; i <= 40; ++i) {
    const double s = i / 40.0;
    const Eigen::Vector2d r2 = spec.root_chord_mm * NacaContourPoint(root, s, spec.trailing_edge);
    EXPECT_LT((wing.Point(s, 0.0) - Eigen::Vector3d(r2.x(), 0, r2.y())).norm(), 1e-9) << s;
    const Eigen::Vector2d t2 = spec.tip_chord_mm * NacaContourPoint(tip, s, spec.trailing_edge);
    const Eigen::Vector3d expected =
        offset + quarter + washout * (Eigen::Vector3d(t2.x(), 0, t2.y()) - quarter);
    EXPECT_LT((wing.Point(s, 1.0) - expected).norm(), 1e-9) << s;
    EXPECT_LT((wing.SectionPoint(true, s) - expected).norm(), 1e-9) << s;
  }
  // Nose down: the tip leading edge below, the trailing edge above, the quarter-chord height.
  const double quarter_z = offset.z();
  EXPECT_LT(wing.Point(0.5, 1.0).z(), quarter_z);
  EXPECT_GT(wing.Point(0.0, 1.0).z(), quarter_z);
  // The tip leading edge sits at span tan(sweep) aft, twist moving it only by c/4 (1 - cos).
  EXPECT_NEAR(wing.Point(0.5, 1.0).x(),
              offset.x() + 0.25 * spec.tip_chord_mm * (1 - std::cos(spec.washout_rad)), 1e-9);
  // Twist keeps the chord.
  EXPECT_NEAR((wing.Point(0.0, 1.0) - wing.Point(0.5, 1.0)).norm(), spec.tip_chord_mm, 1e-9);
}

TEST(NacaWing, DerivativesAndOutwardNormal) {
  const WingSpec spec = SweptTwistedSeedWing();
  const Wing wing = MakeOrFail(spec);
  const double h = 1e-6;
  for (double eta : {0.0, 0.3, 1.0}) {
    for (double s : {0.05, 0.25, 0.49, 0.5, 0.51, 0.75, 0.95}) {
      const WingDerivatives d = wing.Derivatives(s, eta);
      EXPECT_TRUE(d.point.isApprox(wing.Point(s, eta), 1e-14));
      const Eigen::Vector3d fd_s = (wing.Point(s + h, eta) - wing.Point(s - h, eta)) / (2 * h);
      EXPECT_LT((d.d_ds - fd_s).norm(), 1e-5 * d.d_ds.norm()) << s << " " << eta;
      const double e0 = std::max(0.0, eta - h);
      const double e1 = std::min(1.0, eta + h);
      const Eigen::Vector3d fd_eta = (wing.Point(s, e1) - wing.Point(s, e0)) / (e1 - e0);
      EXPECT_LT((d.d_deta - fd_eta).norm(), 1e-5 * d.d_deta.norm()) << s << " " << eta;
      const Eigen::Vector3d n = wing.Normal(s, eta);
      EXPECT_NEAR(n.norm(), 1.0, 1e-12);
      EXPECT_NEAR(n.dot(d.d_ds.normalized()), 0.0, 1e-12);
      EXPECT_NEAR(n.dot(d.d_deta.normalized()), 0.0, 1e-12);
    }
    EXPECT_GT(wing.Normal(0.25, eta).z(), 0.9);   // upper surface: up
    EXPECT_LT(wing.Normal(0.75, eta).z(), -0.9);  // lower surface: down
    EXPECT_LT(wing.Normal(0.5, eta).x(), -0.9);   // nose: forward
  }
}

TEST(NacaWing, GridSamplesTheLoft) {
  const Wing wing = MakeOrFail(SeedWing());
  const WingGrid grid = SampleWing(wing, 9, 5);
  ASSERT_EQ(grid.points.size(), 45u);
  EXPECT_TRUE(grid.At(0, 0).isApprox(wing.Point(0.0, 0.0)));
  EXPECT_TRUE(grid.At(4, 2).isApprox(wing.Point(0.5, 0.5)));
  EXPECT_TRUE(grid.At(8, 4).isApprox(wing.Point(1.0, 1.0)));
  // Linear loft: every spanwise line is straight.
  for (int i = 0; i < 9; ++i) {
    const Eigen::Vector3d mid = 0.5 * (grid.At(i, 0) + grid.At(i, 4));
    EXPECT_LT((grid.At(i, 2) - mid).norm(), 1e-9);
  }
}

TEST(NacaWing, InvalidSpecsAreMessages) {
  const auto error_of = [](const WingSpec& spec) {
    std::string error;
    EXPECT_FALSE(Wing::Make(spec, error).has_value());
    return error;
  };
  WingSpec spec = SeedWing();
  spec.root_chord_mm = 0.0;
  EXPECT_NE(error_of(spec).find("root chord"), std::string::npos);
  spec = SeedWing();
  spec.tip_chord_mm = -1.0;
  EXPECT_NE(error_of(spec).find("tip chord"), std::string::npos);
  spec = SeedWing();
  spec.span_mm = 0.0;
  EXPECT_NE(error_of(spec).find("span"), std::string::npos);
  spec.span_mm = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_of(spec).find("span"), std::string::npos);
  spec = SeedWing();
  spec.tip_code = "230120000";
  EXPECT_NE(error_of(spec).find("tip section"), std::string::npos);
  spec = SeedWing();
  spec.root_code = "2301x";
  EXPECT_NE(error_of(spec).find("root section"), std::string::npos);
  spec = SeedWing();
  spec.sweep_rad = 90.0 * kDeg;
  EXPECT_NE(error_of(spec).find("sweep"), std::string::npos);
}

}  // namespace
}  // namespace stitchsim::geom
