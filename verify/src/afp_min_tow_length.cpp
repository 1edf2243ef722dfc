// afp.min_tow_length: every tow piece the programme lays against the shortest piece the head
// can lay, the distance from its cutter to the compaction roller (docs/report-format.md, the
// afp.* rules; issue 29): a tow added closer than that before its cut is cut before it reaches
// the roller. The minimum: scene::MinTowLengthMm (the scene's limit, else the head's); skipped
// while neither is given.
// A piece is one tow followed from line to line of a course while its centre line continues
// (as afp.steering_radius follows it); its length is the centre line's along the surface, the
// sum of chords at most half a tow width long. A cut, another course or a line that lays
// nothing ends it. A short piece is reported on the line that adds it (one finding per line:
// the shortest piece added there), with the line that cuts it in the message.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "afp_laid.h"
#include "detail/rule_registry.h"
#include "stitchsim/verify/rule_registry.h"

namespace stitchsim::verify {
namespace {

using detail::LaidLine;

class MinTowLengthRule final : public Rule {
 public:
  MinTowLengthRule(const RuleContext& ctx, std::shared_ptr<detail::LaidTows> laid)
      : Rule("afp.min_tow_length",
             "length of every tow piece laid (centre line along the surface, from add to cut) "
             "against the shortest the head can lay, its cutter-to-roller distance "
             "(worst = shortest)",
             "mm"),
        laid_(std::move(laid)),
        tows_(static_cast<std::size_t>(laid_->Layout().tows) + 1) {
    summary_.error_limit =
        scene::MinTowLengthMm(*ctx.scene);  // given (the entry skips the rule otherwise)
    worst_is_smallest_ = true;
    mergeable_ = false;  // a piece runs over many lines (Rule::Mergeable)
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      AddSubject("tow " + std::to_string(t), summary_.error_limit, std::nullopt);
    }
  }

  void OnLine(const trace::LineRecord& record) override {
    const LaidLine* line = laid_->Sample(record);
    if (line == nullptr) {
      CutAll();
      return;
    }
    const geom::Surface& surface = laid_->Surface();
    const double join_tol = 0.25 * laid_->Layout().width_mm;
    const bool on_surface = std::all_of(line->poses.begin(), line->poses.end(),
                                        [](const detail::LaidPose& p) { return p.cross.ok; });
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      Piece& piece = tows_[static_cast<std::size_t>(t)];
      if (!on_surface || !detail::TowLaid(line->tows, t)) {
        if (piece.open) Cut(piece, t);
        continue;
      }
      Eigen::Vector3d point = surface.Point(detail::TowCentreUv(line->poses.front().cross, t));
      const bool continues =
          piece.open && piece.course == line->course && (piece.last - point).norm() < join_tol;
      if (!continues) {
        if (piece.open) Cut(piece, t);
        piece =
            Piece{true, line->course, record.source_line, record.source_line, 0.0, point, point};
      }
      for (std::size_t k = 1; k < line->poses.size(); ++k) {
        const Eigen::Vector3d next = surface.Point(detail::TowCentreUv(line->poses[k].cross, t));
        piece.length_mm += (next - point).norm();
        point = next;
      }
      piece.last = point;
      piece.last_line = record.source_line;
    }
    Flush();
  }

  void Finish(const RuleContext&) override { CutAll(); }

  // The shortest piece under the limit: its centre line's two ends (add, cut), part mm.
  std::vector<DrawnPoints> Drawings() const override {
    if (shortest_ends_.empty()) return {};
    return {{"close_up:afp_short_piece", shortest_ends_}};
  }

 private:
  struct Piece {
    bool open = false;
    int course = 0;
    int first_line = 0;  ///< the line that adds the piece
    int last_line = 0;   ///< the last line that lays it
    double length_mm = 0.0;
    Eigen::Vector3d last = Eigen::Vector3d::Zero();   ///< the centre line's end so far
    Eigen::Vector3d first = Eigen::Vector3d::Zero();  ///< its start (the add), part mm
  };

  void CutAll() {
    for (int t = 1; t <= laid_->Layout().tows; ++t) {
      Piece& piece = tows_[static_cast<std::size_t>(t)];
      if (piece.open) Cut(piece, t);
    }
    Flush();
  }

  // Closes tow `tow`'s piece.
  void Cut(Piece& piece, int tow) {
    piece.open = false;
    ObserveSmallest(piece.length_mm, piece.first_line, static_cast<std::size_t>(tow) - 1);
    if (piece.length_mm < *summary_.error_limit) {
      detail::KeepSmallest(short_, piece.first_line,
                           {piece.length_mm, tow, piece.last_line, piece.first});
      if (piece.length_mm < shortest_) {
        shortest_ = piece.length_mm;
        shortest_ends_ = {piece.first, piece.last};
      }
    }
  }

  // Records the short pieces added before every open piece's first line: one finding per
  // line, in line order.
  void Flush() {
    int open_from = std::numeric_limits<int>::max();
    for (const Piece& piece : tows_)
      if (piece.open) open_from = std::min(open_from, piece.first_line);
    detail::TakeLinesUpTo(short_, open_from - 1, [&](int line, const detail::TowShortfall& s) {
      char buf[200];
      std::snprintf(buf, sizeof(buf),
                    "tow %d laid %.4g mm from its add to its cut after line %d, shorter than "
                    "the head's cutter-to-roller distance of %.4g mm",
                    s.tow, s.value, s.other_line, *summary_.error_limit);
      Record(FindingSeverity::kError, s.value, *summary_.error_limit, line, 0,
             "tow " + std::to_string(s.tow), buf, nullptr,
             s.position_mm ? &*s.position_mm : nullptr);
    });
  }

  std::shared_ptr<detail::LaidTows> laid_;
  std::vector<Piece> tows_;                    ///< per tow (index 1..k)
  std::map<int, detail::TowShortfall> short_;  ///< per add line: the shortest piece under the limit
  double shortest_ = std::numeric_limits<double>::infinity();  ///< mm
  std::vector<Eigen::Vector3d> shortest_ends_;                 ///< its add and cut ends, part mm
};

}  // namespace

RuleEntry AfpMinTowLengthRuleEntry() {
  return {"afp.min_tow_length", CloseUpFamily::kAfp,
          [](const RuleContext& ctx) {
            return detail::RunsWhenLayingWithLimit(
                ctx, scene::MinTowLengthMm(*ctx.scene),
                "no minimum tow length given (limits: afp.min_tow_length: {min_mm: ...}, or the "
                "head's cut_to_roller_mm)");
          },
          detail::MakeLaying<MinTowLengthRule>};
}

}  // namespace stitchsim::verify
