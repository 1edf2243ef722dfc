// The programme executed on the MuJoCo model (S10): the MuJoCo and URDF routes agree on every
// sample; the timed trajectory against hand-computed trapezoids; MuJoCo's inverse dynamics
// against hand statics and Newton's law; kin.torque, kin.payload, kin.acceleration on the
// right line; the dynamic mode's lag reaching the needle rules.
#include "stitchsim/sim/dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "stitchsim/planner/stitch_planner.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/verify/verifier.h"
#include "verify_test_support.h"

namespace stitchsim::verify {
namespace {

using testing::Load;
using testing::Loaded;

constexpr double kGravity = 9.81;
// Tuned by the figures the tests print (docs/timing.md gives them).
constexpr double kHeavyHeadKg = 2000.0;
constexpr double kFastFeed = 60000.0;  // mm/min
constexpr double kSlowFeed = 6000.0;

// Every sample the pipeline hands on.
struct Capture final : trace::TraceSink {
  std::vector<trace::LineRecord> lines;
  std::vector<trace::TraceSample> samples;
  void OnLine(const trace::LineRecord& l) override { lines.push_back(l); }
  void OnSample(const trace::TraceSample& s) override { samples.push_back(s); }
};

struct Tee final : trace::TraceSink {
  trace::TraceSink& a;
  trace::TraceSink& b;
  Tee(trace::TraceSink& x, trace::TraceSink& y) : a(x), b(y) {}
  void OnLine(const trace::LineRecord& l) override {
    a.OnLine(l);
    b.OnLine(l);
  }
  void OnSample(const trace::TraceSample& s) override {
    a.OnSample(s);
    b.OnSample(s);
  }
};

struct Outcome {
  bool ok = false;
  std::string diagnostics;
  Report report;
  Capture capture;
  double simple_time_s = 0.0;
  double timed_s = 0.0;
  sim::DynamicsFigures dynamics;
  const RuleSummary* Rule(const std::string& id) const {
    for (const auto& r : report.rules) {
      if (r.id == id) return &r;
    }
    return nullptr;
  }
};

// What `stitchsim verify` runs (app/src/verify_cmd.cpp), without collision: the executor on
// MuJoCo's kinematics, the timing sink, with `dynamics` the physics, then the verifier.
Outcome Execute(const Loaded& l, const std::string& text, double stitch_length_mm, bool dynamics) {
  Outcome r;
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  const process::ProcessModel model = process::MakeProcessModel(*l.scene, stitch_length_mm);
  DiagnosticSink sink;
  auto kin = sim::MujocoCell::Create(*l.scene, *l.robot, cell, sink);
  EXPECT_NE(kin, nullptr) << (sink.Diagnostics().empty() ? "" : sink.Diagnostics()[0].message);
  if (!kin) return r;
  auto timing_cell = kin->Share(), physics = kin->Share(), poses = kin->Share();
  trace::CellDescription description = sim::DescribeCell(*l.robot, nullptr);
  description.timed = true;
  description.dynamic = dynamics;
  RuleContext ctx{l.scene.get(), &description, &model};
  Verifier verifier(ctx, false);
  Tee tee(verifier, r.capture);
  sim::DynamicsSink physics_sink(*physics, *poses, tee);
  sim::ExecuteOptions options = sim::ExecuteOptionsFor(*l.scene);
  options.mujoco = kin.get();
  options.solve_every_sample = dynamics;
  sim::TimingOptions timing_options;
  timing_options.settle_time_s = options.settle_time_s;
  sim::TimingSink timing(*timing_cell, *l.robot, timing_options,
                         dynamics ? static_cast<trace::TraceSink&>(physics_sink) : tee);
  std::istringstream in(text);
  const sim::ExecutionSummary run = sim::ExecuteProgram(cell, model, program::Dialect::Default(),
                                                        in, "test.nc", options, sink, timing);
  timing.Finish();
  for (const auto& d : sink.Diagnostics()) r.diagnostics += FormatDiagnostic(d) + "\n";
  r.ok = run.ok;
  r.simple_time_s = run.time_s;
  r.timed_s = timing.CycleTime();
  r.dynamics = physics_sink.Figures();
  verifier.Finish(r.report);
  return r;
}

std::string PlanCircle(const Loaded& l, planner::Mode mode) {
  DiagnosticSink sink;
  planner::StitchPlanOptions opt;
  opt.mode = mode;
  auto pl = planner::StitchPathPlanner::Create(*l.scene, *l.scene->FindPath("circle"), opt, sink);
  EXPECT_TRUE(pl.has_value());
  std::ostringstream out;
  planner::WriteStitchProgram(*pl, *l.scene, "circle", program::Dialect::Default(), out);
  return out.str();
}

// A straight move of the tool in the part frame of circle_8in (table mount: part axes are
// the world's): from `from` to `to` (mm), tool z up, at `feed` mm/min.
std::string Move(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double feed) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "G21 G90\nG1 X%.6f Y%.6f Z%.6f A0 B0 C0 F%.3f\nG1 X%.6f Y%.6f Z%.6f\nM30\n",
                from.x(), from.y(), from.z(), feed, to.x(), to.y(), to.z());
  return buf;
}

