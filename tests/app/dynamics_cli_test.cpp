// `stitchsim verify` on the MuJoCo model (S10), as a separate process: the timed cycle time
// beside the simple one in every report, `--dynamics` with its figures, a dialect's blending.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

const fs::path kSource = STITCHSIM_SOURCE_DIR;

// The 8 in circle (decoupled unless said), planned once per test.
fs::path PlanCircle(const std::string& tag, const std::string& mode = "decoupled") {
  const fs::path nc = ScratchDir() / (tag + ".nc");
  const auto plan = RunCli("plan stitch --scene " + (kSource / "scenes/circle_8in.yaml").string() +
                               " --path circle --mode " + mode + " -o " + nc.string(),
                           tag + "_plan");
  EXPECT_EQ(plan.exit_code, 0) << plan.err;
  return nc;
}

nlohmann::json Rule(const nlohmann::json& report, const std::string& id) {
  for (const auto& r : report["rules"]) {
    if (r["id"] == id) return r;
  }
  return nullptr;
}

TEST(VerifyTimed, ReportsGiveBothCycleTimesAndTheDynamicsRules) {
  const fs::path nc = PlanCircle("timed");
  const fs::path json = ScratchDir() / "timed.json";
  const auto run =
      RunCli("verify " + nc.string() + " --scene " + (kSource / "scenes/circle_8in.yaml").string() +
                 " --report " + json.string(),
             "timed_verify");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const auto report = nlohmann::json::parse(ReadText(json));
  const double simple = report["cycle_time_s"], timed = report["cycle_time_timed_s"];
  EXPECT_GT(timed, simple);  // ramps only add time
  // Every decoupled stitch starts and stops (a rotation with its settle between): about
  // 0.45 s a stitch on the ramps against 0.2 s at the stitch rate.
  EXPECT_LT(timed, 2.0 * simple);
  EXPECT_NE(run.out.find("with acceleration"), std::string::npos) << run.out;
  for (const char* id : {"kin.acceleration", "kin.torque", "kin.payload"}) {
    const auto r = Rule(report, id);
    ASSERT_FALSE(r.is_null()) << id;
    EXPECT_EQ(r["errors"], 0) << id;
  }
  EXPECT_TRUE(Rule(report, "dyn.tracking").is_null());  // only in a dynamic run
  EXPECT_TRUE(report["skipped_rules"].empty());
}

TEST(VerifyTimed, DynamicsReportsTrackingAndItsRealTimeFactor) {
  const fs::path nc = PlanCircle("dyn");
  const fs::path json = ScratchDir() / "dyn.json";
  const auto run =
      RunCli("verify " + nc.string() + " --scene " + (kSource / "scenes/circle_8in.yaml").string() +
                 " --dynamics" + " --report " + json.string(),
             "dyn_verify");
  ASSERT_LE(run.exit_code, 1) << run.out << run.err;
  const auto report = nlohmann::json::parse(ReadText(json));
  const auto tracking = Rule(report, "dyn.tracking");
  ASSERT_FALSE(tracking.is_null());
  EXPECT_GT(tracking["checked"].get<long>(), 1000);
  EXPECT_GT(tracking["worst"]["value"].get<double>(), 0.0);
  double simulated = 0, wall = 0, factor = 0;
  const auto at = run.err.find("dynamics: ");
  ASSERT_NE(at, std::string::npos) << run.err;
  ASSERT_EQ(std::sscanf(run.err.c_str() + at, "dynamics: %lf s of motion simulated in %lf s (%lfx",
                        &simulated, &wall, &factor),
            3)
      << run.err;
  EXPECT_GT(simulated, 0.9 * report["cycle_time_timed_s"].get<double>());
  std::printf("dynamics: %.2f s simulated in %.2f s: %.1fx real time\n", simulated, wall, factor);
}

// The dialect states the blending: an exact stop at every line end only adds time.
TEST(VerifyTimed, ExactStopDialectTakesLonger) {
  const fs::path nc = PlanCircle("stop", "coupled");  // many lines in a row to blend
  const fs::path dialect = ScratchDir() / "exact_stop.yaml";
  {
    std::ofstream d(dialect);
    d << "trajectory:\n  blending: exact_stop\n";
  }
  const fs::path a = ScratchDir() / "blend.json", b = ScratchDir() / "stop.json";
  const std::string scene = " --scene " + (kSource / "scenes/circle_8in.yaml").string();
  ASSERT_EQ(RunCli("verify " + nc.string() + scene + " --report " + a.string(), "blend").exit_code,
            1);  // the coupled circle breaks the side-force limit, as before
  ASSERT_EQ(RunCli("verify " + nc.string() + scene + " --dialect " + dialect.string() +
                       " --report " + b.string(),
                   "stop")
                .exit_code,
            1);
  const double blended = nlohmann::json::parse(ReadText(a))["cycle_time_timed_s"];
  const double stopped = nlohmann::json::parse(ReadText(b))["cycle_time_timed_s"];
  EXPECT_GT(stopped, blended);
  // A bad blending mode is bad input with its line.
  {
    std::ofstream d(dialect);
    d << "trajectory:\n  blending: sometimes\n";
  }
  const auto bad =
      RunCli("verify " + nc.string() + scene + " --dialect " + dialect.string(), "bad_blend");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("exact_stop.yaml:2"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace stitchsim::app
