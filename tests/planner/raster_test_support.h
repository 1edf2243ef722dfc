#pragma once
// Shared by the raster planner tests: plan a scene to text, and execute + verify a programme
// in-process with the collision world as `stitchsim verify` does.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "stitchsim/planner/raster_planner.h"
#include "stitchsim/sim/collision.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::planner::testing {

/// The programme of `o` on `s` (failing the test on any diagnostic); its summary if asked.
inline std::string Plan(const scene::Scene& s, const RasterOptions& o,
                        RasterSummary* summary = nullptr) {
  DiagnosticSink sink;
  std::ostringstream out;
  const auto sum = WriteRasterProgram(s, o, program::Dialect::Default(), out, sink);
  EXPECT_TRUE(sum.has_value());
  for (const auto& d : sink.Diagnostics()) ADD_FAILURE() << FormatDiagnostic(d);
  if (sum && summary) *summary = *sum;
  return out.str();
}

/// Executes and verifies `text` on `s`, with the collision world when `collision` is set: the
/// head must clear the stringers and intercostals beside the rows, while turning at a bay edge
/// and while flying a jump.
inline verify::Report VerifyText(const scene::Scene& s, const std::string& text, double pitch_mm,
                                 bool collision = true) {
  DiagnosticSink sink;
  auto robot = sim::LoadRobotModel(s.cell_urdf, sink);
  EXPECT_TRUE(robot.has_value());
  const sim::CellSetup cell = sim::MakeCellSetup(*robot, s);
  const process::ProcessModel model = process::MakeProcessModel(s, pitch_mm);
  std::unique_ptr<sim::CollisionWorld> world;
  if (collision) {
    world = sim::CollisionWorld::Create(s, *robot, sink);
    EXPECT_NE(world, nullptr);
  }
  const trace::CellDescription cell_description = sim::DescribeCell(*robot, world.get());
  verify::RuleContext ctx{&s, &cell_description, &model};
  verify::Verifier verifier(ctx, false);
  std::istringstream in(text);
  sim::ExecuteOptions options = sim::ExecuteOptionsFor(s);
  options.collision = world.get();
  sim::ExecuteProgram(cell, model, program::Dialect::Default(), in, "raster.nc", options, sink,
                      verifier);
  EXPECT_EQ(sink.ErrorCount(), 0u);
  verify::Report report;
  verifier.Finish(report);
  return report;
}

/// The report's errors, one line each (cut after 2000 characters).
inline std::string Errors(const verify::Report& r) {
  std::string s;
  for (const auto& rule : r.rules) {
    for (const auto& f : rule.findings) {
      if (f.severity != verify::FindingSeverity::kError) continue;
      s += rule.id + " line " + std::to_string(f.line) + ": " + f.message + "\n";
      if (s.size() > 2000) return s;
    }
  }
  return s;
}

/// The lines of `text`, without their line ends.
inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// `lines` as one text, each ended by a line feed.
inline std::string Join(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

/// The rule `id` of the report, or nullptr.
inline const verify::RuleSummary* RuleOf(const verify::Report& r, const std::string& id) {
  for (const auto& rule : r.rules) {
    if (rule.id == id) return &rule;
  }
  return nullptr;
}

}  // namespace stitchsim::planner::testing