double Worst(const RuleSummary* r) {
  return r != nullptr && r->worst_value ? *r->worst_value : -1.0;
}

double MaxAbs(const std::vector<trace::TraceSample>& samples, int joint,
              trace::JointVector trace::TraceSample::*field) {
  double m = 0.0;
  for (const auto& s : samples) {
    if (s.has_timing && trace::JointsUsable(s)) m = std::max(m, std::abs((s.*field)[joint]));
  }
  return m;
}

// ---------------------------------------------------------------------------------------------
// Two routes to the frames: MuJoCo's kinematics (what the executor now uses) and the URDF FK.

TEST(dynamics, MujocoAndUrdfRoutesAgreeOnEverySampleOfTheCircle) {
  const Loaded l = Load("circle_8in");
  const Outcome r = Execute(l, PlanCircle(l, planner::Mode::kDecoupled), 5.0, true);
  ASSERT_TRUE(r.ok) << r.diagnostics;
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  DiagnosticSink sink;
  auto mj = sim::MujocoCell::Create(*l.scene, *l.robot, cell, sink);
  ASSERT_NE(mj, nullptr);
  long checked = 0;
  double worst_m = 0.0, worst_rad = 0.0;
  for (const auto& s : r.capture.samples) {
    if (!trace::JointsUsable(s)) continue;
    mj->SetJoints(s.joints);
    const Eigen::Isometry3d urdf = sim::ToolPoseInPart(cell, s.joints);
    const Eigen::Isometry3d mujoco = mj->ToolInPartMm();
    worst_m = std::max(worst_m, (urdf.translation() - mujoco.translation()).norm() / 1000.0);
    worst_rad =
        std::max(worst_rad, Eigen::AngleAxisd(urdf.linear().transpose() * mujoco.linear()).angle());
    for (std::size_t k = 0; k < l.robot->links().size(); ++k) {
      const Eigen::Isometry3d a = sim::LinkPose(*l.robot, s.joints, static_cast<int>(k));
      const Eigen::Isometry3d b = mj->LinkWorld(static_cast<int>(k));
      worst_m = std::max(worst_m, (a.translation() - b.translation()).norm());
      worst_rad =
          std::max(worst_rad, Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle());
    }
    ++checked;
  }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst_m, 1e-9);
  EXPECT_LT(worst_rad, 1e-9);
  std::printf("MuJoCo vs URDF on %ld samples: %.3e m, %.3e rad\n", checked, worst_m, worst_rad);
}

// ---------------------------------------------------------------------------------------------
// The timed trajectory against hand-computed trapezoids: a move along the rail (part x =
// world x on the table; the rail policy follows it, the arm stands still).

