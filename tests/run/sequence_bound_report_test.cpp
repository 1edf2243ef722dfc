// The sequence run's lower bound, optimum and gap (issue 28, Done-when 3): on a set small
// enough for the exact solver, bound <= optimum <= cost and the JSON's gap is (cost - optimum)
// / optimum by hand; on a set over 16 courses the gap is taken to the bound; each set's cost is
// the problem it was laid in (from where the previous set ended), which the run's independent
// move-by-move costs confirm; a given order gets its costs, bound and gap too.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sequence_fixture.h"
#include "stitchsim/run/sequence_report.h"

namespace stitchsim::run {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class SequenceBoundTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::SequenceTestDir() / "bound");
    fs::create_directories(*dir_);
    test::PlanSeqPlate({"pad_0_left", "pad_0_right", "pad_0_mid"}, *dir_ / "pads.nc");
    test::PlanSeqPlate({"base_0", "pad_0_mid"}, *dir_ / "base_pad.nc");
    // 2 plies of 12 courses side by side: one set of 24 courses, too many for the exact solver.
    const fs::path script = fs::path(STITCHSIM_SOURCE_DIR) / "bench" / "make_sequence_bench.py";
    const std::string command = "python3 '" + script.string() + "' '" + dir_->string() +
                                "' --plies 2 --courses-per-ply 12 --layout beside > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path dir_path() { return *dir_; }

  static fs::path* dir_;
};
fs::path* SequenceBoundTest::dir_ = nullptr;

json ReportOf(const SequenceRun& r, const SequenceInputs& in) {
  std::ostringstream s;
  WriteSequenceJson(r.outcome, in.program, s);
  return json::parse(s.str());
}

double Tol(double x) { return 1e-9 * (1.0 + std::abs(x)); }

// Every set: its cost in the chosen measure is the run's own sum of that set's moves (a second
// route: MoveCosts over the whole order), and bound <= optimum (when known) <= cost.
void ExpectSetsConsistent(const SequenceOutcome& out) {
  const auto mi = static_cast<std::size_t>(out.measure);
  double bounds = 0.0;
  for (std::size_t k = 0; k < out.sets.size(); ++k) {
    const SetOutcome& s = out.sets[k];
    ASSERT_TRUE(s.bound.has_value()) << "set " << k;
    ASSERT_TRUE(s.gap.has_value()) << "set " << k;
    EXPECT_NEAR(s.cost, s.offpart_after[mi], Tol(s.cost)) << "set " << k;
    EXPECT_LE(*s.bound, s.cost + Tol(s.cost)) << "set " << k;
    if (s.optimum) {
      EXPECT_LE(*s.bound, *s.optimum + Tol(*s.optimum)) << "set " << k;
      EXPECT_LE(*s.optimum, s.cost + Tol(s.cost)) << "set " << k;
    }
    bounds += *s.bound;
  }
  EXPECT_GT(bounds, 0.0);
}

// Options for `programme` on seq_plate, without a time limit (deterministic).
SequenceOptions Untimed(const fs::path& programme) {
  SequenceOptions o = test::SeqPlateOptions(programme);
  o.time_limit_s = 0;
  return o;
}

// Loads and runs `o`: the run succeeds with `sets` sets, each consistent.
struct Ran {
  SequenceInputs in;
  SequenceRun run;
};
Ran RunChecked(const SequenceOptions& o, std::size_t sets) {
  Ran x{test::LoadOrFail(o), {}};
  x.run = RunSequence(x.in, o, nullptr);
  EXPECT_EQ(x.run.status, SequenceStatus::kOk);
  EXPECT_EQ(x.run.outcome.sets.size(), sets);
  if (x.run.outcome.sets.size() == sets) ExpectSetsConsistent(x.run.outcome);
  return x;
}

