// Sequencing's course ends and costs (run/sequence_costs.h) on seq_plate's pad-ups, planned by
// the ply planner: a course end's tool point is the programme's lay-up point (a reversed course
// swaps them), its axes go back through FK to that point, and the costs of a small order are
// summed here by hand.
#include "stitchsim/run/sequence_costs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sequence_fixture.h"
#include "stitchsim/common/units.h"
#include "stitchsim/run/sequence_timed.h"

namespace stitchsim::run {
namespace {

class SequenceCosts : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto file = test::SequenceTestDir() / "costs_pads.nc";
    test::PlanSeqPlate({"pad_0_left", "pad_0_right", "pad_0_mid"}, file);
    inputs_ = new SequenceInputs(test::LoadOrFail(test::SeqPlateOptions(file)));
    std::filesystem::remove(file);
    cell_ = new sim::CellSetup(sim::MakeCellSetup(*inputs_->loaded.robot, *inputs_->loaded.scene));
    ends_ = new CourseEnds(SolveCourseEnds(*cell_, inputs_->program, inputs_->home,
                                           inputs_->loaded.scene->head.sequence.retract_mm));
  }
  static void TearDownTestSuite() {
    delete ends_;
    delete cell_;
    delete inputs_;
  }
  static const program::AfpProgram& Program() { return inputs_->program; }

  static SequenceInputs* inputs_;
  static sim::CellSetup* cell_;
  static CourseEnds* ends_;
};
SequenceInputs* SequenceCosts::inputs_ = nullptr;
sim::CellSetup* SequenceCosts::cell_ = nullptr;
CourseEnds* SequenceCosts::ends_ = nullptr;

// Axes back to joints: rail mm -> m, degrees -> radians (the inverse of AxesOf).
trace::JointVector JointsOf(const std::vector<double>& axes) {
  trace::JointVector q;
  for (int j = 0; j < trace::kNumJoints; ++j)
    q[j] = j == trace::kRailX ? axes[static_cast<std::size_t>(j)] / 1000.0
                              : axes[static_cast<std::size_t>(j)] * kDeg;
  return q;
}

TEST_F(SequenceCosts, CourseEndsAreTheLayupPointsAndReversedSwapsThem) {
  const auto& courses = Program().courses;
  ASSERT_GE(courses.size(), 3u);
  ASSERT_EQ(ends_->ends.size(), 4 * courses.size());
  EXPECT_TRUE(ends_->home.ok) << ends_->home.reason;
  for (std::size_t c = 0; c < courses.size(); ++c) {
    const Eigen::Vector3d first = courses[c].stations.front().pose.translation();
    const Eigen::Vector3d last = courses[c].stations.back().pose.translation();
    const EndPoint* e = &ends_->ends[4 * c];
    EXPECT_TRUE(e[0].ok && e[1].ok && e[2].ok && e[3].ok) << "course " << c;
    EXPECT_TRUE(ends_->reversible[c]);
    EXPECT_LT((e[0].tool - first).norm(), 1e-9) << "course " << c;
    EXPECT_LT((e[1].tool - last).norm(), 1e-9);
    EXPECT_LT((e[2].tool - last).norm(), 1e-9);  // backwards: starts at the last point
    EXPECT_LT((e[3].tool - first).norm(), 1e-9);
    // The tool measure's point is the tool point; the axes' point goes back through FK to it.
    const std::vector<double> tool = PointOf(e[0], Measure::kTool);
    EXPECT_EQ(tool, (std::vector<double>{first.x(), first.y(), first.z()}));
    for (int k = 0; k < 4; ++k) {
      ASSERT_EQ(e[k].axes.size(), static_cast<std::size_t>(trace::kNumJoints));
      const Eigen::Isometry3d fk = sim::ToolPoseInPart(*cell_, JointsOf(e[k].axes));
      EXPECT_LT((fk.translation() - e[k].tool).norm(), 1e-3) << "course " << c << " end " << k;
    }
  }
}

TEST_F(SequenceCosts, AxesOfIsMillimetresAndDegrees) {
  trace::JointVector q = trace::JointVector::Zero();
  q[trace::kRailX] = 1.25;  // m
  q[1] = kPi / 2;
  q[7] = -kPi;
  const std::vector<double> axes = AxesOf(q);
  ASSERT_EQ(axes.size(), static_cast<std::size_t>(trace::kNumJoints));
  EXPECT_DOUBLE_EQ(axes[trace::kRailX], 1250.0);
  EXPECT_DOUBLE_EQ(axes[1], 90.0);
  EXPECT_DOUBLE_EQ(axes[7], -180.0);
  EXPECT_EQ(axes[2], 0.0);
}

