// Dominance at the run level (issue 28, Done-when 2): on every case of seed 004
// (bench/seed004_cases.txt: seq_plate and seq_cylinder plies planned by the ply planner),
// `--bidirectional` never ends dearer than forward-only, in the tool-path and the axes
// measures. The totals compared are the sum of the sets' costs in the measure minimised, each
// set from where the previous one ended (and home at the end): the run's own objective.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "sequence_fixture.h"

namespace stitchsim::run {
namespace {

namespace fs = std::filesystem;

struct Seed004Case {
  std::string name;
  fs::path scene;
  std::vector<std::string> plies;
};

/// bench/seed004_cases.txt: "name scene ply,ply,... [style]" a line, '#' comments.
std::vector<Seed004Case> ReadSeed004Cases() {
  const fs::path root = STITCHSIM_SOURCE_DIR;
  std::ifstream in(root / "bench" / "seed004_cases.txt");
  std::vector<Seed004Case> cases;
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    Seed004Case c;
    std::string scene, plies;
    if (!(words >> c.name >> scene >> plies)) continue;
    c.scene = root / scene;
    std::istringstream list(plies);
    for (std::string ply; std::getline(list, ply, ',');) c.plies.push_back(ply);
    cases.push_back(std::move(c));
  }
  return cases;
}

double TotalCost(const SequenceOutcome& out) {
  double total = 0.0;
  for (const SetOutcome& set : out.sets) total += set.cost;
  return total;
}

TEST(SequenceDominanceRun, BidirectionalNeverWorseOnSeed004Cases) {
  const std::vector<Seed004Case> cases = ReadSeed004Cases();
  ASSERT_EQ(cases.size(), 7u);
  const fs::path dir = test::SequenceTestDir();
  for (const Seed004Case& c : cases) {
    const fs::path programme = dir / (c.name + ".nc");
    test::PlanSeqPlate(c.plies, programme, c.scene);
    for (const Measure measure : {Measure::kTool, Measure::kAxes}) {
      SequenceOptions o = test::SeqPlateOptions(programme, c.scene);
      o.measure = measure;
      o.return_home = true;
      // No time limit (a cut search may end above the forward-only answer); few rounds.
      o.time_limit_s = 0.0;
      o.starts = 2;
      o.stagnation = 300;
      const SequenceInputs in = test::LoadOrFail(o);
      const SequenceRun forward = RunSequence(in, o, nullptr);
      o.bidirectional = true;
      const SequenceRun both = RunSequence(in, o, nullptr);
      ASSERT_EQ(forward.status, SequenceStatus::kOk) << c.name;
      ASSERT_EQ(both.status, SequenceStatus::kOk) << c.name;
      const double f = TotalCost(forward.outcome), b = TotalCost(both.outcome);
      EXPECT_LE(b, f * (1 + 1e-9)) << c.name << (measure == Measure::kTool ? " tool" : " axes")
                                   << ": bidirectional " << b << " against forward-only " << f;
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stitchsim::run