TEST_F(SequenceBoundTest, SmallSetBoundBelowOptimumBelowCostAndTheGapByHand) {
  for (const bool bidirectional : {false, true}) {
    SequenceOptions o = Untimed(dir_path() / "pads.nc");
    o.bidirectional = bidirectional;
    const Ran x = RunChecked(o, 1);
    ASSERT_FALSE(HasFailure());
    const SequenceInputs& in = x.in;
    const SequenceRun& r = x.run;
    ASSERT_LE(r.outcome.sets[0].courses.size(), 12u);
    const json set = ReportOf(r, in).at("sets").at(0);
    ASSERT_TRUE(set.at("optimum").is_number()) << "exact by default up to 12 courses";
    const double cost = set.at("cost").get<double>(), optimum = set.at("optimum").get<double>();
    const double bound = set.at("bound").get<double>();
    EXPECT_EQ(set.at("bound_method"), "held-karp");
    EXPECT_LE(bound, optimum + Tol(optimum));
    EXPECT_LE(optimum, cost + Tol(cost));
    const double gap = (cost - optimum) / optimum;
    EXPECT_NEAR(set.at("gap").get<double>(), std::abs(gap) < 1e-9 ? 0.0 : gap, 1e-12);
    EXPECT_EQ(set.at("status"), planner::ToString(r.outcome.sets[0].status));
    EXPECT_EQ(set.at("original_cost").get<double>(), r.outcome.sets[0].original_cost);
    EXPECT_EQ(set.at("kept_original").get<bool>(), r.outcome.sets[0].kept_original);
    // The safeguard: never worse than the programme's order.
    EXPECT_LE(cost, set.at("original_cost").get<double>() + Tol(cost));
  }
}

TEST_F(SequenceBoundTest, LargerSetGapToTheBound) {
  const fs::path nc = dir_path() / "seq_bench_beside_2x12.nc";
  SequenceOptions o = Untimed(nc);
  o.scene_file = (dir_path() / "seq_bench_beside_2x12.yaml").string();
  o.measure_gap = true;  // still too large for the exact solver
  const Ran x = RunChecked(o, 1);
  ASSERT_FALSE(HasFailure());
  ASSERT_GT(x.run.outcome.sets[0].courses.size(), 16u);
  const json report = ReportOf(x.run, x.in);
  const json set = report.at("sets").at(0);
  EXPECT_TRUE(set.at("optimum").is_null());
  const double cost = set.at("cost").get<double>(), bound = set.at("bound").get<double>();
  EXPECT_EQ(set.at("bound_method"), "held-karp");
  EXPECT_NEAR(set.at("gap").get<double>(), (cost - bound) / bound, 1e-12);
  EXPECT_GE(bound, 0.9 * cost);  // not weak
  EXPECT_EQ(report.at("totals").at("bound").get<double>(), bound);
}

// Two sets: the second's problem starts where the first ended as laid; its cost (and so the
// bound's problem) matches the run's own move costs, and a given order (the report's, read
// back) gets the same costs, bound and gap.
TEST_F(SequenceBoundTest, EachSetFromWhereThePreviousEndedAndGivenOrdersToo) {
  SequenceOptions o = Untimed(dir_path() / "base_pad.nc");
  o.return_home = true;
  const Ran x = RunChecked(o, 2);
  ASSERT_FALSE(HasFailure());
  const SequenceRun& r = x.run;
  const json report = ReportOf(r, x.in);
  EXPECT_NEAR(report.at("totals").at("bound").get<double>(),
              *r.outcome.sets[0].bound + *r.outcome.sets[1].bound, 1e-9);

  const fs::path file = dir_path() / "solved.json";
  std::ofstream(file) << report.dump();
  SequenceOptions given = o;
  given.order_file = file.string();
  const Ran y = RunChecked(given, 2);
  ASSERT_FALSE(HasFailure());
  const SequenceRun& laid = y.run;
  for (std::size_t k = 0; k < 2; ++k) {
    const SetOutcome &a = r.outcome.sets[k], &b = laid.outcome.sets[k];
    EXPECT_EQ(b.status, planner::SolveStatus::kGiven);
    EXPECT_EQ(b.cost, a.cost);
    EXPECT_EQ(b.original_cost, a.original_cost);
    EXPECT_EQ(b.bound, a.bound);
    EXPECT_EQ(b.gap, a.gap);
  }
}

}  // namespace
}  // namespace stitchsim::run
