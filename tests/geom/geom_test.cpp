// Geometry: Euler conventions, surfaces, equal-arc-length sampling, the stitch count rule, STL.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/curve.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/geom/stl.h"
#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {
namespace {

TEST(Rotation, DialectDefaultIsFixedXyz) {
  const Eigen::Vector3d abc(0.1, -0.2, 0.3);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_TRUE(RotationFromEuler(*ParseEulerOrder("XYZ"), abc).isApprox(expected, 1e-15));
}

TEST(Rotation, EulerRoundTripsForEveryOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  for (const char* name : {"XYZ", "ZYX", "ZXZ", "ZYZ", "XZY", "YXZ"}) {
    const EulerOrder order = *ParseEulerOrder(name);
    for (int i = 0; i < 500; ++i) {
      const Eigen::Vector3d angles(u(rng), u(rng) / 2, u(rng));
      const Eigen::Matrix3d r = RotationFromEuler(order, angles);
      const Eigen::Vector3d back = EulerFromRotation(order, r);
      EXPECT_LT(AngleBetween(RotationFromEuler(order, back), r), 1e-9) << name;
      const Eigen::Vector3d hinted = EulerFromRotation(order, r, &angles);
      EXPECT_LT(AngleBetween(RotationFromEuler(order, hinted), r), 1e-9) << name;
    }
  }
  EXPECT_FALSE(ParseEulerOrder("XXY").has_value());
  EXPECT_FALSE(ParseEulerOrder("xyz").has_value());
}

TEST(Rotation, HintKeepsAnglesContinuousAcrossPi) {
  const EulerOrder order{};
  const Eigen::Vector3d near_pi(0, 0, kPi - 0.01);
  const Eigen::Matrix3d r = RotationFromEuler(order, Eigen::Vector3d(0, 0, kPi + 0.01));
  const Eigen::Vector3d e = EulerFromRotation(order, r, &near_pi);
  EXPECT_NEAR(e[2], kPi + 0.01, 1e-12);
}

TEST(StitchCount, PicksTheLengthClosestToNominal) {
  EXPECT_EQ(*StitchCount(100.0, 5.0), 20);
  EXPECT_EQ(*StitchCount(102.4, 5.0), 20);  // 5.12 vs 4.876
  EXPECT_EQ(*StitchCount(102.6, 5.0), 21);  // 5.13 vs 4.886
  // Closest in stitch length, not in count: 12.4 / 2 = 6.2 (1.2 off), 12.4 / 3 = 4.13 (0.87).
  EXPECT_EQ(*StitchCount(12.4, 5.0), 3);
  EXPECT_EQ(*StitchCount(5.0, 5.0), 1);
}

TEST(StitchCount, NearTiesAreStableAndExactTiesGoShorter) {
  // Tie between n and n+1 at L = l * 2n(n+1)/(2n+1).
  for (int n = 1; n < 200; ++n) {
    const double l = 5.0;
    const double tie = l * 2.0 * n * (n + 1) / (2.0 * n + 1);
    EXPECT_EQ(*StitchCount(tie, l), n + 1) << n;
    EXPECT_EQ(*StitchCount(tie * (1 - 1e-9), l), n) << n;
    EXPECT_EQ(*StitchCount(tie * (1 + 1e-9), l), n + 1) << n;
  }
}

TEST(StitchCount, ShorterThanOneStitchOrBadInputIsAnError) {
  EXPECT_FALSE(StitchCount(4.99, 5.0).has_value());
  EXPECT_FALSE(StitchCount(0.0, 5.0).has_value());
  EXPECT_FALSE(StitchCount(10.0, 0.0).has_value());
  EXPECT_FALSE(StitchCount(std::nan(""), 5.0).has_value());
  EXPECT_FALSE(StitchCount(10.0, -1.0).has_value());
  EXPECT_FALSE(StitchCount(INFINITY, 5.0).has_value());
}

TEST(Surface, CylinderPointsNormalsAndProjection) {
  for (bool outside : {true, false}) {
    auto cyl = MakeCylinder(500.0, outside, 400.0, 600.0);
    for (double v : {-250.0, -10.0, 0.0, 33.0, 290.0}) {
      const Eigen::Vector2d uv(12.0, v);
      const Eigen::Vector3d p = cyl->Point(uv);
      const Eigen::Vector3d n = cyl->Normal(uv);
      EXPECT_NEAR(n.norm(), 1.0, 1e-12);
      const Eigen::Vector3d axis_point(p.x(), 0.0, outside ? -500.0 : 500.0);
      EXPECT_NEAR((p - axis_point).norm(), 500.0, 1e-9);
      const SurfaceProjection pr = cyl->Project(p + 3.0 * n);
      EXPECT_NEAR(pr.signed_distance_mm, 3.0, 1e-9);
      EXPECT_LT((pr.uv - uv).norm(), 1e-9);
      Eigen::Vector3d hit;
      ASSERT_TRUE(cyl->IntersectLine(p + 2.0 * n, -n, hit));
      EXPECT_LT((hit - p).norm(), 1e-9);
    }
    const Eigen::Vector3d expected_crown_normal = Eigen::Vector3d::UnitZ();
    EXPECT_LT((cyl->Normal(Eigen::Vector2d::Zero()) - expected_crown_normal).norm(), 1e-15);
  }
}

TEST(Surface, PolynomialProjectionAndJacobian) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(2, 0) = 1e-4;
  c(0, 2) = -2e-3;
  c(1, 1) = 5e-4;
  Domain2 d{Eigen::Vector2d(-300, -100), Eigen::Vector2d(300, 100)};
  auto s = MakePolynomialHeightField(c, d);
  const Eigen::Vector2d uv(40, -20);
  const Eigen::Vector3d p = s->Point(uv);
  const Eigen::Vector3d n = s->Normal(uv);
  const SurfaceProjection pr = s->Project(p + 5.0 * n);
  EXPECT_NEAR(pr.signed_distance_mm, 5.0, 1e-8);
  EXPECT_LT((pr.uv - uv).norm(), 1e-8);
  // Normal is orthogonal to the Jacobian columns.
  const auto j = s->Jacobian(uv);
  EXPECT_NEAR(j.col(0).dot(n), 0.0, 1e-12);
  EXPECT_NEAR(j.col(1).dot(n), 0.0, 1e-12);
}

