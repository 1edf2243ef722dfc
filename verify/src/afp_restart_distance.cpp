// afp.restart_distance: every tow the programme adds again within a course against the
// shortest distance the head must travel between cutting a tow and adding it again
// (docs/report-format.md, the afp.* rules; issue 29). The minimum: scene::MinRestartMm (the
// scene's limit, else the head's); skipped while neither is given.
// The distance is the tow's centre line along the surface, from the last point laid before the
// cut to the first point laid at the re-add, followed over the lines in between at their
// sampled poses (at most half a tow width apart: the chords of afp_laid.h; a line that lays no
// tow is sampled the same way). A rapid or lifted move within the course, or a pose whose
// roller is off the surface, is bridged by the chord across it, which is never longer than the
// path on the surface: the distance is then a lower bound and can only fire early. Another
// course or ply resets: a tow added in a new course is not a restart. One finding per line
// (the closest restart added there), on the line that adds the tow again, with the line after
// which it was cut in the message.
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "detail/rule_registry.h"
#include "stitchsim/verify/rule_registry.h"

namespace stitchsim::verify {
namespace {

class RestartDistanceRule final : public Rule {
 public:
  RestartDistanceRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.restart_distance",
             "distance along each tow's centre line on the surface, within a course, from the "
             "point where it is cut to the point where it is added again, against the head's "
             "minimum restart distance (worst = shortest)",
             "mm"),
        laid_(std::move(laid)),
        tows_(static_cast<std::size_t>(laid_->Layout().tows) + 1) {
    summary_.error_limit = scene::MinRestartMm(*ctx.scene);
    worst_is_smallest_ = true;
    mergeable_ = false;  // a cut and its re-add lie on different lines (Rule::Mergeable)
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      AddSubject("tow " + std::to_string(t), summary_.error_limit, std::nullopt);
    }
  }

  void OnLine(const trace::LineRecord& record) override {
    if (record.course == 0 || record.course != course_ || record.ply != ply_) {
      for (TowTrack& track : tows_) track = TowTrack{};
      course_ = record.course;
      ply_ = record.ply;
    }
    const detail::LaidLine* line = PathOf(record);
    if (line == nullptr) {
      // A rapid or lifted move lays nothing: the tows laid so far are cut where they stopped.
      for (TowTrack& track : tows_) CutIfLaying(track);
      return;
    }
    for (int t = 1; t <= laid_->Layout().tows; ++t) Follow(*line, t);
    detail::TakeLinesUpTo(short_, record.source_line, [&](int at, const detail::TowShortfall& s) {
      char buf[200];
      std::snprintf(buf, sizeof(buf),
                    "tow %d added again %.4g mm after its cut after line "
                    "%d, closer than the head's minimum restart distance "
                    "of %.4g mm",
                    s.tow, s.value, s.other_line, *summary_.error_limit);
      Record(FindingSeverity::kError, s.value, *summary_.error_limit, at, 0,
             "tow " + std::to_string(s.tow), buf, nullptr,
             s.position_mm ? &*s.position_mm : nullptr);
    });
  }

  // The closest restart under the limit: the tow's last point before its cut and its first
  // at the re-add (its centre line, part mm).
  std::vector<DrawnPoints> Drawings() const override {
    if (closest_ends_.empty()) return {};
    return {{"close_up:afp_restart", closest_ends_}};
  }

 private:
  struct TowTrack {
    bool laid = false;          ///< laid earlier in this course: adding it again is a restart
    bool laying = false;        ///< laid on the last line that sampled the path
    bool have_point = false;    ///< `point` is set
    int cut_line = 0;           ///< the last line that laid it
    double since_cut_mm = 0.0;  ///< centre line followed since the cut, mm
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< the centre line's last point, part mm
    Eigen::Vector3d cut = Eigen::Vector3d::Zero();    ///< the last point laid before the cut
  };

  // The sampled line: the shared sampling for a laying line, else this rule's own of a feed
  // move within the course; nullptr outside a course, for a rapid and with the head lifted.
  const detail::LaidLine* PathOf(const trace::LineRecord& record) {
    if (const detail::LaidLine* line = laid_->Sample(record)) return line;
    if (record.course == 0 || record.rapid || record.head_retracted) return nullptr;
    laid_->SamplePath(record, path_);
    return &path_;
  }

  static void CutIfLaying(TowTrack& track) {
    if (!track.laying) return;
    track.laying = false;
    track.since_cut_mm = 0.0;
    track.cut = track.point;
  }

  // Follows tow `tow`'s centre line over `line`: the distance since its cut while the line
  // does not lay it; the restart at the line's first point on the surface when it lays it again.
  void Follow(const detail::LaidLine& line, int tow) {
    TowTrack& track = tows_[static_cast<std::size_t>(tow)];
    const bool lays = detail::TowLaid(line.tows, tow);
    if (!lays && !track.laid) return;  // not added yet in this course
    if (!lays) CutIfLaying(track);
    bool restart = lays && track.laid && !track.laying;
    for (const detail::LaidPose& pose : line.poses) {
      if (!pose.cross.ok) continue;
      const Eigen::Vector3d p = laid_->Surface().Point(detail::TowCentreUv(pose.cross, tow));
      if ((!lays || restart) && track.have_point) track.since_cut_mm += (p - track.point).norm();
      track.point = p;
      track.have_point = true;
      if (restart) Restart(track, tow, line.source_line);
      restart = false;
    }
    if (restart) Restart(track, tow, line.source_line);  // no pose on the surface: so far
    if (lays) {
      track.laid = true;
      track.laying = true;
      track.cut_line = line.source_line;
    }
  }

  void Restart(const TowTrack& track, int tow, int line) {
    ObserveSmallest(track.since_cut_mm, line, static_cast<std::size_t>(tow) - 1);
    if (track.since_cut_mm < *summary_.error_limit) {
      detail::KeepSmallest(short_, line, {track.since_cut_mm, tow, track.cut_line, track.point});
      if (track.since_cut_mm < closest_) {
        closest_ = track.since_cut_mm;
        closest_ends_ = {track.cut, track.point};
      }
    }
  }

  std::shared_ptr<detail::LaidTows> laid_;
  std::vector<TowTrack> tows_;                 ///< per tow (index 1..k)
  int course_ = 0, ply_ = 0;                   ///< the course followed (0: none)
  detail::LaidLine path_;                      ///< a feed move laying no tow, as sampled here
  std::map<int, detail::TowShortfall> short_;  ///< per re-add line: the closest restart
  double closest_ = std::numeric_limits<double>::infinity();  ///< mm
  std::vector<Eigen::Vector3d> closest_ends_;  ///< its cut and re-add points, part mm
};

}  // namespace

RuleEntry AfpRestartDistanceRuleEntry() {
  return {"afp.restart_distance", CloseUpFamily::kAfp,
          [](const RuleContext& ctx) {
            return detail::RunsWhenLayingWithLimit(
                ctx, scene::MinRestartMm(*ctx.scene),
                "no minimum restart distance given (limits: afp.restart_distance: {min_mm: "
                "...}, or the head's min_restart_mm)");
          },
          detail::MakeLaying<RestartDistanceRule>};
}

}  // namespace stitchsim::verify