TEST(dynamics, RailMoveIsTheHandTrapezoid) {
  const Loaded l = Load("circle_8in");
  // 1000 mm at 6000 mm/min: cruise 0.1 /s (10 s at the feed), ramp 0.25 s -> 0.4 /s^2 (the
  // rail's 1 m/s^2 does not cap it): 0.25 s up, 9.75 s at speed, 0.25 s down.
  const Outcome slow = Execute(l, Move({-500, 0, 0}, {500, 0, 0}, 6000.0), 5.0, false);
  ASSERT_TRUE(slow.ok) << slow.diagnostics;
  EXPECT_NEAR(slow.simple_time_s, 10.0, 1e-9);
  EXPECT_NEAR(slow.timed_s, 10.25, 1e-9);
  // At 60000 mm/min the rail's 1 m/s and 1 m/s^2 cap it: a triangle, 1 s up, 1 s down.
  const Outcome fast = Execute(l, Move({-500, 0, 0}, {500, 0, 0}, 60000.0), 5.0, false);
  ASSERT_TRUE(fast.ok) << fast.diagnostics;
  EXPECT_NEAR(fast.simple_time_s, 1.0, 1e-9);
  EXPECT_NEAR(fast.timed_s, 2.0, 1e-9);
  EXPECT_NEAR(MaxAbs(fast.capture.samples, trace::kRailX, &trace::TraceSample::joint_velocities),
              1.0, 0.03);  // the peak lies between grid samples 20 mm apart
  EXPECT_NEAR(MaxAbs(fast.capture.samples, trace::kRailX, &trace::TraceSample::joint_accelerations),
              1.0, 1e-6);
}

// A decoupled straight row repeats each stitch's pose in a rotation line that does not turn:
// the controller passes through those blocks, so the row takes as long as the coupled one.
TEST(dynamics, BlocksThatRepeatThePoseDoNotStopTheArm) {
  const Loaded l = Load("flat_straight");
  double timed[2] = {0, 0};
  int k = 0;
  for (planner::Mode mode : {planner::Mode::kCoupled, planner::Mode::kDecoupled}) {
    DiagnosticSink sink;
    planner::StitchPlanOptions opt;
    opt.mode = mode;
    auto pl = planner::StitchPathPlanner::Create(*l.scene, *l.scene->FindPath("row"), opt, sink);
    ASSERT_TRUE(pl.has_value());
    std::ostringstream out;
    planner::WriteStitchProgram(*pl, *l.scene, "row", program::Dialect::Default(), out);
    const Outcome r = Execute(l, out.str(), pl->StitchLengthMm(), false);
    ASSERT_TRUE(r.ok) << r.diagnostics;
    timed[k++] = r.timed_s;
  }
  EXPECT_NEAR(timed[1], timed[0], 1e-6 * timed[0]);
  EXPECT_EQ(Worst(Execute(l, "G21 G90\nG1 X0 Y0 Z0 A0 B0 C0 F600\nG1 X10\nG1 X10\nG1 X20\nM30\n",
                          5.0, false)
                      .Rule("kin.acceleration")) < 100.0,
            true);
}

