// Constraint footprints (scene/footprint.h), shared by the raster planner and the
// constraint.crossing rule: the row interval, containment and crossing agree; a box tilted
// out of the plane has a footprint that holds its whole shadow; a mesh constraint uses its
// bounding box; the grown box in 3D.
#include "stitchsim/scene/footprint.h"

#include <gtest/gtest.h>

namespace stitchsim::scene {
namespace {

TEST(Footprint, RowIntervalAndCrossingAgree) {
  Footprint f;
  f.centre = {10, 5};
  f.axis_x = Eigen::Vector2d(1, 1).normalized();
  f.axis_y = Eigen::Vector2d(-1, 1).normalized();
  f.half_mm = {4, 1};
  double a = 0, b = 0;
  ASSERT_TRUE(f.RowInterval(5.0, a, b));
  EXPECT_TRUE(f.Contains({0.5 * (a + b), 5.0}));
  EXPECT_FALSE(f.Contains({a - 1e-6, 5.0}));
  EXPECT_FALSE(f.Contains({b + 1e-6, 5.0}));
  EXPECT_TRUE(f.Crosses({a - 5, 5.0}, {b + 5, 5.0}));
  EXPECT_FALSE(f.Crosses({a - 5, 5.0}, {a - 1, 5.0}));
  EXPECT_FALSE(f.RowInterval(40.0, a, b));
  // SegmentDepth: negative exactly when Crosses is false; the depth of the crossing's middle.
  EXPECT_LT(f.SegmentDepth({a - 5, 5.0}, {a - 1, 5.0}), 0.0);
  EXPECT_NEAR(f.SegmentDepth({a - 5, 5.0}, {b + 5, 5.0}), f.Depth({0.5 * (a + b), 5.0}), 1e-9);
  EXPECT_NEAR(f.Depth(f.centre), 1.0, 1e-12);
}

TEST(Footprint, TiltedBoxShadowLiesInside) {
  Constraint c;
  c.name = "stringer";
  c.size_mm = {100, 2, 10};
  c.pose_mm = Eigen::Translation3d(5, -3, 4) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) *
              Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ());
  const Footprint f = ConstraintFootprint(c, 1.5);
  EXPECT_EQ(f.name, "stringer");
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner(((k & 1) ? 0.5 : -0.5) * c.size_mm.x(),
                                 ((k & 2) ? 0.5 : -0.5) * c.size_mm.y(),
                                 ((k & 4) ? 0.5 : -0.5) * c.size_mm.z());
    const Eigen::Vector2d shadow = (c.pose_mm * corner).head<2>();
    EXPECT_GE(f.Depth(shadow), 1.5 - 1e-9) << k;  // inside, by at least the margin
  }
  // The grown box: its centre is half the smallest extent plus the margin deep; a segment
  // through it crosses, one beside it does not.
  const GrownBox b = ConstraintBox(c, 1.5);
  EXPECT_NEAR(b.Depth(c.pose_mm.translation()), 2.5, 1e-9);
  EXPECT_GE(
      b.SegmentDepth(c.pose_mm * Eigen::Vector3d(0, -20, 0), c.pose_mm * Eigen::Vector3d(0, 20, 0)),
      0.0);
  // Beside the box (5 mm along its y, half extent 1 + 1.5 mm), all along its length: clear.
  EXPECT_LT(b.SegmentDepth(c.pose_mm * Eigen::Vector3d(-200, 5, 0),
                           c.pose_mm * Eigen::Vector3d(200, 5, 0)),
            0.0);
}

TEST(Footprint, MeshUsesItsBoundingBox) {
  Constraint c;
  c.shape = Constraint::Shape::kMesh;
  c.mesh.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 4, 0}, {10, 4, 2}};
  const Footprint f = ConstraintFootprint(c, 1.0);
  EXPECT_TRUE(f.centre.isApprox(Eigen::Vector2d(5, 2)));
  EXPECT_TRUE(f.half_mm.isApprox(Eigen::Vector2d(6, 3)));
  const GrownBox b = ConstraintBox(c, 1.0);
  EXPECT_NEAR(b.Depth({5, 2, 1}), 2.0, 1e-12);
}

}  // namespace
}  // namespace stitchsim::scene
