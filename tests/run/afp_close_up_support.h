#pragma once
// Shared by the AFP close-up tests: scenes/afp_panel.yaml's ply skin_0 planned, its programme
// text edited course by course (a planted fault of known size), verified keeping the laid
// material (as verify --snapshots), and a rule's close-up planned and shot at 320 x 240.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>

#include "run_test_support.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/render/scene_model.h"
#include "stitchsim/run/close_up.h"
#include "stitchsim/run/verify_run.h"

namespace stitchsim::run::testing {

/// skin_0 of scenes/afp_panel.yaml as the ply planner writes it (3 courses along x; course 2
/// at y = 0, course 3 lays tows 12-16 only).
inline std::string PanelSkin0Text() {
  LoadedScene ls = Bundled("afp_panel");
  if (!ls.scene) return "";
  DiagnosticSink sink;
  const auto plan = planner::PlanPly(*ls.scene, *ls.scene->FindPly("skin_0"), {}, sink);
  EXPECT_TRUE(plan) << AllDiagnostics(sink);
  if (!plan) return "";
  std::ostringstream text;
  planner::WritePlyProgram(*plan, *ls.scene, program::Dialect::Default(), text);
  return text.str();
}

/// `text` with every G1 line of course `course` (from its M71 P<course> to the next M71 or
/// M72) handed to `edit(number, xyz)` (1-based line number, the tool point X Y Z, mm, which it
/// may change); the lines `edit` returns ("" none) follow that line.
inline std::string EditCourse(const std::string& text, int course,
                              const std::function<std::string(int, Eigen::Vector3d&)>& edit) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string l;
  bool inside = false;
  int number = 0;
  while (std::getline(in, l)) {
    ++number;
    if (l.rfind("M71 P", 0) == 0) {
      inside = std::stoi(l.substr(5)) == course;
    } else if (l.rfind("M72", 0) == 0) {
      inside = false;
    }
    std::string after;
    if (inside && l.rfind("G1 ", 0) == 0) {
      std::istringstream words(l);
      std::vector<std::string> w;
      for (std::string x; words >> x;) w.push_back(x);
      Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
      for (const std::string& x : w) {
        if (x[0] >= 'X' && x[0] <= 'Z') xyz[x[0] - 'X'] = std::stod(x.substr(1));
      }
      after = edit(number, xyz);
      l.clear();
      for (std::string& x : w) {
        if (x[0] >= 'X' && x[0] <= 'Z') {
          char buf[40];
          std::snprintf(buf, sizeof(buf), "%c%.6f", x[0], xyz[x[0] - 'X']);
          x = buf;
        }
        l += (l.empty() ? "" : " ") + x;
      }
    }
    out << l << "\n" << after;
  }
  return out.str();
}

/// `text` written to `dir` as `name` and verified on `scene` (default scenes/afp_panel.yaml)
/// keeping the laid material; nullptr (and a test failure) when the run does not finish.
inline std::unique_ptr<VerifyRun> VerifyPanelText(const std::string& text, const ScratchDir& dir,
                                                  const std::string& name,
                                                  std::filesystem::path scene = {}) {
  if (scene.empty()) scene = SourceDir() / "scenes" / "afp_panel.yaml";
  DiagnosticSink load;
  std::optional<LoadedScene> loaded = LoadScene(scene, scene::LoadOptions{}, load);
  EXPECT_TRUE(loaded && load.Diagnostics().empty()) << AllDiagnostics(load);
  if (!loaded) return nullptr;
  LoadedScene ls = std::move(*loaded);
  const std::string program = dir.File(name);
  std::ofstream(program) << text;
  VerifyRunOptions o;
  o.program = program;
  o.scene = scene.string();
  o.keep_stitch_marks = true;
  DiagnosticSink sink;
  auto run = std::make_unique<VerifyRun>(
      RunVerification(o, std::move(ls), program::Dialect::Default(), nullptr, sink));
  EXPECT_EQ(run->status, RunStatus::kOk) << AllDiagnostics(sink);
  return run->status == RunStatus::kOk ? std::move(run) : nullptr;
}

/// The rule `id` of the run's verifier (nullptr: none).
inline const verify::Rule* RuleOf(const VerifyRun& run, const std::string& id) {
  for (const auto& r : run.verifier->Rules()) {
    if (r->Summary().id == id) return r.get();
  }
  return nullptr;
}

/// The points rule `id` draws under `label` (Rule::Drawings), part frame, mm.
inline std::vector<Eigen::Vector3d> DrawnBy(const VerifyRun& run, const std::string& id,
                                            const std::string& label) {
  const verify::Rule* rule = RuleOf(run, id);
  if (rule == nullptr) return {};
  for (const verify::DrawnPoints& d : rule->Drawings()) {
    if (d.label == label) return d.points_mm;
  }
  return {};
}

/// The close-up of rule `id` (which must have errors) planned and shot at 320 x 240.
inline void ShootAfpCloseUp(const VerifyRun& run, const std::string& id, CloseUpPlan& plan,
                            Shot& shot) {
  const verify::Rule* rule = RuleOf(run, id);
  ASSERT_NE(rule, nullptr) << id;
  ASSERT_GT(rule->Summary().errors, 0) << id;
  DiagnosticSink sink;
  const LoadedScene& ls = run.model->loaded;
  render::MjModelPtr model = render::LoadSceneModel(*ls.scene, sink);
  ASSERT_TRUE(model);
  model->vis.map.znear = std::min<float>(model->vis.map.znear, 0.01 / model->stat.extent);
  render::MjDataPtr data(mj_makeData(model.get()));
  const verify::Verifier& v = *run.verifier;
  const CloseUpContext ctx{&ls,
                           run.model->process.get(),
                           &run.model->description,
                           model.get(),
                           data.get(),
                           &v.StitchMarks(),
                           &v};
  std::optional<CloseUpPlan> planned;
  std::string error;
  ASSERT_TRUE(PlanCloseUp(ctx, *rule, planned, error)) << error;
  ASSERT_TRUE(planned.has_value()) << id;
  plan = *planned;
  ASSERT_TRUE(ShootCloseUp(model.get(), data.get(), plan, 320, 240, shot, error)) << error;
}

/// Shoots rule `id`'s close-up and checks its one subject: at least `min_pixels` of it seen,
/// none of it hidden (at least 90 % of what it shows alone), nothing made see-through to show
/// it (its overlays lie above the surface), a legend naming the limit first.
inline void ExpectSubjectSeen(const VerifyRun& run, const std::string& id, long min_pixels) {
  SCOPED_TRACE(id);
  CloseUpPlan plan;
  Shot shot;
  ShootAfpCloseUp(run, id, plan, shot);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(plan.family, verify::CloseUpFamily::kAfp);
  ASSERT_EQ(shot.pixels.size(), 1U);
  const SubjectPixels& s = shot.pixels.front();
  EXPECT_GE(s.visible, min_pixels) << s.visible;
  EXPECT_EQ(s.hidden, 0);
  EXPECT_GE(s.visible, s.alone * 9 / 10);
  EXPECT_TRUE(shot.see_through.empty()) << shot.see_through.front();
  ASSERT_FALSE(plan.legend.empty());
  EXPECT_NE(plan.legend.front().label.find("limit"), std::string::npos);
}

}  // namespace stitchsim::run::testing