// Newton on the rail: the carriage carries every link and the head, so the rail force is the
// total moving mass (URDF inertials + head spec + the rail's armature) times the acceleration,
// plus the viscous damping times the speed.
TEST(dynamics, RailForceIsMassTimesAccelerationPlusDamping) {
  const Loaded l = Load("circle_8in");
  ASSERT_TRUE(l.scene->head.inertial.has_value());
  double mass = l.scene->head.inertial->mass_kg;
  bool on_carriage = false;
  for (const auto& link : l.robot->links()) {
    if (link.name == "carriage") on_carriage = true;
    if (link.name == "table" || link.name == "rotator_base" || link.name == "rotator") continue;
    if (on_carriage && link.inertial) mass += link.inertial->mass_kg;
  }
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  DiagnosticSink sink;
  auto mj = sim::MujocoCell::Create(*l.scene, *l.robot, cell, sink);
  ASSERT_NE(mj, nullptr);
  const double armature = mj->Armature(trace::kRailX);
  const double damping = l.robot->dampings()[trace::kRailX];
  const Outcome fast = Execute(l, Move({-500, 0, 0}, {500, 0, 0}, 60000.0), 5.0, false);
  ASSERT_TRUE(fast.ok) << fast.diagnostics;
  int checked = 0;
  for (const auto& s : fast.capture.samples) {
    if (!s.has_timing || !trace::JointsUsable(s)) continue;
    const double v = s.joint_velocities[trace::kRailX], a = s.joint_accelerations[trace::kRailX];
    EXPECT_NEAR(s.joint_torques[trace::kRailX], (mass + armature) * a + damping * v,
                1e-6 * (mass + armature))
        << "line fraction " << s.line_fraction;
    ++checked;
  }
  EXPECT_GT(checked, 40);
  std::printf("rail: moving mass %.1f kg + armature %.1f kg, damping %.1f N s/m\n", mass, armature,
              damping);
}

// The Newton-Euler route the timing sink uses equals mj_inverse on random states.
TEST(dynamics, InverseDynamicsEqualsMujocosOwn) {
  const Loaded l = Load("circle_8in");
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  DiagnosticSink sink;
  auto mj = sim::MujocoCell::Create(*l.scene, *l.robot, cell, sink);
  ASSERT_NE(mj, nullptr);
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    trace::JointVector q, qd, qdd;
    for (int j = 0; j < trace::kNumJoints; ++j) {
      const double lo = l.robot->lower_limits()[j], hi = l.robot->upper_limits()[j];
      q[j] = lo + (hi - lo) * (0.5 + 0.5 * u(rng));
      qd[j] = l.robot->max_velocities()[j] * u(rng);
      qdd[j] = l.robot->max_accelerations()[j] * u(rng);
    }
    const trace::JointVector fast = mj->InverseDynamics(q, qd, qdd);
    const trace::JointVector reference = mj->InverseDynamicsReference(q, qd, qdd);
    for (int j = 0; j < trace::kNumJoints; ++j) {
      EXPECT_NEAR(fast[j], reference[j], 1e-9 * std::max(1.0, std::abs(reference[j]))) << j;
    }
  }
}