// Capabilities are asked of the surface, not read from Kind(): a height field has u = x,
// v = y (Point(x, y) lies over (x, y)); a mesh's domain is only its bounding box.
TEST(Surface, CapabilitiesMatchTheParametrisation) {
  const Domain2 d{Eigen::Vector2d(-50, -40), Eigen::Vector2d(60, 30)};
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(1, 1) = 1e-3;
  TriangleMesh tri;
  tri.vertices = {{0, 0, 0}, {10, 0, 1}, {0, 10, 2}};
  tri.triangles = {{0, 1, 2}};
  std::vector<std::unique_ptr<Surface>> surfaces;
  surfaces.push_back(MakePlane(100, 80));
  surfaces.push_back(MakePolynomialHeightField(c, d));
  surfaces.push_back(MakeMeshSurface(tri));
  surfaces.push_back(MakeCylinder(500.0, true, 400.0, 600.0));
  surfaces.push_back(MakeCylinder(500.0, false, 400.0, 600.0));
  for (const auto& s : surfaces) {
    SCOPED_TRACE(s->Kind());
    const bool cylinder = s->Kind().rfind("cylinder", 0) == 0;
    EXPECT_EQ(s->IsHeightField(), !cylinder);
    EXPECT_EQ(s->CoversDomain(), s->Kind() != "mesh");
    if (!s->IsHeightField()) continue;
    const Eigen::Vector2d uv(3.0, 2.0);
    EXPECT_TRUE(s->Point(uv).head<2>().isApprox(uv));
  }
  // A cylinder's v is arc length around it, not y.
  EXPECT_FALSE(surfaces.back()->Point({3.0, 200.0}).head<2>().isApprox(Eigen::Vector2d(3, 200)));
}

