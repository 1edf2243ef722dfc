// Surfaces as one B-spline patch (export-step): the kernel's own surface for CAD kinds, an
// interpolation exact on planes and cubic height fields, measured deviations, and a STEP
// round trip through ReadCadFace.
#include "stitchsim/geom/surface_export.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "seed_wing.h"
#include "stitchsim/geom/wing_surface.h"

namespace stitchsim::geom {
namespace {

WingSpec SeedWing() { return testing::SeedWingSpec(); }

// Largest distance between `a` and `b` at the same (u, v) on a grid over a's domain.
double SameParameterDistance(const Surface& a, const Surface& b, int n = 40) {
  const Domain2 d = a.Domain();
  double worst = 0.0;
  for (int i = 0; i <= n; ++i) {
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector2d uv =
          d.min + (d.max - d.min).cwiseProduct(Eigen::Vector2d(i, k) / static_cast<double>(n));
      worst = std::max(worst, (a.Point(uv) - b.Point(uv)).norm());
    }
  }
  return worst;
}

TEST(SurfaceExport, TheWingIsItsOwnKernelSurface) {
  std::string error;
  for (const WingSkin skin : {WingSkin::kFull, WingSkin::kUpper}) {
    const WingSurface wing = MakeWingSurface(SeedWing(), skin, error);
    ASSERT_TRUE(wing.surface) << error;
    const auto patch = SurfaceToBSpline(*wing.surface, 0.001, error);
    ASSERT_TRUE(patch) << error;
    EXPECT_TRUE(patch->converted);
    EXPECT_LT(patch->max_deviation_mm, 1e-6);
    const auto back = MakeBSplineSurface(patch->spec, error);
    ASSERT_TRUE(back) << error;
    EXPECT_LT(SameParameterDistance(*wing.surface, *back), 1e-6);
    const Eigen::Vector2d mid = wing.surface->Domain().max / 2;
    EXPECT_GT(back->Normal(mid).dot(wing.surface->Normal(mid)), 0.999999);
  }
}

// Largest distance between `a` and `b` at the same fraction of their domains.
double SameFractionDistance(const Surface& a, const Surface& b, int n = 40) {
  const Domain2 da = a.Domain();
  const Domain2 db = b.Domain();
  double worst = 0.0;
  for (int i = 0; i <= n; ++i) {
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector2d f = Eigen::Vector2d(i, k) / static_cast<double>(n);
      worst = std::max(worst, (a.Point(da.min + (da.max - da.min).cwiseProduct(f)) -
                               b.Point(db.min + (db.max - db.min).cwiseProduct(f)))
                                  .norm());
    }
  }
  return worst;
}

TEST(SurfaceExport, CubicHeightFieldsAndPlanesAreOneExactBezierPatch) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();  // every term up to x^3 y^3
  c << 1, 0.01, -2e-4, 3e-6, 0.02, 1e-4, 2e-6, -1e-8, -3e-4, 5e-6, 1e-8, 2e-10, 2e-6, -1e-8, 3e-10,
      1e-12;
  Domain2 d;
  d.min = Eigen::Vector2d(-300, -100);
  d.max = Eigen::Vector2d(200, 150);
  std::string error;
  for (const auto& surface : {MakePolynomialHeightField(c, d), MakePlane(600, 400)}) {
    const auto patch = SurfaceToBSpline(*surface, 0.001, error);
    ASSERT_TRUE(patch) << error;
    EXPECT_FALSE(patch->converted);
    EXPECT_EQ(patch->grid, 4);
    EXPECT_LT(patch->max_deviation_mm, 1e-9);
    const auto back = MakeBSplineSurface(patch->spec, error);
    ASSERT_TRUE(back) << error;
    EXPECT_LT(SameFractionDistance(*surface, *back, 97), 1e-9);
    const Eigen::Vector2d mid = (surface->Domain().min + surface->Domain().max) / 2;
    EXPECT_GT(back->Normal(back->Domain().max / 2).dot(surface->Normal(mid)), 0.999999);
  }
}

TEST(SurfaceExport, ACylinderIsRefinedToTheToleranceAndTheDeviationIsTrue) {
  for (const bool outside : {true, false}) {
    const auto cylinder = MakeCylinder(250, outside, 800, 450);
    std::string error;
    const auto coarse = SurfaceToBSpline(*cylinder, 0.05, error);
    const auto fine = SurfaceToBSpline(*cylinder, 0.0001, error);
    ASSERT_TRUE(coarse && fine) << error;
    EXPECT_LE(coarse->max_deviation_mm, 0.05);
    EXPECT_LE(fine->max_deviation_mm, 0.0001);
    EXPECT_GT(fine->grid, coarse->grid);
    // Independent check of the reported figure: distances to the axis against the radius.
    const auto back = MakeBSplineSurface(coarse->spec, error);
    ASSERT_TRUE(back) << error;
    const double axis_z = outside ? -250 : 250;
    double worst = 0.0;
    for (int i = 0; i <= 300; ++i) {
      const Eigen::Vector2d f(0.37, i / 300.0);
      const Eigen::Vector3d p = back->Point(back->Domain().max.cwiseProduct(f));
      worst = std::max(worst, std::abs(std::hypot(p.y(), p.z() - axis_z) - 250));
    }
    EXPECT_LE(worst, coarse->max_deviation_mm * 1.01 + 1e-9);
    EXPECT_GT(worst, coarse->max_deviation_mm * 0.2);
    const Eigen::Vector2d mid = (cylinder->Domain().min + cylinder->Domain().max) / 2;
    EXPECT_GT(back->Normal(back->Domain().max / 2).dot(cylinder->Normal(mid)), 0.999);
  }
}

}  // namespace
}  // namespace stitchsim::geom