// Hand statics: at rest, a2 holds the moment of every mass beyond it about its axis; the URDF
// FK places each centre of mass (and the head spec's), MuJoCo's mj_inverse must agree.
TEST(dynamics, HoldingTorqueIsTheHandStaticsOfTheUrdfMasses) {
  const Loaded l = Load("circle_8in");
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  DiagnosticSink sink;
  auto mj = sim::MujocoCell::Create(*l.scene, *l.robot, cell, sink);
  ASSERT_NE(mj, nullptr);
  const sim::RobotModel& robot = *l.robot;
  const trace::JointVector zero = trace::JointVector::Zero();
  for (const trace::JointVector& q : {sim::HomeJoints(robot, 3.0), trace::JointVector(zero)}) {
    const trace::JointVector tau = mj->InverseDynamics(q, zero, zero);
    for (int j : {trace::kA2, trace::kA3, trace::kA5}) {
      const sim::JointInfo& joint = robot.joint(j);
      const Eigen::Isometry3d frame = sim::LinkPose(robot, q, joint.child_link_index);
      const Eigen::Vector3d axis = frame.linear() * joint.axis, at = frame.translation();
      const Eigen::Vector3d g(0, 0, -kGravity);
      double hand = 0.0;
      // Every link whose chain passes through this joint's child, and the head on the flange.
      for (std::size_t k = 0; k < robot.links().size(); ++k) {
        const auto& chain = robot.ChainTo(static_cast<int>(k));
        if (std::find(chain.begin(), chain.end(), joint.child_link_index) == chain.end()) continue;
        const auto& in = robot.links()[k].inertial;
        if (!in) continue;
        const Eigen::Vector3d c = sim::LinkPose(robot, q, static_cast<int>(k)) * in->com_m;
        hand -= axis.dot((c - at).cross(in->mass_kg * g));
      }
      const auto& head = *l.scene->head.inertial;
      const Eigen::Vector3d c = sim::FlangePose(robot, q) * head.com_m;
      hand -= axis.dot((c - at).cross(head.mass_kg * g));
      EXPECT_NEAR(tau[j], hand, 1e-6 * std::max(1.0, std::abs(hand))) << joint.name;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// kin.torque: a head heavier than the arm is rated for, swung fast near full reach (the rail
// held by the programme, E word, so a1 turns the head through +-13 deg at 2.2 to 3 m), needs
// more torque than the wrist and a1 motors give on the fast line; slowly it does not.

const Eigen::Vector3d kNear(0, 400, 0), kFar(0, -400, 0);
const Eigen::Vector3d kSwingFrom(-600, -400, 0), kSwingTo(600, -400, 0);
constexpr double kRailOppositeMm = 2800.0;  // a1 opposite the table's middle (x 3.5 m)

std::string Swing(double feed) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "G21 G90\nG1 X%.1f Y%.1f Z0 A0 B0 C0 E%.1f F%.3f\nG1 X%.1f\nM30\n",
                kSwingFrom.x(), kSwingFrom.y(), kRailOppositeMm, feed, kSwingTo.x());
  return buf;
}

TEST(dynamics, TorqueFiresOnTheFastLineOfAHeavyHeadAndNotWhenSlow) {
  Loaded l = Load("circle_8in");
  l.scene->head.inertial->mass_kg = kHeavyHeadKg;
  const Outcome fast = Execute(l, Swing(kFastFeed), 5.0, false);
  const Outcome slow = Execute(l, Swing(kSlowFeed), 5.0, false);
  ASSERT_TRUE(fast.ok && slow.ok) << fast.diagnostics << slow.diagnostics;
  const RuleSummary* f = fast.Rule("kin.torque");
  const RuleSummary* s = slow.Rule("kin.torque");
  ASSERT_TRUE(f && s);
  std::printf("heavy head: worst torque %.1f %% fast, %.1f %% slow\n", Worst(f), Worst(s));
  ASSERT_GT(f->errors, 0);
  EXPECT_EQ(f->findings.front().line, 3);  // the swing; line 2 only places the tool
  std::printf("  first finding: %s\n", f->findings.front().message.c_str());
  EXPECT_EQ(s->errors, 0);
  // The head's own mass passes fast too.
  const Loaded own = Load("circle_8in");
  const Outcome rated = Execute(own, Swing(kFastFeed), 5.0, false);
  EXPECT_EQ(rated.Rule("kin.torque")->errors, 0) << Worst(rated.Rule("kin.torque"));
}

// kin.acceleration: the time law keeps every axis within its limit (the planner's promise,
// checked on the trace); a scene that allows only a quarter of it flags the fast line.
TEST(dynamics, AccelerationStaysWithinTheLimitAndFiresOnTheFastLineWhenTightened) {
  Loaded l = Load("circle_8in");
  const Outcome fast = Execute(l, Move(kNear, kFar, kFastFeed), 5.0, false);
  ASSERT_TRUE(fast.ok) << fast.diagnostics;
  const RuleSummary* a = fast.Rule("kin.acceleration");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->errors, 0);
  EXPECT_LE(Worst(a), 100.0 + 1e-6);
  EXPECT_GT(Worst(a), 25.0);  // the fast line runs the arm hard
  DiagnosticSink sink;
  l.scene->limits.Set(scene::LimitKey::kAccelerationMaxFraction, 0.25);
  const Outcome tight = Execute(l, Move(kNear, kFar, kFastFeed), 5.0, false);
  ASSERT_GT(tight.Rule("kin.acceleration")->errors, 0);
  EXPECT_EQ(tight.Rule("kin.acceleration")->findings.front().line, 3);
  const Outcome slow = Execute(l, Move(kNear, kFar, kSlowFeed), 5.0, false);
  EXPECT_EQ(slow.Rule("kin.acceleration")->errors, 0) << Worst(slow.Rule("kin.acceleration"));
  std::printf("acceleration: %.1f %% fast, %.1f %% slow\n", Worst(a),
              Worst(slow.Rule("kin.acceleration")));
}

