// The constant-angle reference course (`reference: path: constant_angle`, issue 29): on a
// plane every reference path is the same straight line; on a cylinder the streamline of the
// design field against its closed forms (a circle, the projected 45 deg line u = R sin(v/R))
// and, at a turned angle, each chord's direction against the field computed here by hand.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "ply_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/geom/surface.h"
#include "stitchsim/planner/ply_planner.h"

namespace stitchsim::planner {
namespace {

namespace fs = std::filesystem;
using testing::Folder;
using testing::Load;
using testing::SceneText;

constexpr double kRadius = 600.0;

/// A ply through `origin` along `direction`, projected along -z (the normal at the crown).
scene::PlySpec CylinderPly(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                           double angle_rad) {
  scene::PlySpec ply;
  ply.name = "p";
  ply.origin_mm = origin;
  ply.direction = direction.normalized();
  ply.projection = -Eigen::Vector3d::UnitZ();
  ply.angle_rad = angle_rad;
  return ply;
}

std::unique_ptr<geom::Surface> Cylinder() { return geom::MakeCylinder(kRadius, true, 1600, 1500); }

TEST(PlyReference, OnAPlaneEveryPathIsTheSameStraightLine) {
  const fs::path dir = Folder("reference_plane");
  const std::string box = "[[-150, -100], [150, -100], [150, 100], [-150, 100]]";
  std::string plies = "plies:\n";
  for (const char* path : {"projected", "geodesic", "constant_angle"}) {
    plies += "  - name: " + std::string(path) +
             "\n    angle_deg: 30\n    reference: {origin: [20, -10, 100], direction: [1, 0, 0], "
             "path: " +
             path + "}\n    boundary_uv: " + box + "\n    coverage: 50\n";
  }
  std::ofstream(dir / "s.yaml") << SceneText("surface:\n  type: plane\n  size: [600, 400]\n",
                                             plies);
  const auto s = Load(dir / "s.yaml");
  ASSERT_NE(s, nullptr);
  // Closed form: the line through the foot (20, -10) at 30 deg to u.
  const Eigen::Vector2d foot(20, -10), along(std::cos(kPi / 6), std::sin(kPi / 6));
  const Eigen::Vector2d across(-along.y(), along.x());
  std::vector<std::pair<double, double>> ends;  // the reference course's, along the line
  for (const scene::PlySpec& ply : s->plies) {
    SCOPED_TRACE(ply.name);
    DiagnosticSink sink;
    const auto plan = PlanPly(*s, ply, {}, sink);
    ASSERT_TRUE(plan.has_value());
    int reference = 0;
    for (const PlyCourse& c : plan->courses) {
      if (c.offset_index != 0) continue;
      ++reference;
      ASSERT_GE(c.points.size(), 20u);
      double first = 1e9, last = -1e9;
      for (const PlyPoint& p : c.points) {
        EXPECT_NEAR(across.dot(p.uv - foot), 0.0, 1e-6);
        first = std::min(first, along.dot(p.uv - foot));
        last = std::max(last, along.dot(p.uv - foot));
      }
      // Across the box: beyond where the centre line crosses its edges, less a band width.
      EXPECT_LT(first, -(100 - 10) / std::sin(kPi / 6) + 120.0);
      EXPECT_GT(last, (150 - 20) / std::cos(kPi / 6) - 120.0);
      ends.emplace_back(first, last);
    }
    EXPECT_EQ(reference, 1);
  }
  ASSERT_EQ(ends.size(), 3u);  // the same course: cut and added at the same places
  for (const auto& [first, last] : ends) {
    EXPECT_NEAR(first, ends.front().first, 0.01);
    EXPECT_NEAR(last, ends.front().second, 0.01);
  }
}

TEST(PlyReference, CylinderCircumferentialAtNinetyDegIsACircle) {
  const auto surface = Cylinder();
  const scene::PlySpec ply = CylinderPly({100, 0, 50}, Eigen::Vector3d::UnitX(), kPi / 2);
  const geom::Domain2 region{{-700, -600}, {700, 600}};
  const ReferenceCurve ref = ConstantAngleReference(*surface, ply, ply.angle_rad, region, 5.0);
  ASSERT_TRUE(ref.ok) << ref.message;
  ASSERT_GE(ref.points.size(), 200u);
  for (const CurvePoint& p : ref.points) {
    EXPECT_NEAR(p.uv.x(), 100.0, 1e-9);
    const double phi = p.uv.y() / kRadius;  // closed form: the circle x = 100
    const Eigen::Vector3d on(100, kRadius * std::sin(phi), kRadius * std::cos(phi) - kRadius);
    EXPECT_LT((p.position - on).norm(), 1e-6);
  }
  // Across the region, 5 mm apart.
  EXPECT_GT(std::abs(ref.points.front().uv.y()), 595.0);
  EXPECT_GT(std::abs(ref.points.back().uv.y()), 595.0);
  EXPECT_LT(ref.points.front().uv.y() * ref.points.back().uv.y(), 0.0);
  for (std::size_t i = 1; i < ref.points.size(); ++i)
    EXPECT_LE((ref.points[i].position - ref.points[i - 1].position).norm(), 5.0 + 1e-9);
}

TEST(PlyReference, CylinderAt45DegFollowsTheProjectedLine) {
  // The reference direction (1, 1, 0) projected along -z: at phi = v / R the field is
  // (1, 1, -tan phi), whose (u, v) slope is dv/du = 1 / cos phi: u - u0 = R sin(v / R).
  const auto surface = Cylinder();
  const scene::PlySpec ply = CylinderPly({100, 0, 50}, {1, 1, 0}, 0.0);
  const geom::Domain2 region{{-700, -600}, {700, 600}};
  const ReferenceCurve ref = ConstantAngleReference(*surface, ply, 0.0, region, 5.0);
  ASSERT_TRUE(ref.ok) << ref.message;
  ASSERT_GE(ref.points.size(), 200u);
  double worst = 0.0;
  for (const CurvePoint& p : ref.points)
    worst = std::max(worst, std::abs(p.uv.x() - 100.0 - kRadius * std::sin(p.uv.y() / kRadius)));
  EXPECT_LT(worst, 1e-6);  // 6e-10 mm measured; Euler steps: 0.9 mm
  EXPECT_GT(ref.points.back().uv.y() - ref.points.front().uv.y(), 1150.0);
  EXPECT_GT(ref.points.back().uv.x(), ref.points.front().uv.x());  // along the direction
}

TEST(PlyReference, CylinderTurnedPlyKeepsTheDesignAngleAlongTheCourse) {
  // Direction (1, 1, 0) turned 30 deg: each chord's direction against the design field at its
  // middle, computed here from the cylinder's normal (oblique projection along -z, turned
  // about the normal by Rodrigues' formula): the defining property, < 1e-3 rad.
  const auto surface = Cylinder();
  const double angle = kPi / 6;
  const scene::PlySpec ply = CylinderPly({-50, 30, 50}, {1, 1, 0}, angle);
  const geom::Domain2 region{{-700, -600}, {700, 600}};
  const ReferenceCurve ref = ConstantAngleReference(*surface, ply, angle, region, 5.0);
  ASSERT_TRUE(ref.ok) << ref.message;
  ASSERT_GE(ref.points.size(), 100u);
  double worst = 0.0;
  for (std::size_t i = 1; i + 1 < ref.points.size(); ++i) {
    const double phi = ref.points[i].uv.y() / kRadius;
    const Eigen::Vector3d n(0, std::sin(phi), std::cos(phi));
    const Eigen::Vector3d d0 =
        Eigen::Vector3d(1, 1, 0) + (std::sin(phi) / std::cos(phi)) * Eigen::Vector3d(0, 0, -1);
    const Eigen::Vector3d design =
        (std::cos(angle) * d0 + std::sin(angle) * n.cross(d0)).normalized();
    const Eigen::Vector3d chord =
        (ref.points[i + 1].position - ref.points[i - 1].position).normalized();
    worst = std::max(worst, std::acos(std::min(1.0, std::abs(chord.dot(design)))));
  }
  EXPECT_LT(worst, 1e-4);  // 1.0e-5 rad measured; Euler steps: 2.7e-3
  // Not the straight fibre axis: the course turns against it by tens of mm over the region.
  const Eigen::Vector2d a = ref.points.front().uv, b = ref.points.back().uv;
  double bow = 0.0;
  for (const CurvePoint& p : ref.points) {
    const Eigen::Vector2d t = (b - a).normalized();
    bow = std::max(bow, std::abs(t.x() * (p.uv - a).y() - t.y() * (p.uv - a).x()));
  }
  EXPECT_GT(bow, 10.0);
}

TEST(PlyReference, AReferenceThatDoesNotProjectIsNotOk) {
  const auto surface = Cylinder();
  scene::PlySpec ply = CylinderPly({0, 0, 50}, {1, 0, 0}, 0.0);
  ply.projection = Eigen::Vector3d::UnitY();  // in the tangent plane at the crown
  const geom::Domain2 region{{-700, -600}, {700, 600}};
  const ReferenceCurve ref = ConstantAngleReference(*surface, ply, 0.0, region, 5.0);
  EXPECT_FALSE(ref.ok);
  EXPECT_NE(ref.message.find("does not project"), std::string::npos) << ref.message;
}

}  // namespace
}  // namespace stitchsim::planner
