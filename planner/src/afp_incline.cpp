#include "stitchsim/planner/afp_incline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "stitchsim/common/units.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/reader.h"

namespace stitchsim::planner {
namespace {

// Programme line -> index of the course point its move ends at (moves in order = points).
std::map<int, std::size_t> PointLines(const std::string& text) {
  DiagnosticSink sink;
  std::map<int, std::size_t> out;
  std::size_t point = 0;
  for (const auto& b : program::ParseString(text, program::Dialect::Default(), "c.nc", sink)) {
    if (b.motion != program::Motion::kNone) out[b.source_line] = point++;
  }
  return out;
}

// Lowers the feed of every move the joint-speed rule flags so its worst joint lands at the
// target fraction of the limit. False (with the reason) when a flagged line is not a feed
// move.
bool LowerFeeds(const InclineVerdict& v, const std::string& text, double target, AfpPlan& plan,
                std::string& why) {
  const std::map<int, std::size_t> points = PointLines(text);
  for (const auto& [line, pct] : v.joint_speed_pct) {
    const auto at = points.find(line);
    if (at == points.end() || at->second == 0 || at->second >= plan.points.size()) {
      why = v.joint_speed_rule + " at line " + std::to_string(line) +
            ", which is not a feed move: its speed cannot be lowered";
      return false;
    }
    plan.points[at->second].feed_fraction *= target * v.joint_speed_limit_pct / pct;
  }
  return !v.joint_speed_pct.empty();
}

// Judges one planned candidate, lowering feeds where only the joint speed fails. Fills the
// verdict; returns false when the programme could not be judged (`error`).
bool JudgeCandidate(const scene::Scene& scene, const InclineJudge& judge,
                    const InclineSearchOptions& search, AfpPlan& plan, InclineCandidate& c,
                    std::string& error) {
  if (!plan.over_travel.empty()) {
    c.failure = plan.over_travel.front().code + ": " + plan.over_travel.front().message;
    return true;
  }
  for (int round = 0; round <= search.max_feed_rounds; ++round) {
    std::ostringstream text;
    WriteAfpProgram(plan, scene, program::Dialect::Default(), text);
    const InclineVerdict v = judge(text.str());
    if (!v.error.empty()) {
      error = v.error;
      return false;
    }
    c.slowed_moves = 0;
    c.slowest_feed_fraction = 1.0;
    for (const auto& p : plan.points) {
      if (p.feed_fraction < 1.0) ++c.slowed_moves;
      c.slowest_feed_fraction = std::min(c.slowest_feed_fraction, p.feed_fraction);
    }
    if (v.pass) {
      c.pass = true;
      c.failure.clear();
      return true;
    }
    c.failure = v.first_failure;
    if (!v.only_joint_speed_fails) return true;
    if (round == search.max_feed_rounds) {
      c.failure += " (still, after lowering the feed " + std::to_string(round) + " times)";
      return true;
    }
    std::string why;
    if (!LowerFeeds(v, text.str(), search.feed_target_fraction, plan, why)) {
      if (!why.empty()) c.failure = why;
      return true;
    }
  }
  return true;
}

}  // namespace

std::vector<double> InclineCandidates(const InclineSearchOptions& search) {
  const int steps = static_cast<int>(std::floor(search.max_deg / search.step_deg + 1e-9));
  std::vector<double> out{0.0};
  for (int k = 1; k <= steps; ++k) {
    out.push_back(k * search.step_deg * kDeg);
    out.push_back(-k * search.step_deg * kDeg);
  }
  return out;
}

InclineSearchResult SearchAfpIncline(
    const scene::Scene& scene, const scene::PathSpec* path, AfpPlanOptions options,
    const InclineSearchOptions& search, const InclineJudge& judge, DiagnosticSink& sink,
    const std::function<void(const InclineCandidate&)>& on_candidate) {
  InclineSearchResult out;
  for (double incline_rad : InclineCandidates(search)) {
    options.incline_rad = incline_rad;
    auto plan = PlanAfpCourse(scene, path, options, sink);
    if (!plan || sink.HasErrors()) {
      out.error = "the course could not be planned";
      return out;
    }
    InclineCandidate c;
    c.incline_rad = incline_rad;
    std::string error;
    if (!JudgeCandidate(scene, judge, search, *plan, c, error)) {
      char deg[32];
      std::snprintf(deg, sizeof(deg), "%.3f", incline_rad / kDeg);
      out.error = std::string("incline ") + deg + " deg: " + error;
      return out;
    }
    out.candidates.push_back(c);
    if (on_candidate) on_candidate(c);
    if (c.pass) {
      out.plan = std::move(plan);
      return out;
    }
  }
  return out;
}

}  // namespace stitchsim::planner
