// The wing's kernel B-spline against the closed-form loft of naca.h (seed 002's wing).
#include "stitchsim/geom/wing_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

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

// Issue 26 item 7: a projection started on one skin of the closed wing finds the other skin
// when that is the nearer. Second route: the closed-form loft (naca.h) and its outward normal;
// the point lies 2 mm out from the loft, so the loft's point is its closest on the wing (to the
// fit's 0.005 mm). Near the trailing edge the skins are 5..30 mm apart: a descent from the
// other skin's point at the same chord station stops there, 7..32 mm away.
TEST(WingSurface, ProjectionFromAHintOnTheOtherSkinFindsTheNearerSkin) {
  const WingSpec spec = SeedWing();
  const WingSurface w = MakeOrFail(spec, WingSkin::kFull);
  ASSERT_TRUE(w.surface);
  std::string error;
  const std::optional<Wing> wing = Wing::Make(spec, error);
  ASSERT_TRUE(wing) << error;
  constexpr double kOut = 2.0;
  int cases = 0;
  for (const double s : {0.05, 0.1, 0.9, 0.95}) {  // upper (< 0.5) and lower skin
    for (const double eta : {0.1, 0.5, 0.9}) {
      const Eigen::Vector3d foot = wing->Point(s, eta);
      const Eigen::Vector3d p = foot + kOut * wing->Normal(s, eta);
      // The other skin's point at the same chord station (s mirrored about the nose).
      const Eigen::Vector2d hint = Uv(*w.surface, WingSkin::kFull, 1.0 - s, eta);
      const double other = (w.surface->Point(hint) - p).norm();
      ASSERT_GT(other, kOut + 3.0) << s << " " << eta;
      for (const bool thread_hint : {false, true}) {
        SurfaceProjection f;
        if (thread_hint) {
          w.surface->Project(w.surface->Point(hint));  // the thread's last foot: the other skin
          f = w.surface->Project(p);
        } else {
          f = w.surface->ProjectFrom(p, hint);
        }
        EXPECT_TRUE(f.inside_domain);
        EXPECT_LT((f.point - foot).norm(), 0.02) << s << " " << eta << " other skin at " << other;
        EXPECT_NEAR(f.signed_distance_mm, kOut, 0.02) << s << " " << eta;
        EXPECT_GT(f.normal.dot(wing->Normal(s, eta)), 0.999) << s << " " << eta;
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 24);
}

// The global search against dense sampling of the fitted surface itself: points inside the
// wing between the skins near the trailing edge, at 20 .. 80 % of the way from the upper skin
// to the lower, each started from the farther skin.
TEST(WingSurface, ProjectionMatchesDenseSamplingFromTheFartherSkin) {
  const WingSurface w = MakeOrFail(SeedWing(), WingSkin::kFull);
  ASSERT_TRUE(w.surface);
  const Surface& s = *w.surface;
  const Eigen::Vector2d len = s.Domain().max;
  const double v = 0.3 * len.y();
  std::vector<Eigen::Vector3d> samples;  // round the contour at this span station, 0.17 mm apart
  for (int i = 0; i <= 20000; ++i) samples.push_back(s.Point({len.x() * i / 20000.0, v}));
  for (const double u_frac : {0.01, 0.03, 0.06, 0.1}) {
    const Eigen::Vector2d upper(len.x() * u_frac, v), lower(len.x() * (1.0 - u_frac), v);
    for (const double f : {0.2, 0.4, 0.6, 0.8}) {
      const Eigen::Vector3d p = s.Point(upper) + f * (s.Point(lower) - s.Point(upper));
      double best = 1e300;
      for (const Eigen::Vector3d& q : samples) best = std::min(best, (q - p).norm());
      const SurfaceProjection proj = s.ProjectFrom(p, f < 0.5 ? lower : upper);
      EXPECT_LE((proj.point - p).norm(), best + 1e-9) << u_frac << " " << f;
      EXPECT_GT((proj.point - p).norm(), best - 0.01) << u_frac << " " << f;
      EXPECT_EQ(proj.normal.z() > 0, f < 0.5) << u_frac << " " << f;  // the nearer skin's side
    }
  }
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
