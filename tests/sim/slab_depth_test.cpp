// Penetration depth into the mold slab, an independent route: a probe head made of one box
// (or one ball) placed with the robot at a known depth into a flat mold plate and tilt; the
// depth the collision world reports must equal the hand value (docs/collision.md, "Depth").
// FCL's mesh-primitive contact depth did not: it is not a penetration depth, and a body wholly
// inside the (hollow) mold mesh was not reported at all.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "sim_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/collision.h"

namespace stitchsim::sim {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = STITCHSIM_SOURCE_DIR;

// Probe geometry in the flange frame (metres). The tool point is 0.82 m out along flange z
// with the tool z pointing back at the flange (afp.yaml's tool_frame), so a geom centred at
// flange z = 0.82 - h with half height h sits with its far face on the tool point.
constexpr double kToolZ = 0.82;
constexpr double kBoxHalfMm[3] = {30.0, 20.0, 40.0};
constexpr double kBallRadiusMm = 25.0;

struct Probe {
  std::unique_ptr<scene::Scene> scene;
  std::optional<RobotModel> robot;
  std::unique_ptr<CollisionWorld> world;
};

// One folder per test case under this build: ctest runs the cases in parallel.
fs::path ScratchDir() {
  const fs::path dir = fs::path(STITCHSIM_BINARY_DIR) / "slab_depth_test" /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::create_directories(dir);
  return dir;
}

// A flat plate (mold `mold_depth_mm`, preform 2 mm) on the table and a head made of `geom`.
Probe MakeProbe(const std::string& name, const std::string& geom, double mold_depth_mm,
                const std::string& extra_scene = "",
                const std::string& surface = "  type: plane\n  size: [600, 600]\n") {
  const fs::path dir = ScratchDir();
  std::ifstream head_in(kSource / "models" / "heads" / "afp.yaml");
  std::stringstream head;
  head << head_in.rdbuf();
  std::string head_text = head.str();
  head_text.replace(head_text.find("mjcf: afp.xml"), 13, "mjcf: " + name + ".xml");
  // The probe makes no process contact: every contact with the part counts.
  const std::string roller = "  - {head: roller, with: [preform, mold]}\n";
  head_text.replace(head_text.find(roller), roller.size(), "");
  head_text.replace(head_text.find("allowed_contacts:\n"), 18, "allowed_contacts: []\n");
  std::ofstream(dir / (name + ".yaml")) << head_text;
  std::ofstream(dir / (name + ".xml"))
      << "<mujoco model=\"" << name << "\"><worldbody><body name=\"head\">" << geom
      << "</body></worldbody></mujoco>";
  std::ofstream(dir / (name + "_scene.yaml"))
      << "stitchsim_scene: 1\nname: " << name
      << "\nunits: mm\nhead: " << (dir / (name + ".yaml")).string()
      << "\npart:\n  mount: table\n  position: [0, 0, 50]\n"
         "surface:\n"
      << surface << "preform:\n  thickness: 2\nmold:\n  depth: " << mold_depth_mm << "\n"
      << extra_scene << "paths:\n  - {name: row, type: line, from: [-100, 0], to: [100, 0]}\n";
  Probe p;
  DiagnosticSink sink;
  p.scene = scene::LoadScene(dir / (name + "_scene.yaml"), sink);
  EXPECT_TRUE(p.scene) << testing::FormatAll(sink);
  if (!p.scene) return p;
  p.robot = LoadRobotModel(p.scene->cell_urdf, sink);
  EXPECT_TRUE(p.robot) << testing::FormatAll(sink);
  if (!p.robot) return p;
  p.world = CollisionWorld::Create(*p.scene, *p.robot, sink);
  EXPECT_TRUE(p.world) << testing::FormatAll(sink);
  return p;
}

std::string BoxGeom() {
  std::ostringstream s;
  s << "<geom name=\"probe\" type=\"box\" pos=\"0 0 " << kToolZ - kBoxHalfMm[2] / 1000.0
    << "\" size=\"" << kBoxHalfMm[0] / 1000.0 << " " << kBoxHalfMm[1] / 1000.0 << " "
    << kBoxHalfMm[2] / 1000.0 << "\"/>";
  return s.str();
}

std::string BallGeom() {
  std::ostringstream s;
  s << "<geom name=\"probe\" type=\"sphere\" pos=\"0 0 " << kToolZ - kBallRadiusMm / 1000.0
    << "\" size=\"" << kBallRadiusMm / 1000.0 << "\"/>";
  return s.str();
}

// The probe's contact with `body` with the tool point `below_mm` under the surface (part
// origin), the tool z along the surface normal tilted `tilt_deg` about the tool x axis.
// -1 when there is none.
// The probe's contact with `body`, nullopt when there is none.
std::optional<Contact> ContactAt(Probe& p, double below_mm, double tilt_deg,
                                 const std::string& body) {
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.translation() = Eigen::Vector3d(0, 0, -below_mm);
  tool.linear() = Eigen::AngleAxisd(tilt_deg * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const CellSetup cell = MakeCellSetup(*p.robot, *p.scene);
  const ToolPoseSolution sol = SolveToolPose(cell, tool, 0.0, std::nullopt, nullptr);
  EXPECT_TRUE(sol.ik.ok()) << below_mm << " mm, " << tilt_deg << " deg";
  const CollisionResult r = p.world->Check(sol.ik.joints, CollisionOptions{});
  EXPECT_TRUE(r.error.empty()) << r.error;
  for (const Contact& c : r.contacts) {
    if (c.body_a == "head:probe" && c.body_b == body) {
      EXPECT_EQ(c.kind, ContactClass::kHeadPart);
      return c;
    }
  }
  return std::nullopt;
}

// Its depth in mm, -1 when there is no contact.
double DepthMm(Probe& p, double below_mm, double tilt_deg, const std::string& body = "mold") {
  const std::optional<Contact> c = ContactAt(p, below_mm, tilt_deg, body);
  if (!c) return -1.0;
  EXPECT_TRUE(c->depth_measured);
  return c->depth_m * 1000.0;
}

// A box tilted about its x axis dips its lower edge hy sin(tilt) below the tool point: with
// the tool point at 3 - hy sin(tilt) mm under the surface the depth is 3.0 mm at every tilt
// (FCL's mesh contact depth gave 0.16 mm at 3 deg and 85-107 mm at 2 and 9 deg for the AFP
// feed module, issue 10 item 6).
TEST(SlabDepthTest, BoxDepthEqualsTheHandValueAtEveryTilt) {
  Probe p = MakeProbe("probe_box", BoxGeom(), 50.0);
  ASSERT_TRUE(p.world);
  for (double tilt : {0.0, 2.0, 3.0, 9.0, 15.0, -7.0}) {
    const double below = 3.0 - kBoxHalfMm[1] * std::sin(std::abs(tilt) * kDeg);
    EXPECT_NEAR(DepthMm(p, below, tilt), 3.0, 1e-6) << tilt << " deg";
    // Through the 2 mm preform: its whole thickness.
    EXPECT_NEAR(DepthMm(p, below, tilt, "preform"), 2.0, 1e-6) << tilt << " deg";
  }
}

// Depth follows the placement one to one (smooth and monotonic), at a fixed tilt.
TEST(SlabDepthTest, BoxDepthFollowsThePlacement) {
  Probe p = MakeProbe("probe_box", BoxGeom(), 50.0);
  ASSERT_TRUE(p.world);
  const double dip = kBoxHalfMm[1] * std::sin(3.0 * kDeg);
  double previous = 0.0;
  for (double below = 0.25; below <= 12.0; below += 0.25) {
    const double depth = DepthMm(p, below, 3.0);
    EXPECT_NEAR(depth, below + dip, 1e-6) << below;
    EXPECT_GT(depth, previous);
    previous = depth;
  }
  // Clear of the mold (preform only) when the lowest edge is above the surface.
  EXPECT_EQ(DepthMm(p, -dip - 0.5, 3.0), -1.0);
}

// A ball's lowest point: its centre sits r along the tilted tool z from the tool point.
TEST(SlabDepthTest, BallDepthEqualsTheHandValue) {
  Probe p = MakeProbe("probe_ball", BallGeom(), 50.0);
  ASSERT_TRUE(p.world);
  for (double tilt : {0.0, 3.0, 9.0, 30.0}) {
    for (double below : {1.0, 3.0, 8.0}) {
      const double hand = below - kBallRadiusMm * std::cos(tilt * kDeg) + kBallRadiusMm;
      EXPECT_NEAR(DepthMm(p, below, tilt), hand, 1e-6) << below << " mm, " << tilt << " deg";
    }
  }
}

// On a convex cylinder (radius R, axis R under the crown) the deepest point of the probe's
// flat far face, tilted phi about the axis direction, is the foot of the perpendicular from
// the axis, inside the face and off its grid: depth = R - (R - below) cos(phi).
TEST(SlabDepthTest, BoxFaceDeepestPointOnAConvexCylinder) {
  constexpr double kR = 300.0;
  Probe p = MakeProbe("probe_box", BoxGeom(), 50.0, "",
                      "  type: cylinder\n  radius: 300\n  side: outside\n  length: 600\n"
                      "  arc_length: 400\n");
  ASSERT_TRUE(p.world);
  for (double tilt : {0.0, 1.0, 2.0, 3.0}) {
    for (double below : {1.0, 3.0, 6.0}) {
      // The foot point lies (R - below) sin(phi) from the face centre: inside its 20 mm.
      ASSERT_LT((kR - below) * std::sin(tilt * kDeg), kBoxHalfMm[1]);
      const double hand = kR - (kR - below) * std::cos(tilt * kDeg);
      EXPECT_NEAR(DepthMm(p, below, tilt), hand, 0.01) << below << " mm, " << tilt << " deg";
    }
  }
}

// A body wholly inside the mold crosses none of its triangles; it is a contact all the same,
// with the depth of its deepest point under the surface.
TEST(SlabDepthTest, BodyWhollyInsideTheMoldIsReported) {
  Probe p = MakeProbe("probe_box", BoxGeom(), 200.0);
  ASSERT_TRUE(p.world);
  // The box spans 150..70 mm under the surface (mold 0..200): inside, touching no face.
  EXPECT_NEAR(DepthMm(p, 150.0, 0.0), 150.0, 1e-6);
  EXPECT_EQ(DepthMm(p, 150.0, 0.0, "preform"), -1.0);
  const double tilted = DepthMm(p, 120.0, 9.0);
  EXPECT_NEAR(tilted, 120.0 + kBoxHalfMm[1] * std::sin(9.0 * kDeg), 1e-6);
  // Ball too.
  Probe ball = MakeProbe("probe_ball", BallGeom(), 200.0);
  ASSERT_TRUE(ball.world);
  EXPECT_NEAR(DepthMm(ball, 100.0, 0.0), 100.0, 1e-6);
}

// Against a mesh constraint FCL's depth is one triangle's: the contact is reported, no depth.
TEST(SlabDepthTest, MeshConstraintContactHasNoDepth) {
  const fs::path stl = ScratchDir() / "cube.stl";
  {
    // A 100 mm cube on the surface at the part origin, 12 outward triangles.
    std::ofstream out(stl);
    out << "solid cube\n";
    const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& t : f) {
      out << "facet normal 0 0 0\nouter loop\n";
      for (int k : t) {
        out << "vertex " << ((k & 1) ? 50 : -50) << " " << ((k & 2) ? 50 : -50) << " "
            << ((k & 4) ? 100 : 0) << "\n";
      }
      out << "endloop\nendfacet\n";
    }
    out << "endsolid cube\n";
  }
  Probe p = MakeProbe("probe_box", BoxGeom(), 50.0,
                      "constraints:\n  - {name: cube, type: mesh, file: " + stl.string() + "}\n");
  ASSERT_TRUE(p.world);
  // The probe's far face 50 mm above the surface: through the cube's top face.
  const std::optional<Contact> c = ContactAt(p, -50.0, 0.0, "constraint:cube");
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->depth_measured);
  EXPECT_EQ(c->depth_m, 0.0);
  EXPECT_EQ(DepthMm(p, -50.0, 0.0), -1.0);  // clear of the mold
}

}  // namespace
}  // namespace stitchsim::sim