TEST(SurfacePath, CircleLengthAndEqualArcSpacing) {
  auto plane = MakePlane(1000, 1000);
  Curve2 circle;
  circle.Add(MakeEllipticArc(Eigen::Vector2d(0, 0), 203.2, 203.2, 0.0, 0.0, 2 * kPi));
  SurfacePath path(*plane, circle);
  EXPECT_NEAR(path.Length(), 2 * kPi * 203.2, 1e-9);
  EXPECT_TRUE(path.Closed());
  for (double s = 0; s < path.Length(); s += 37.3) {
    const PathPoint p = path.AtArcLength(s);
    EXPECT_NEAR(std::atan2(p.position.y(), p.position.x()) < 0
                    ? std::atan2(p.position.y(), p.position.x()) + 2 * kPi
                    : std::atan2(p.position.y(), p.position.x()),
                s / 203.2, 1e-10);
  }
}

TEST(SurfacePath, LengthOnACylinderIsTheDevelopedLength) {
  auto cyl = MakeCylinder(2286.0, true, 1000.0, 700.0);
  Curve2 line;
  line.Add(MakeLineSegment(Eigen::Vector2d(-100, -68.58), Eigen::Vector2d(100, 68.58)));
  SurfacePath path(*cyl, line);
  EXPECT_NEAR(path.Length(), std::hypot(200.0, 137.16), 1e-8);
  const PathPoint mid = path.AtArcLength(path.Length() / 2);
  EXPECT_LT((mid.uv - Eigen::Vector2d(0, 0)).norm(), 1e-8);
}

// The inverse undoes the arc length; the arc length itself against a second route, the
// elliptic integral of the second kind (<cmath>): the half ellipse (20 + 5 cos t, 10 sin t),
// t in [-pi/2, pi/2], has speed 10 sqrt(1 - k^2 sin^2 t) with k^2 = 1 - (5/10)^2, so its arc
// length from t = -pi/2 is 10 (E(k) + E(k, t)).
TEST(SurfacePath, EllipseArcLengthInverseIsConsistent) {
  auto plane = MakePlane(100, 100);
  Curve2 c;
  c.Add(MakeLineSegment(Eigen::Vector2d(-20, -10), Eigen::Vector2d(20, -10)));
  c.Add(MakeEllipticArc(Eigen::Vector2d(20, 0), 5, 10, 0, -kPi / 2, kPi / 2));
  SurfacePath path(*plane, c);
  for (double s = 0; s <= path.Length(); s += 0.77) {
    const PathPoint p = path.AtArcLength(s);
    EXPECT_NEAR(path.ArcLengthAt(p.segment, p.t), s, 1e-9);
  }
  const double k = std::sqrt(0.75);
  EXPECT_NEAR(path.Length(), 40.0 + 20.0 * std::comp_ellint_2(k), 1e-7);
  for (double t = -kPi / 2; t <= kPi / 2; t += 0.13) {
    const double s = 40.0 + 10.0 * (std::comp_ellint_2(k) + std::ellint_2(k, t));
    const PathPoint p = path.AtArcLength(s);
    EXPECT_LT((p.position - Eigen::Vector3d(20 + 5 * std::cos(t), 10 * std::sin(t), 0)).norm(),
              1e-7)
        << "t " << t;
  }
}

