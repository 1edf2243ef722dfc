// Collision world and rules: clean poses clear, interferences caught with their line, the
// between-samples guarantee, bundled scenes free of false positives, unsupported geometry an
// error. Uses the real FCL and MuJoCo (no mocks).
#include "stitchsim/sim/collision.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "sim_test_support.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/afp_planner.h"
#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::sim {
namespace {

std::filesystem::path SourceDir() { return std::filesystem::path(STITCHSIM_SOURCE_DIR); }

struct Loaded {
  std::unique_ptr<scene::Scene> scene;
  std::optional<RobotModel> robot;
  std::unique_ptr<CollisionWorld> world;
};

Loaded Load(const std::filesystem::path& file) {
  Loaded l;
  DiagnosticSink sink;
  l.scene = scene::LoadScene(file, sink);
  EXPECT_TRUE(l.scene) << testing::FormatAll(sink);
  if (!l.scene) return l;
  l.robot = LoadRobotModel(l.scene->cell_urdf, sink);
  EXPECT_TRUE(l.robot) << testing::FormatAll(sink);
  if (!l.robot) return l;
  l.world = CollisionWorld::Create(*l.scene, *l.robot, sink);
  EXPECT_TRUE(l.world) << testing::FormatAll(sink);
  EXPECT_EQ(sink.Diagnostics().size(), 0u) << testing::FormatAll(sink);
  return l;
}

std::string PlanDecoupled(const scene::Scene& scene, const scene::PathSpec& path) {
  DiagnosticSink sink;
  planner::StitchPlanOptions options;
  options.mode = planner::Mode::kDecoupled;
  auto p = planner::StitchPathPlanner::Create(scene, path, options, sink);
  EXPECT_TRUE(p) << testing::FormatAll(sink);
  std::ostringstream out;
  if (p) planner::WriteStitchProgram(*p, scene, path.name, program::Dialect::Default(), out);
  return out.str();
}

// Executes `text` and runs every rule, the collision rules included.
verify::Report Verify(const Loaded& l, const std::string& text, bool subdivide) {
  const CellSetup cell = MakeCellSetup(*l.robot, *l.scene);
  const process::ProcessModel model =
      process::MakeProcessModel(*l.scene, l.scene->nominal_stitch_length_mm);
  const trace::CellDescription cell_description = DescribeCell(*l.robot, l.world.get());
  verify::RuleContext ctx{l.scene.get(), &cell_description, &model};
  verify::Verifier verifier(ctx, false);
  ExecuteOptions options = ExecuteOptionsFor(*l.scene);
  options.collision = l.world.get();
  options.collision_subdivide = subdivide;
  std::istringstream in(text);
  DiagnosticSink sink;
  const ExecutionSummary run = ExecuteProgram(cell, model, program::Dialect::Default(), in,
                                              "test.nc", options, sink, verifier);
  EXPECT_TRUE(run.ok) << testing::FormatAll(sink);
  verify::Report report;
  verifier.Finish(report);
  return report;
}

const verify::RuleSummary* RuleOf(const verify::Report& r, const std::string& id) {
  for (const auto& s : r.rules) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

// The programme line `line` (1-based).
std::string LineOf(const std::string& text, int line) {
  std::istringstream in(text);
  std::string s;
  for (int i = 0; i < line && std::getline(in, s); ++i) {
  }
  return s;
}

double WordOf(const std::string& line, char letter) {
  const auto p = line.find(letter);
  return p == std::string::npos ? 0.0 : std::stod(line.substr(p + 1));
}

TEST(CollisionTest, CleanPosesAreClear) {
  Loaded l = Load(SourceDir() / "scenes" / "flat_straight.yaml");
  ASSERT_TRUE(l.world);
  const CellSetup cell = MakeCellSetup(*l.robot, *l.scene);
  for (double x : {-300.0, 0.0, 300.0}) {
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
    tool.translation() = Eigen::Vector3d(x, 0, 0);
    tool.linear() = Eigen::AngleAxisd(-90 * kDeg, Eigen::Vector3d::UnitZ()).matrix();
    const ToolPoseSolution sol = SolveToolPose(cell, tool, 0.0, std::nullopt, nullptr);
    ASSERT_TRUE(sol.ik.ok());
    const CollisionResult r = l.world->Check(sol.ik.joints, {});
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_TRUE(r.contacts.empty())
        << r.contacts.front().body_a << "|" << r.contacts.front().body_b;
    // The presser foot rides 0.2 mm over the preform (allowed); the nearest forbidden pair is
    // the needle housing over the preform top, about 18 mm.
    EXPECT_GT(r.min_clearance_m, 0.010) << r.min_clearance_pair;
  }
  const CollisionResult home = l.world->Check(HomeJoints(*l.robot, 3.0), {});
  EXPECT_TRUE(home.contacts.empty());
}

TEST(CollisionTest, MaxPointTravelBoundsTheRealMotion) {
  Loaded l = Load(SourceDir() / "scenes" / "flat_straight.yaml");
  ASSERT_TRUE(l.world);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int flange = l.robot->flange_link();
  const Eigen::Vector3d tip(0, 0, 0.7);  // the head's tool point, flange frame
  for (int i = 0; i < 200; ++i) {
    JointVector a = HomeJoints(*l.robot, 3.0);
    for (int j = kA1; j <= kA6; ++j) a[j] += 0.8 * u(rng);
    JointVector b = a;
    for (int j = kRailX; j <= kA6; ++j) b[j] += 0.05 * u(rng);
    const double bound = l.world->MaxPointTravel(a, b);
    EXPECT_EQ(l.world->MaxPointTravel(a, a), 0.0);
    for (int k = 0; k <= 10; ++k) {
      const JointVector q = a + (b - a) * (k / 10.0);
      const double moved =
          (LinkPose(*l.robot, q, flange) * tip - LinkPose(*l.robot, a, flange) * tip).norm();
      EXPECT_LE(moved, bound + 1e-12);
    }
  }
}

TEST(CollisionTest, Rs566SeamIntoStringerCaughtWithLine) {
  Loaded l = Load(SourceDir() / "scenes" / "rs566_stringer_seam.yaml");
  ASSERT_TRUE(l.world);
  const std::string text = PlanDecoupled(*l.scene, l.scene->paths.front());
  const verify::Report report = Verify(l, text, true);
  const verify::RuleSummary* head = RuleOf(report, "collision.head_mold");
  ASSERT_NE(head, nullptr);
  ASSERT_GT(head->errors, 0);
  const verify::Finding& first = head->findings.front();
  EXPECT_NE(first.subject.find("constraint:stringer"), std::string::npos) << first.subject;
  // The stringer's near face is at u = 140 mm; the presser foot reaches 30 mm ahead of the
  // tool point, so the first hit is where the programmed X passes about 110 mm.
  const double x = WordOf(LineOf(text, first.line), 'X');
  EXPECT_GT(x, 100.0) << LineOf(text, first.line);
  EXPECT_LT(x, 140.0) << LineOf(text, first.line);
  // The C-frame's lower arm and table run under the preform: allowed, never reported.
  for (const auto& f : head->findings) {
    EXPECT_EQ(f.subject.find("ee_table|preform"), std::string::npos);
    EXPECT_EQ(f.subject.find("cframe_lower_arm|mold"), std::string::npos);
  }
  EXPECT_EQ(RuleOf(report, "collision.robot_cell")->errors, 0);
}

TEST(CollisionTest, RailAndCarriageHitCaught) {
  Loaded l = Load(SourceDir() / "scenes" / "rail_hit.yaml");
  ASSERT_TRUE(l.world);
  // Hand-written pose: the arm turned round over the carriage, elbow folded down.
  JointVector q = JointVector::Zero();
  q << 3.0, 180 * kDeg, 0.0, 100 * kDeg, 0.0, 90 * kDeg, 0.0, 0.0;
  const CollisionResult r = l.world->Check(q, {});
  ASSERT_TRUE(r.error.empty());
  bool carriage = false;
  for (const Contact& c : r.contacts) {
    EXPECT_EQ(c.kind, ContactClass::kRobotCell);
    EXPECT_GT(c.depth_m, 0.0);
    carriage = carriage || c.body_a == "carriage" || c.body_b == "carriage";
  }
  EXPECT_TRUE(carriage);
  EXPECT_EQ(r.min_clearance_m, 0.0);
  // The scene's own row: the coupon hangs low beside the rail, its face tilted back towards
  // it, the carriage parked 1 m along the rail; the head reaching down and back to it clips
  // the rail beam with its body on every line, and nothing else is hit.
  const std::string text = PlanDecoupled(*l.scene, l.scene->paths.front());
  const verify::Report report = Verify(l, text, true);
  const verify::RuleSummary* cell = RuleOf(report, "collision.robot_cell");
  ASSERT_NE(cell, nullptr);
  EXPECT_GE(cell->errors, 80);
  ASSERT_FALSE(cell->findings.empty());
  for (const verify::Finding& f : cell->findings) {
    EXPECT_NE(f.subject.find("|rail"), std::string::npos) << f.subject;
    EXPECT_NE(f.subject.find("head:"), std::string::npos) << f.subject;
    EXPECT_EQ(f.subject.find("rotator"), std::string::npos) << f.subject;
    EXPECT_GT(f.line, 0);
    EXPECT_GT(f.value, 0.0);
  }
  // The first finding is at the start pose (the G0 line), then one per stitch line.
  EXPECT_EQ(LineOf(text, cell->findings.front().line).rfind("G0", 0), 0u)
      << LineOf(text, cell->findings.front().line);
  EXPECT_EQ(RuleOf(report, "collision.head_mold")->errors, 0);
  EXPECT_EQ(report.errors, cell->errors) << "only the rail hit is expected";
}

std::string PlanAfp(const scene::Scene& scene, double incline_deg) {
  DiagnosticSink sink;
  planner::AfpPlanOptions options;
  options.lay_angle_rad = 45.0 * kDeg;
  options.incline_rad = incline_deg * kDeg;
  auto plan = planner::PlanAfpCourse(scene, nullptr, options, sink);
  EXPECT_TRUE(plan) << testing::FormatAll(sink);
  std::ostringstream out;
  if (plan) planner::WriteAfpProgram(*plan, scene, program::Dialect::Default(), out);
  return out.str();
}

// Seed 003: in the 300 mm concave cylinder the head's approach side (the feed module ahead
// of the roller) runs into the mold at normal pressure; leaning the head back along the
// course tangent clears it, with nothing else in the way.
TEST(CollisionTest, AfpNormalPressureHitsSmallConcaveMoldAndInclinationClears) {
  Loaded l = Load(SourceDir() / "scenes" / "concave_cylinder_small.yaml");
  ASSERT_TRUE(l.world);
  const std::string normal = PlanAfp(*l.scene, 0.0);
  const verify::Report at_normal = Verify(l, normal, true);
  const verify::RuleSummary* head = RuleOf(at_normal, "collision.head_mold");
  ASSERT_NE(head, nullptr);
  ASSERT_GT(head->errors, 0);
  double deepest = 0.0;
  for (const verify::Finding& f : head->findings) {
    EXPECT_GT(f.line, 0);
    EXPECT_GT(f.value, 0.0);
    // The roller on the laminate is the one allowed contact.
    EXPECT_EQ(f.subject.find("roller|"), std::string::npos) << f.subject;
    EXPECT_NE(f.subject.find("head:feed_module"), std::string::npos) << f.subject;
    deepest = std::max(deepest, f.value);
  }
  EXPECT_GT(deepest, 5.0);
  EXPECT_EQ(LineOf(normal, head->findings.front().line).rfind("G", 0), 0u);
  // Normal pressure is reachable: the mold hit is the only error.
  EXPECT_EQ(at_normal.errors, head->errors);
  // Leaning back 10 deg: clean, every rule.
  const verify::Report leaned = Verify(l, PlanAfp(*l.scene, -10.0), true);
  EXPECT_EQ(leaned.errors, 0);
  for (const auto& s : leaned.rules) {
    EXPECT_EQ(s.errors, 0) << s.id << ": "
                           << (s.findings.empty() ? "" : s.findings.front().message);
  }
  // Leaning forward makes it worse.
  EXPECT_GT(RuleOf(Verify(l, PlanAfp(*l.scene, 10.0), true), "collision.head_mold")->errors, 0);
}

int RunCli(const std::string& args, const std::filesystem::path& out) {
  const std::string cmd =
      (std::filesystem::path(STITCHSIM_BINARY_DIR) / "app" / "stitchsim").string() + " " + args +
      " >" + out.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The same through the CLI: `plan afp --incline 0` then `verify` finds collision.head_mold
// (exit 1); `--incline auto` picks a non-zero lean whose programme verifies clean (exit 0).
TEST(CollisionTest, AfpInclineAutoClearsTheSmallConcaveMoldCli) {
  const auto dir = std::filesystem::temp_directory_path() / "stitchsim_collision_afp_cli";
  std::filesystem::create_directories(dir);
  const std::string scene = (SourceDir() / "scenes" / "concave_cylinder_small.yaml").string();
  const auto p0 = dir / "p0.nc";
  const auto pa = dir / "pa.nc";
  ASSERT_EQ(RunCli("plan afp --scene " + scene + " --lay-angle 45 --incline 0 -o " + p0.string(),
                   dir / "plan0.txt"),
            0)
      << Slurp(dir / "plan0.txt");
  EXPECT_EQ(RunCli("verify " + p0.string() + " --scene " + scene + " --quiet", dir / "verify0.txt"),
            1);
  const std::string v0 = Slurp(dir / "verify0.txt");
  EXPECT_NE(v0.find("head:feed_module hits"), std::string::npos) << v0;
  EXPECT_NE(v0.find("depth"), std::string::npos) << v0;
  EXPECT_NE(v0.find("collision.head_mold: "), std::string::npos) << v0;

  ASSERT_EQ(RunCli("plan afp --scene " + scene + " --lay-angle 45 --incline auto -o " + pa.string(),
                   dir / "plana.txt"),
            0)
      << Slurp(dir / "plana.txt");
  const std::string plan = Slurp(dir / "plana.txt");
  const std::string tag = "incline auto: ";
  const auto at = plan.find(tag);
  ASSERT_NE(at, std::string::npos) << plan;
  const double theta = std::stod(plan.substr(at + tag.size()));
  EXPECT_NE(theta, 0.0);
  EXPECT_LE(std::abs(theta), 20.0);
  EXPECT_NE(plan.find("incline 0.000 deg: rejected: collision.head_mold at line "),
            std::string::npos)
      << plan;
  EXPECT_EQ(RunCli("verify " + pa.string() + " --scene " + scene + " --quiet", dir / "verifya.txt"),
            0)
      << Slurp(dir / "verifya.txt");
  EXPECT_EQ(Slurp(dir / "verifya.txt").rfind("PASS", 0), 0u) << Slurp(dir / "verifya.txt");
}

// The broad phase (near lists kept while the motion bound allows, oriented-box bounds,
// nearest-first distances) must give what checking every pair gives: the same contact pairs
// and the same clearance, on random walks of the head near each part (touching, clear and
// penetrating), with jumps that force the near lists to be rebuilt. The wing's mesh makes
// checking every pair 60 times slower than on the other parts: it gets 2 walks, they 8.
TEST(CollisionTest, BroadPhaseAgreesWithCheckingEveryPair) {
  int compared = 0, with_contacts = 0;
  for (const char* name :
       {"wing_cover", "rs566_stringer_seam", "concave_cylinder_small", "rail_hit", "cutout_slot"}) {
    const int walks = std::string(name) == "wing_cover" ? 2 : 8;
    Loaded l = Load(SourceDir() / "scenes" / (std::string(name) + ".yaml"));
    ASSERT_TRUE(l.world) << name;
    const CellSetup cell = MakeCellSetup(*l.robot, *l.scene);
    const geom::Surface& s = *l.scene->surface;
    const geom::Domain2 dom = s.Domain();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (int walk = 0; walk < walks; ++walk) {
      Eigen::Vector2d uv =
          dom.min + (dom.max - dom.min).cwiseProduct(Eigen::Vector2d(u01(rng), u01(rng)));
      double yaw = 360.0 * u01(rng) * kDeg;
      double standoff = -15.0 + 75.0 * u01(rng);
      const JointVector* prev = nullptr;
      JointVector last;
      for (int step = 0; step < 25; ++step) {
        uv += Eigen::Vector2d(8.0 * (u01(rng) - 0.5), 8.0 * (u01(rng) - 0.5));
        uv = uv.cwiseMax(dom.min).cwiseMin(dom.max);
        yaw += 4.0 * (u01(rng) - 0.5) * kDeg;
        standoff += 4.0 * (u01(rng) - 0.5);
        Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
        const Eigen::Vector3d n = s.Normal(uv);
        tool.translation() = s.Point(uv) + standoff * n;
        const Eigen::Vector3d t = s.Jacobian(uv).col(0).normalized();
        const Eigen::Vector3d y = (std::cos(yaw) * t + std::sin(yaw) * n.cross(t)).normalized();
        tool.linear().col(2) = n;
        tool.linear().col(1) = y;
        tool.linear().col(0) = y.cross(n);
        const ToolPoseSolution sol = SolveToolPose(cell, tool, 0.0, std::nullopt, prev);
        if (!sol.ik.ok()) continue;
        last = sol.ik.joints;
        prev = &last;
        CollisionOptions fast;
        CollisionOptions naive;
        naive.naive_baseline = true;
        const CollisionResult a = l.world->Check(sol.ik.joints, fast);
        const CollisionResult b = l.world->Check(sol.ik.joints, naive);
        ASSERT_TRUE(a.error.empty() && b.error.empty()) << a.error << b.error;
        auto pairs = [](const CollisionResult& r) {
          std::vector<std::string> v;
          for (const Contact& c : r.contacts) {
            v.push_back(std::min(c.body_a, c.body_b) + "|" + std::max(c.body_a, c.body_b));
          }
          std::sort(v.begin(), v.end());
          v.erase(std::unique(v.begin(), v.end()), v.end());
          return v;
        };
        EXPECT_EQ(pairs(a), pairs(b)) << name << " walk " << walk << " step " << step;
        EXPECT_NEAR(a.min_clearance_m, b.min_clearance_m, 1e-9)
            << name << " walk " << walk << " step " << step << ": " << a.min_clearance_pair;
        ++compared;
        with_contacts += a.contacts.empty() ? 0 : 1;
      }
    }
  }
  EXPECT_GE(compared, 400);
  EXPECT_GE(with_contacts, 40);  // the walks do reach into parts and constraints
  std::printf("compared %d poses, %d with contacts\n", compared, with_contacts);
}

// Every bundled stitching scene's decoupled programme verifies free of collision findings,
// except the scenes built to interfere.
TEST(CollisionTest, BundledCleanScenesHaveNoFalsePositives) {
  const std::map<std::string, std::string> interfering = {
      {"rail_hit", "by design"},
      {"rs566_stringer_seam", "by design"},
      {"concave_cylinder_small", "AFP, by design"},
      {"afp_concave_cylinder", "AFP course"}};
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourceDir() / "scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().stem().string();
    Loaded l = Load(entry.path());
    ASSERT_TRUE(l.world) << name;
    if (!l.scene->head.IsStitching()) continue;
    for (const auto& path : l.scene->paths) {
      const verify::Report report = Verify(l, PlanDecoupled(*l.scene, path), true);
      const auto* head = RuleOf(report, "collision.head_mold");
      const auto* cell = RuleOf(report, "collision.robot_cell");
      ASSERT_TRUE(head && cell);
      if (interfering.count(name) != 0) continue;
      ++checked;
      EXPECT_EQ(head->errors, 0) << name << " " << path.name << ": "
                                 << (head->findings.empty() ? "" : head->findings[0].message);
      EXPECT_EQ(cell->errors, 0) << name << " " << path.name << ": "
                                 << (cell->findings.empty() ? "" : cell->findings[0].message);
      // The frame-flange line ends 2 mm from the stringer faces: a clearance warning is
      // the right call there; everywhere else there must be none.
      if (name != "cylinder_r90_frame") {
        EXPECT_EQ(RuleOf(report, "collision.clearance")->warnings, 0) << name << " " << path.name;
      }
    }
  }
  EXPECT_GE(checked, 5);
}

// A 2 mm plate across a 600 mm move, struck only by the needles: the plain 20 mm grid steps
// over it; with the world given to the executor, the clearance-bounded steps catch it.
TEST(CollisionTest, ThinPlateBetweenSamplesIsCaught) {
  const auto dir = std::filesystem::temp_directory_path() / "stitchsim_collision_test";
  std::filesystem::create_directories(dir);
  const auto scene_file = dir / "plate.yaml";
  std::ofstream(scene_file) << "stitchsim_scene: 1\nname: plate\nunits: mm\nhead: rs535\n"
                               "part:\n  mount: table\n  position: [0, 0, 50]\n"
                               "surface:\n  type: plane\n  size: [1000, 600]\n"
                               "preform:\n  thickness: 12\nmold:\n  depth: 50\n"
                               "constraints:\n"
                               "  - {name: plate, type: box, center: [10.7, 0, 6], "
                               "size: [2, 100, 8]}\n"
                               "paths:\n  - {name: row, type: line, from: [-300, 0], "
                               "to: [300, 0]}\n";
  Loaded l = Load(scene_file);
  ASSERT_TRUE(l.world);
  const std::string text =
      "%\nG21 G90\nT1 M6\nG0 X-300 Y0 Z0 A0 B0 C-90 U0 V0\n"
      "G1 X300 Y0 Z0 A0 B0 C-90 F3000\nM30\n%\n";
  const verify::Report coarse = Verify(l, text, false);
  EXPECT_EQ(RuleOf(coarse, "collision.head_mold")->errors, 0) << "the grid should miss it";
  const verify::Report fine = Verify(l, text, true);
  const auto* head = RuleOf(fine, "collision.head_mold");
  ASSERT_GT(head->errors, 0);
  EXPECT_EQ(head->findings.front().line, 5);
  EXPECT_NE(head->findings.front().subject.find("head:needle"), std::string::npos);
  EXPECT_NE(head->findings.front().subject.find("constraint:plate"), std::string::npos);
}

// A head geometry FCL cannot be given (an ellipsoid) is an error, never "clear".
TEST(CollisionTest, UnsupportedGeometryIsAnError) {
  const auto dir = std::filesystem::temp_directory_path() / "stitchsim_collision_test";
  std::filesystem::create_directories(dir);
  std::ifstream head_in(SourceDir() / "models" / "heads" / "rs535.yaml");
  std::stringstream head;
  head << head_in.rdbuf();
  std::string head_text = head.str();
  head_text.replace(head_text.find("mjcf: rs535.xml"), 15, "mjcf: odd.xml");
  std::ofstream(dir / "odd.yaml") << head_text;
  std::ofstream(dir / "odd.xml")
      << "<mujoco model=\"odd\"><worldbody><body name=\"head\">"
         "<geom name=\"blob\" type=\"ellipsoid\" size=\"0.1 0.1 0.2\" pos=\"0 0 0.3\"/>"
         "<site name=\"tool_point\" pos=\"0 0 0.7\" euler=\"180 0 0\"/>"
         "</body></worldbody></mujoco>";
  std::ofstream(dir / "odd_scene.yaml")
      << "stitchsim_scene: 1\nname: odd\nunits: mm\nhead: " << (dir / "odd.yaml").string()
      << "\npart:\n  mount: table\n  position: [0, 0, 50]\n"
         "surface:\n  type: plane\n  size: [400, 400]\n"
         "paths:\n  - {name: row, type: line, from: [-100, 0], to: [100, 0]}\n";
  DiagnosticSink sink;
  auto scene = scene::LoadScene(dir / "odd_scene.yaml", sink);
  ASSERT_TRUE(scene) << testing::FormatAll(sink);
  auto robot = LoadRobotModel(scene->cell_urdf, sink);
  ASSERT_TRUE(robot);
  EXPECT_EQ(CollisionWorld::Create(*scene, *robot, sink), nullptr);
  ASSERT_TRUE(sink.HasErrors());
  EXPECT_EQ(sink.Diagnostics().front().code, "collision-unsupported-geom")
      << testing::FormatAll(sink);
}

}  // namespace
}  // namespace stitchsim::sim
