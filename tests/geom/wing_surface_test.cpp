// The wing's kernel B-spline against the closed-form loft of naca.h (seed 002's wing).
#include "stitchsim/geom/wing_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "seed_wing.h"

namespace stitchsim::geom {
namespace {

WingSpec SeedWing() { return testing::SeedWingSpec(); }

WingSpec SweptTwistedSeedWing() { return testing::SweptTwistedSeedWingSpec(); }

WingSurface MakeOrFail(const WingSpec& spec, WingSkin skin) {
  std::string error;
  WingSurface w = MakeWingSurface(spec, skin, error);
  EXPECT_TRUE(w.surface) << error;
  return w;
}

// The surface parameter of the loft's (s, eta), as the header documents it.
Eigen::Vector2d Uv(const Surface& surface, WingSkin skin, double s, double eta) {
  const Eigen::Vector2d range = WingSkinRange(skin);
  const Eigen::Vector2d len = surface.Domain().max;
  return {len.x() * (s - range.x()) / (range.y() - range.x()), len.y() * eta};
}

// Largest distance between surface and loft on a grid far denser than the fit's stations,
// clustered at the leading edge (s = 0.5) and the trailing edges.
double Deviation(const WingSpec& spec, const Surface& surface, WingSkin skin) {
  std::string error;
  const std::optional<Wing> wing = Wing::Make(spec, error);
  EXPECT_TRUE(wing) << error;
  const Eigen::Vector2d range = WingSkinRange(skin);
  double worst = 0.0;
  for (const double eta : {0.0, 0.37, 0.5, 1.0}) {
    for (int i = 0; i <= 5000; ++i) {
      const double t = i / 5000.0;
      const double s = range.x() + (range.y() - range.x()) * t;
      const Eigen::Vector3d p = surface.Point(Uv(surface, skin, s, eta));
      worst = std::max(worst, (p - wing->Point(s, eta)).norm());
    }
    for (int i = -200; i <= 200; ++i) {  // the nose, a few microns apart in s
      const double s = 0.5 + i * 1e-6;
      if (s < range.x() || s > range.y()) continue;
      const Eigen::Vector3d p = surface.Point(Uv(surface, skin, s, eta));
      worst = std::max(worst, (p - wing->Point(s, eta)).norm());
    }
  }
  return worst;
}

TEST(WingSurface, SeedWingFitsTheLoftToAHundredthOfAMillimetre) {
  const WingSpec spec = SeedWing();
  const WingSurface w = MakeOrFail(spec, WingSkin::kFull);
  ASSERT_TRUE(w.surface);
  EXPECT_EQ(w.surface->Kind(), "wing");
  EXPECT_LT(w.fit_error_mm, 0.01);
  RecordProperty("stations", w.stations);
  EXPECT_LT(Deviation(spec, *w.surface, WingSkin::kFull), 0.01);
}

TEST(WingSurface, SweptTwistedWingAndEachSkinFit) {
  const WingSpec spec = SweptTwistedSeedWing();
  for (const WingSkin skin : {WingSkin::kFull, WingSkin::kUpper, WingSkin::kLower}) {
    const WingSurface w = MakeOrFail(spec, skin);
    ASSERT_TRUE(w.surface);
    EXPECT_LT(Deviation(spec, *w.surface, skin), 0.01) << static_cast<int>(skin);
  }
}

TEST(WingSurface, NormalPointsOutOfTheWing) {
  const WingSpec spec = SweptTwistedSeedWing();
  std::string error;
  const std::optional<Wing> wing = Wing::Make(spec, error);
  ASSERT_TRUE(wing) << error;
  for (const WingSkin skin : {WingSkin::kFull, WingSkin::kUpper, WingSkin::kLower}) {
    const WingSurface w = MakeOrFail(spec, skin);
    ASSERT_TRUE(w.surface);
    const Eigen::Vector2d range = WingSkinRange(skin);
    for (const double t : {0.02, 0.3, 0.5, 0.7, 0.98}) {
      const double s = range.x() + (range.y() - range.x()) * t;
      for (const double eta : {0.0, 0.5, 1.0}) {
        const Eigen::Vector3d n = w.surface->Normal(Uv(*w.surface, skin, s, eta));
        EXPECT_GT(n.dot(wing->Normal(s, eta)), 0.9999) << s << " " << eta;
      }
    }
  }
  // The upper skin at mid-chord faces up, the lower down, the nose forward (-x).
  const WingSurface full = MakeOrFail(SeedWing(), WingSkin::kFull);
  ASSERT_TRUE(full.surface);
  EXPECT_GT(full.surface->Normal(Uv(*full.surface, WingSkin::kFull, 0.25, 0.5)).z(), 0.9);
  EXPECT_LT(full.surface->Normal(Uv(*full.surface, WingSkin::kFull, 0.75, 0.5)).z(), -0.9);
  EXPECT_LT(full.surface->Normal(Uv(*full.surface, WingSkin::kFull, 0.5, 0.5)).x(),
            -0.9);  // cambered nose
}

TEST(WingSurface, ProjectionFindsTheLoftParameter) {
  const WingSpec spec = SeedWing();
  const WingSurface w = MakeOrFail(spec, WingSkin::kUpper);
  ASSERT_TRUE(w.surface);
  const Eigen::Vector2d uv = Uv(*w.surface, WingSkin::kUpper, 0.2, 0.4);
  const Eigen::Vector3d p = w.surface->Point(uv) + 3.0 * w.surface->Normal(uv);
  const SurfaceProjection f = w.surface->Project(p);
  EXPECT_TRUE(f.inside_domain);
  EXPECT_LT((f.uv - uv).norm(), 1e-6);
  EXPECT_NEAR(f.signed_distance_mm, 3.0, 1e-6);
}

TEST(WingSurface, BadSpecsAreErrorsNotThrows) {
  const auto fails = [](WingSpec spec, const std::string& says) {
    std::string error;
    const WingSurface w = MakeWingSurface(spec, WingSkin::kFull, error);
    EXPECT_FALSE(w.surface);
    EXPECT_NE(error.find(says), std::string::npos) << error;
  };
  WingSpec s = SeedWing();
  s.root_chord_mm = 0;
  fails(s, "root chord");
  s = SeedWing();
  s.tip_chord_mm = -5;
  fails(s, "tip chord");
  s = SeedWing();
  s.span_mm = 0;
  fails(s, "span");
  s = SeedWing();
  s.root_code = "123456789";
  fails(s, "4 or 5 digits");
  s = SeedWing();
  s.tip_code = "23x12";
  fails(s, "digits only");
}

}  // namespace
}  // namespace stitchsim::geom