TEST(Stl, WriteReadRoundTripAndMeshSurface) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(2, 0) = 2e-4;
  c(0, 2) = -1e-3;
  Domain2 d{Eigen::Vector2d(-200, -80), Eigen::Vector2d(200, 80)};
  auto poly = MakePolynomialHeightField(c, d);
  // A top-surface-only mesh of the polynomial on a fine grid.
  TriangleMesh mesh;
  const int nu = 80, nv = 40;
  for (int i = 0; i <= nu; ++i) {
    for (int j = 0; j <= nv; ++j) {
      mesh.vertices.push_back(
          poly->Point(Eigen::Vector2d(-200 + 400.0 * i / nu, -80 + 160.0 * j / nv)));
    }
  }
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const int a = i * (nv + 1) + j;
      mesh.triangles.emplace_back(a, a + nv + 1, a + nv + 2);
      mesh.triangles.emplace_back(a, a + nv + 2, a + 1);
    }
  }
  const auto file = std::filesystem::temp_directory_path() / "stitchsim_geom_test.stl";
  std::string err;
  ASSERT_TRUE(WriteStl(file, mesh, err)) << err;
  TriangleMesh back;
  ASSERT_TRUE(ReadStl(file, 1.0, back, err, 1e-4)) << err;
  EXPECT_EQ(back.triangles.size(), mesh.triangles.size());
  EXPECT_EQ(back.vertices.size(), mesh.vertices.size());
  auto ms = MakeMeshSurface(std::move(back));
  for (double x : {-150.0, -3.0, 77.0}) {
    for (double y : {-60.0, 0.0, 41.0}) {
      const Eigen::Vector2d uv(x, y);
      EXPECT_NEAR(ms->Point(uv).z(), poly->Point(uv).z(), 0.05);
      EXPECT_GT(ms->Normal(uv).dot(poly->Normal(uv)), std::cos(0.01));
    }
  }
  EXPECT_FALSE(ReadStl("/nonexistent.stl", 1.0, back, err));
}

// Found while writing the STL fuzz target: vertex welding keyed on llround(x / tol) overflowed
// beyond 2^63 grid steps (9.2e9 file units at the default 1e-9), so distant vertices were
// merged and the mesh silently changed. Large coordinates stay apart; ones too large for the
// grid are refused.
TEST(Stl, LargeCoordinatesAreNotWeldedTogether) {
  const auto file = std::filesystem::temp_directory_path() / "stitchsim_geom_big.stl";
  auto write_ascii = [&](const std::vector<std::array<Eigen::Vector3d, 3>>& triangles) {
    std::ofstream out(file);
    out << "solid big\n";
    for (const auto& t : triangles) {
      out << "facet normal 0 0 1\nouter loop\n";
      for (const auto& v : t) out << "vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
      out << "endloop\nendfacet\n";
    }
    out << "endsolid big\n";
  };
  // Five distinct vertices; (1e12, 0, 0) and (2e12, 0, 0) once shared one overflowed key.
  write_ascii(
      {{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e12, 0, 0), Eigen::Vector3d(1e12, 1e12, 0)},
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2e12, 0, 0), Eigen::Vector3d(0, 3e12, 0)}});
  TriangleMesh mesh;
  std::string err;
  ASSERT_TRUE(ReadStl(file, 1.0, mesh, err)) << err;
  ASSERT_EQ(mesh.vertices.size(), 5u);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.vertices[static_cast<std::size_t>(mesh.triangles[1][1])],
            Eigen::Vector3d(2e12, 0, 0));
  // 1e300 / 1e-9 is not a finite grid key: an error, not a mesh.
  write_ascii({{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e300, 0, 0), Eigen::Vector3d(0, 1, 0)}});
  TriangleMesh untouched;
  EXPECT_FALSE(ReadStl(file, 1.0, untouched, err));
  EXPECT_NE(err.find("too large"), std::string::npos) << err;
  EXPECT_TRUE(untouched.vertices.empty());
  std::filesystem::remove(file);
}

TEST(Tessellation, SlabIsClosedWithPositiveVolume) {
  auto cyl = MakeCylinder(300.0, false, 200.0, 500.0);
  const TriangleMesh m = TessellateSlab(*cyl, cyl->Domain(), -20.0, 0.0, 0.5);
  double volume = 0.0;
  for (const auto& t : m.triangles) {
    volume += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  }
  // Roughly area * thickness.
  EXPECT_NEAR(volume, 200.0 * 500.0 * 20.0, 200.0 * 500.0 * 20.0 * 0.05);
}

}  // namespace
}  // namespace stitchsim::geom
