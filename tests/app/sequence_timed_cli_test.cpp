// `stitchsim sequence --cost timed` end to end (issue 28): the panel's two plies ordered by the
// off-part moves' time through the controller's time law, laid bidirectionally and back home,
// verify clean; the report carries the timed measure before and after beside the others; and
// the time it says the new order saves is the time `verify` (which times every line of both
// programmes on the same law, via points, blending and all) finds saved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "app_test_support.h"

namespace stitchsim::app {
namespace {

namespace fs = std::filesystem;

testing::CliRun TimedCli(const std::string& args) { return testing::RunCli(args, "seqt"); }

// verify's cycle time on the time law (s), or NaN when it does not pass.
double VerifiedTimedCycle(const fs::path& nc, const fs::path& scene) {
  const fs::path rep = nc.string() + ".verify.json";
  const testing::CliRun v = TimedCli("verify " + nc.string() + " --scene " + scene.string() +
                                     " --report " + rep.string());
  EXPECT_EQ(v.exit_code, 0) << nc << "\n" << v.out << v.err;
  if (v.exit_code != 0) return std::nan("");
  return nlohmann::json::parse(testing::ReadText(rep)).at("cycle_time_timed_s").get<double>();
}

TEST(SequenceTimed, PanelPliesOrderedByTheTimeLawVerifyCleanAndSaveWhatVerifyFinds) {
  const fs::path scene = fs::path(STITCHSIM_SOURCE_DIR) / "scenes" / "afp_panel.yaml";
  const fs::path dir = testing::ScratchDir();
  const fs::path planned = dir / "timed_panel.nc";
  const testing::CliRun plan = TimedCli("plan ply --scene " + scene.string() +
                                        " --ply skin_0 --ply skin_45 -o " + planned.string());
  ASSERT_EQ(plan.exit_code, 0) << plan.out << plan.err;
  const std::string common = planned.string() + " --scene " + scene.string() + " --return-home";
  const fs::path out = dir / "timed_panel_seq.nc", rep = dir / "timed_panel_seq.json";
  const testing::CliRun r = TimedCli("sequence " + common + " --cost timed --bidirectional -o " +
                                     out.string() + " --report " + rep.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("cost timed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  timed off-part"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(testing::ReadText(rep));
  EXPECT_EQ(j.at("cost"), "timed");
  const auto& t = j.at("totals");
  const double before = t.at("offpart_before").at("timed_s").get<double>();
  const double after = t.at("offpart_after").at("timed_s").get<double>();
  const double layup = t.at("layup").at("timed_s").get<double>();
  EXPECT_LT(after, before);
  EXPECT_GT(layup, 0.0);
  EXPECT_NEAR(t.at("total_after").at("timed_s").get<double>(), after + layup, 1e-9 * layup);
  double sets = 0.0;
  for (const auto& s : j.at("sets")) sets += s.at("cost").get<double>();
  EXPECT_NEAR(sets, after, 1e-9 * after);  // the solver's table prices what the report does

  // The programme's own order written with the same kind of off-part moves (--order), so
  // that verify's times of the two programmes differ by the order alone.
  nlohmann::json order = j.at("order");
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    return std::make_pair(a.at("ply").template get<int>(), a.at("course").template get<int>()) <
           std::make_pair(b.at("ply").template get<int>(), b.at("course").template get<int>());
  });
  for (auto& v : order) v["reversed"] = false;
  const fs::path given = dir / "timed_panel_given.json", as_written = dir / "timed_panel_orig.nc";
  std::ofstream(given) << nlohmann::json{{"order", order}}.dump();
  ASSERT_EQ(
      TimedCli("sequence " + common + " --order " + given.string() + " -o " + as_written.string())
          .exit_code,
      0);
  const double verified_saving =
      VerifiedTimedCycle(as_written, scene) - VerifiedTimedCycle(out, scene);
  // Measured: sequence says 1.068 s, verify finds 1.048 s (the move's via points and the
  // blending into the lay-ups, which the measure leaves out, cancel almost entirely).
  EXPECT_GT(verified_saving, 0.0);
  EXPECT_NEAR(before - after, verified_saving, 0.1 * verified_saving);
}

}  // namespace
}  // namespace stitchsim::app