// Two courses in a tiny order (course 1 backwards, then course 0): every move's cost in every
// measure, summed here by hand from the points.
TEST_F(SequenceCosts, MoveCostsOfATinyOrderByHand) {
  const std::vector<program::CourseVisit> order{{1, true}, {0, false}};
  const EndPoint& home = ends_->home;
  const EndPoint& in1 = ends_->ends[4 * 1 + 2];
  const EndPoint& out1 = ends_->ends[4 * 1 + 3];
  const EndPoint& in0 = ends_->ends[0];
  const EndPoint& out0 = ends_->ends[1];
  const std::vector<double> w{1.0, 0.5, 0.5, 0.5, 0.25, 0.25, 0.25, 2.0};
  // Tool: Euclidean distances.
  const MeasureSpec tool = SpecOf(Measure::kTool, *inputs_->loaded.robot, w);
  const auto t = MoveCosts(*ends_, order, tool, Measure::kTool, true);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t[0], (in1.tool - home.tool).norm(), 1e-9);
  EXPECT_NEAR(t[1], (in0.tool - out1.tool).norm(), 1e-9);
  EXPECT_NEAR(t[2], (home.tool - out0.tool).norm(), 1e-9);
  // Axes: weighted L1 of the axes' differences.
  const MeasureSpec axes = SpecOf(Measure::kAxes, *inputs_->loaded.robot, w);
  const auto a = MoveCosts(*ends_, order, axes, Measure::kAxes, false);
  ASSERT_EQ(a.size(), 2u);
  double l1 = 0.0;
  for (std::size_t j = 0; j < w.size(); ++j) l1 += w[j] * std::abs(in0.axes[j] - out1.axes[j]);
  EXPECT_NEAR(a[1], l1, 1e-9 * (1 + l1));
  // Time: the slowest axis, each at its top speed (mm or degrees per second).
  const MeasureSpec time = SpecOf(Measure::kTime, *inputs_->loaded.robot, w);
  EXPECT_EQ(time.norm, planner::CostNorm::kMax);
  const auto s = MoveCosts(*ends_, order, time, Measure::kTime, false);
  double slowest = 0.0;
  for (int j = 0; j < trace::kNumJoints; ++j) {
    const double v = inputs_->loaded.robot->joint(j).max_velocity;
    const double per_s = j == trace::kRailX ? v * 1000.0 : v * kRadToDeg;
    const double d =
        std::abs(in1.axes[static_cast<std::size_t>(j)] - home.axes[static_cast<std::size_t>(j)]);
    if (per_s > 0.0) slowest = std::max(slowest, d / per_s);
  }
  EXPECT_NEAR(s[0], slowest, 1e-9 * (1 + slowest));
  // The set problem of the same order prices it the same (the planner's PathCost).
  const auto p = SetProblem(*ends_, {0, 1}, tool, Measure::kTool, true, home, &home);
  const double path = planner::PathCost(p, {{1, true}, {0, false}});
  EXPECT_NEAR(path, t[0] + t[1] + t[2], 1e-9);
}

// The lay-up's tool path and time from the stations, by hand; the axes' travel is positive and
// the same whatever the order (it does not depend on one).
TEST_F(SequenceCosts, LayupCostsByHand) {
  const MeasureSpec axes = SpecOf(Measure::kAxes, *inputs_->loaded.robot, inputs_->axis_weights);
  const TimedModel timed =
      TimedModelOf(*inputs_->loaded.robot, *inputs_->loaded.scene, program::Dialect::Default());
  const Costs c = LayupCosts(*cell_, Program(), axes, timed);
  double tool = 0.0, time = 0.0;
  for (const auto& course : Program().courses) {
    for (std::size_t i = 1; i < course.stations.size(); ++i) {
      const double len =
          (course.stations[i].pose.translation() - course.stations[i - 1].pose.translation())
              .norm();
      tool += len;
      const double feed = course.stations[i - 1].feed_mm_per_min;
      if (feed > 0.0) time += len / feed * 60.0;
    }
  }
  EXPECT_NEAR(c[2], tool, 1e-6 * tool);
  EXPECT_NEAR(c[1], time, 1e-9 * (1 + time));
  EXPECT_GT(time, 0.0);
  EXPECT_GT(c[0], 0.0);
}

}  // namespace
}  // namespace stitchsim::run
