// afp.steering_radius: the steering radius of every laid tow's centre line against the head's
// smallest steering radius, by the one definition the ply planner reports it with
// (process/afp_steering.h; docs/afp.md, "Steering radius"): the circle through the tow
// centres at a vertex and at the vertices a half window before and after it along the tow,
// laid into the tangent plane. The vertices are the programme's poses (line ends) where the
// tow lays; a line longer than the half window is divided at its sampled poses, so that a head
// turning along one long move is measured too. A tow is followed from line to line of a course
// while its centre line continues; a cut, another course or a line that lays nothing starts it
// again. A radius is reported on the line that ends at its vertex (one finding per line, the
// smallest tow). A curve in space that is a geodesic of the surface (a helix on a cylinder)
// does not steer: its turning lies along the normal.
#include "stitchsim/process/afp_steering.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "detail/rule_registry.h"

namespace stitchsim::verify {
namespace {

using detail::LaidLine;
using process::SteeringWindow;

class SteeringRadiusRule final : public Rule {
 public:
  SteeringRadiusRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.steering_radius",
             "steering radius (geodesic radius of the centre line over a 50 mm window) of every "
             "laid tow against the smallest the head allows (worst = smallest)",
             "mm"),
        laid_(std::move(laid)),
        tows_(static_cast<std::size_t>(laid_->Layout().tows) + 1) {
    const std::optional<double> given = ctx.scene->limits.Get(scene::LimitKey::kAfpSteeringMinMm);
    summary_.error_limit = given ? *given : ctx.scene->head.afp.min_steering_radius_mm;
    worst_is_smallest_ = true;
    mergeable_ = false;  // judged over whole plies (Rule::Mergeable)
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      AddSubject("tow " + std::to_string(t), summary_.error_limit, std::nullopt);
    }
  }

  void OnLine(const trace::LineRecord& record) override {
    const LaidLine* line = laid_->Sample(record);
    if (line == nullptr) {
      for (Tow& tow : tows_) tow.laying = false;
      Flush(std::numeric_limits<int>::max());
      return;
    }
    const geom::Surface& surface = laid_->Surface();
    const double join_tol = 0.25 * laid_->Layout().width_mm;
    const std::size_t n = line->poses.size();
    // Divide a line longer than the half window at sampled poses (none on a planner's line).
    const double length = (record.to.translation() - record.from.translation()).norm();
    const std::size_t pieces = static_cast<std::size_t>(
        std::clamp(std::ceil(length / process::kSteeringHalfWindowMm - 1e-9), 1.0,
                   static_cast<double>(n - 1)));
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      Tow& tow = tows_[static_cast<std::size_t>(t)];
      const bool ok = detail::TowLaid(line->tows, t) &&
                      std::all_of(line->poses.begin(), line->poses.end(),
                                  [](const detail::LaidPose& p) { return p.cross.ok; });
      if (!ok) {
        tow.laying = false;
        continue;
      }
      auto centre = [&](std::size_t i) { return detail::TowCentreUv(line->poses[i].cross, t); };
      const Eigen::Vector3d start = surface.Point(centre(0));
      const bool continues =
          tow.laying && tow.course == line->course && (tow.last - start).norm() < join_tol;
      if (!continues) {
        tow.window.Reset();
        tow.laying = true;
        tow.course = line->course;
      }
      radii_.clear();
      for (std::size_t k = continues ? 1 : 0; k <= pieces; ++k) {
        const Eigen::Vector2d uv = centre(k * (n - 1) / pieces);
        tow.last = surface.Point(uv);
        tow.window.Add(tow.last, surface.Normal(uv), line->source_line, radii_);
      }
      for (const auto& r : radii_) Consider(r, t);
    }
    // Lines before every tow's next unmeasured vertex are complete.
    Flush(line->source_line - 1);
  }

  void Finish(const RuleContext&) override {
    for (Tow& tow : tows_) tow.laying = false;
    Flush(std::numeric_limits<int>::max());
  }

  // The smallest radius under the limit: the steered tow's centres a half window before, at
  // and after the measured vertex (the circle's three points), for its close-up.
  std::vector<DrawnPoints> Drawings() const override {
    if (window_.empty()) return {};
    return {{"close_up:afp_steering", window_}};
  }

 private:
  struct Tow {
    bool laying = false;
    int course = 0;
    Eigen::Vector3d last = Eigen::Vector3d::Zero();  ///< the last vertex's centre
    SteeringWindow window;
  };
  // Counts one measurement of tow `tow` and tracks the smallest radius (the rule's and the
  // tow's: Rule::Observe keeps the largest); a radius under the limit waits for its line.
  // The smallest radius under the limit keeps its window's three tow centres (Drawings()).
  void Consider(const SteeringWindow::Radius& r, int tow) {
    const double radius = r.radius_mm;
    const int line = r.tag;
    ObserveSmallest(radius, line, static_cast<std::size_t>(tow) - 1);
    if (detail::LaidFigures* f = laid_->Figures()) f->SteeringRadius(line, tow, radius);
    if (radius >= *summary_.error_limit) return;
    detail::KeepSmallest(below_, line, {radius, tow, 0, r.at});
    if (radius < smallest_below_) {
      smallest_below_ = radius;
      window_ = {r.before, r.at, r.after};
    }
  }

  // Records the lines up to `last_line` with a radius under the limit: one finding per line.
  void Flush(int last_line) {
    int pending = std::numeric_limits<int>::max();  // no tow waits for a window beyond this
    for (const Tow& tow : tows_)
      if (tow.laying) pending = std::min(pending, tow.window.PendingTag());
    last_line = std::min(last_line, pending - 1);
    detail::TakeLinesUpTo(below_, last_line, [&](int line, const detail::TowShortfall& worst) {
      char buf[200];
      std::snprintf(buf, sizeof(buf),
                    "tow %d steers on a radius of %.4g mm, below the head's smallest steering "
                    "radius of %.4g mm",
                    worst.tow, worst.value, *summary_.error_limit);
      Record(FindingSeverity::kError, worst.value, *summary_.error_limit, line, 0,
             "tow " + std::to_string(worst.tow), buf, nullptr,
             worst.position_mm ? &*worst.position_mm : nullptr);
    });
  }

  std::shared_ptr<detail::LaidTows> laid_;
  std::vector<Tow> tows_;  ///< per tow (index 1..k)
  std::vector<SteeringWindow::Radius> radii_;
  std::map<int, detail::TowShortfall> below_;  ///< per line: the smallest radius under the limit
  double smallest_below_ = std::numeric_limits<double>::infinity();  ///< mm
  std::vector<Eigen::Vector3d> window_;  ///< its three tow centres, part frame, mm
};

}  // namespace

RuleEntry AfpSteeringRuleEntry() {
  return {"afp.steering_radius", CloseUpFamily::kAfp, detail::RunsWhenLaying,
          [](const RuleContext& ctx, detail::RuleMaking& making) -> std::unique_ptr<Rule> {
            return std::make_unique<SteeringRadiusRule>(ctx, making.Laid(ctx));
          }};
}

}  // namespace stitchsim::verify