// kin.payload against the load diagram by hand: the larger of mass / rated, the a5 moment
// (lever from the a5 axis) and the a6 moment (lever off the flange axis) over the rated ones.
TEST(dynamics, PayloadIsTheLoadDiagramByHand) {
  Loaded l = Load("circle_8in");
  const sim::PayloadRating rating = l.robot->payload_rating();
  ASSERT_GT(rating.mass_kg, 0.0);
  const double c4 = l.robot->opw().c4_m;
  const auto percent = [&](const scene::HeadInertial& h) {
    const double lz = h.com_m.z(), lxy = std::hypot(h.com_m.x(), h.com_m.y());
    const double a5 = std::hypot(c4 + lz, lxy) / std::hypot(c4 + rating.lz_m, rating.lxy_m);
    const double a6 = rating.lxy_m > 0 ? lxy / rating.lxy_m : 0.0;
    return 100.0 * h.mass_kg / rating.mass_kg * std::max({1.0, a5, a6});
  };
  const std::string text = Move(kNear, kFar, kSlowFeed);
  const Outcome own = Execute(l, text, 5.0, false);
  ASSERT_TRUE(own.ok) << own.diagnostics;
  EXPECT_EQ(own.Rule("kin.payload")->errors, 0);
  EXPECT_NEAR(Worst(own.Rule("kin.payload")), percent(*l.scene->head.inertial), 1e-9);
  // The rated mass with its centre of mass 0.3 m further out than rated: the a5 moment breaks.
  l.scene->head.inertial->mass_kg = rating.mass_kg;
  l.scene->head.inertial->com_m = Eigen::Vector3d(rating.lxy_m, 0.0, rating.lz_m + 0.3);
  const Outcome out = Execute(l, text, 5.0, false);
  const RuleSummary* p = out.Rule("kin.payload");
  ASSERT_GT(p->errors, 0);
  EXPECT_NEAR(p->findings.front().value, percent(*l.scene->head.inertial), 1e-9);
  EXPECT_EQ(p->findings.front().subject, "a5 moment");
  EXPECT_EQ(p->findings.front().line, 2);  // the first motion line
}

// dyn.tracking against the servo's closed form: on the rail move at cruise the servo feeds
// the velocity and the bias forward but not the joint's viscous damping, so it settles where
// kp e = damping v: a lag of damping v / kp along the rail (the arm stands still). And the
// rule fires on the moving line once its limit is below that lag.
TEST(dynamics, TrackingLagIsTheServoClosedFormAndFiresOnItsLine) {
  Loaded l = Load("circle_8in");
  const sim::CellSetup cell = sim::MakeCellSetup(*l.robot, *l.scene);
  DiagnosticSink sink;
  auto mj = sim::MujocoCell::Create(*l.scene, *l.robot, cell, sink);
  ASSERT_NE(mj, nullptr);
  const double v = 0.1;  // m/s: 6000 mm/min
  const double lag_mm =
      1000.0 * l.robot->dampings()[trace::kRailX] * v / mj->Servo(trace::kRailX).kp;
  const Outcome r = Execute(l, Move({-500, 0, 0}, {500, 0, 0}, 6000.0), 5.0, true);
  ASSERT_TRUE(r.ok) << r.diagnostics;
  int checked = 0;
  for (const auto& s : r.capture.samples) {
    // Mid-cruise: the ramps end at s = 0.0125 and 0.9875; the servo settles in ~0.05 s.
    if (s.source_line != 3 || s.line_fraction < 0.1 || s.line_fraction > 0.9) continue;
    ASSERT_TRUE(s.tracked);
    EXPECT_NEAR(s.tracking_error_mm, lag_mm, 0.02 * lag_mm) << s.line_fraction;
    ++checked;
  }
  EXPECT_GT(checked, 30);
  std::printf("rail lag at cruise: %.3e mm (closed form %.3e mm)\n", Worst(r.Rule("dyn.tracking")),
              lag_mm);
  l.scene->limits.Set(scene::LimitKey::kTrackingErrorMm, 0.5 * lag_mm);
  const Outcome tight = Execute(l, Move({-500, 0, 0}, {500, 0, 0}, 6000.0), 5.0, true);
  const RuleSummary* t = tight.Rule("dyn.tracking");
  ASSERT_NE(t, nullptr);
  ASSERT_GT(t->errors, 0);
  EXPECT_EQ(t->findings.front().line, 3);
}

// ---------------------------------------------------------------------------------------------
// The dynamic mode on the decoupled 8 in circle: the servos lag; at a stitch rate well above
// the head's the lag breaks the side-force limit, which kinematic mode cannot see.

TEST(dynamics, DynamicModeLagReachesTheNeedleRules) {
  Loaded l = Load("circle_8in");
  const Outcome normal = Execute(l, PlanCircle(l, planner::Mode::kDecoupled), 5.0, true);
  ASSERT_TRUE(normal.ok) << normal.diagnostics;
  const RuleSummary* tracking = normal.Rule("dyn.tracking");
  ASSERT_NE(tracking, nullptr);
  if (std::getenv("DBG")) {
    for (const auto& s : normal.capture.samples) {
      if (s.source_line < 40 || s.source_line > 46) continue;
      std::printf("L%d f=%.3f t=%.4f in=%d ev=%d lag=%.4f mm %.4f deg\n", s.source_line,
                  s.line_fraction, s.timed_s, s.needles_in, int(s.event), s.tracking_error_mm,
                  s.tracking_error_deg);
    }
  }
  EXPECT_GT(Worst(tracking), 0.0);
  EXPECT_GT(normal.dynamics.samples, 1000);
  std::printf("circle at %.0f/min: lag %.4f mm, side force %.4f mm (dynamic)\n",
              l.scene->head.stitch.stitch_rate_per_min, Worst(tracking),
              Worst(normal.Rule("needle.side_force")));
  // Raise the stitch rate (the planner's feed follows it) until the dynamic run breaks the
  // side-force limit; kinematic mode at that rate sees nothing.
  double rate = 0.0;
  std::string fast_text;
  for (double r : {450.0, 600.0, 900.0, 1200.0, 1800.0, 2400.0, 3600.0}) {
    l.scene->head.stitch.stitch_rate_per_min = r;
    fast_text = PlanCircle(l, planner::Mode::kDecoupled);
    const Outcome d = Execute(l, fast_text, 5.0, true);
    ASSERT_TRUE(d.ok);
    std::printf("circle at %.0f/min: side force %.4f mm dynamic (lag %.4f mm)\n", r,
                Worst(d.Rule("needle.side_force")), Worst(d.Rule("dyn.tracking")));
    if (d.Rule("needle.side_force")->errors > 0) {
      rate = r;
      break;
    }
  }
  ASSERT_GT(rate, 0.0) << "no stitch rate up to 3600/min broke the side-force limit";
  const Outcome kinematic = Execute(l, fast_text, 5.0, false);
  ASSERT_TRUE(kinematic.ok);
  const RuleSummary* k = kinematic.Rule("needle.side_force");
  std::printf("circle at %.0f/min: side force %.4f mm kinematic\n", rate, Worst(k));
  EXPECT_EQ(k->errors, 0);
  EXPECT_EQ(kinematic.Rule("dyn.tracking"), nullptr);  // not a dynamic run
}

}  // namespace
}  // namespace stitchsim::verify
