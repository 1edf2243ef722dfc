// The programme and the tow CSV of a planned ply (docs/program-format.md, "Fibre placement";
// docs/afp.md, "Plies, courses and tows").

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <span>

#include "detail/program_text.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/ply_planner.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::planner {
namespace {

std::string PlyNum(double v, const char* format = "%.6f") {
  if (std::abs(v) < 5e-7) v = 0.0;
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

/// Tow adds and cuts per course position (the events of every tow, by s).
struct TowCodes {
  std::vector<int> add, cut;
};
std::map<double, TowCodes> CourseEvents(const PlyCourse& c) {
  std::map<double, TowCodes> m;
  for (const PlyTow& t : c.tows) {
    for (const TowSegment& g : t.laid) {
      m[g.start_mm].add.push_back(t.tow);
      m[g.end_mm].cut.push_back(t.tow);
    }
  }
  return m;
}

class PlyWriter {
 public:
  PlyWriter(std::span<const PlyPlan* const> plans, const scene::Scene& scene,
            const program::Dialect& d, std::ostream& out)
      : plans_(plans), plan_(plans.front()), scene_(scene), d_(d), w_(out, d), pose_(d) {}

  void Write(const std::string& laminate = {}) {
    program::ProgramIdentity id;
    if (!laminate.empty()) id.laminate = laminate;
    id.scene = scene_.name;
    id.head = scene_.head.name;
    id.tows = plan_->band.count;
    if (plans_.size() == 1) {
      id.ply = plan_->ply_name;
      id.angle_deg = plan_->angle_rad * 180.0 / kPi;
      id.coverage_pct = plan_->coverage * 100.0;
      id.courses = static_cast<long>(plan_->courses.size());
    } else {
      // Several plies: names joined by commas, courses summed (each ply's own line says more).
      std::string names;
      std::size_t courses = 0;
      for (const PlyPlan* p : plans_) {
        names += (names.empty() ? "" : ",") + p->ply_name;
        courses += p->courses.size();
      }
      id.plies = names;
      id.courses = static_cast<long>(courses);
    }
    detail::WriteOpening(w_, b_, d_, program::WriteIdentity(id), scene_.head.tool_number);
    for (const PlyPlan* p : plans_) {
      plan_ = p;
      b_.Clear();
      b_.m_codes = {d_.m.ply_start};
      b_.param = plan_->ply_index;
      b_.comment =
          "PLY name=" + plan_->ply_name + " angle=" + PlyNum(plan_->angle_rad * 180.0 / kPi, "%g");
      w_.Write(b_);
      for (const PlyCourse& c : plan_->courses) WriteCourse(c);
    }
    detail::WriteEnding(w_, b_, d_);
  }

 private:
  void Rapid(const PlyPoint& p, int m_code, const char* comment) {
    b_.Clear();
    b_.motion = program::Motion::kRapid;
    pose_.Set(b_, p.tool.translation() + kPlyApproachHeightMm * p.tool.linear().col(2),
              p.tool.linear());
    if (m_code >= 0) b_.m_codes = {m_code};
    b_.comment = comment;
    w_.Write(b_);
  }
  void Code(int m_code, std::optional<int> param, std::string comment = {}) {
    detail::WriteCode(w_, b_, m_code, param, std::move(comment));
  }
  /// A feed move to `p` at `feed_mm_s` (F only when it changes).
  void Feed(const PlyPoint& p, double feed_mm_s) {
    b_.Clear();
    b_.motion = program::Motion::kFeed;
    pose_.Set(b_, p.tool);
    const double feed = feed_mm_s * 60.0;
    if (feed != feed_) b_.feed = feed_ = feed;
    w_.Write(b_);
  }

  /// The feed of the move from `a` to `b` along a course whose cuts and adds lie at `events`:
  /// the head's slow-zone feed when the move's middle is within cut_add_zone_mm of one (the
  /// planner puts points at the zones' edges, so a move lies wholly in or out), else the
  /// lay-up speed; mm/s.
  double FeedOf(const PlyPoint& a, const PlyPoint& b,
                const std::map<double, TowCodes>& events) const {
    const scene::AfpSpec& afp = scene_.head.afp;
    if (afp.cut_add_feed_mm_s <= 0.0 || afp.cut_add_zone_mm <= 0.0) return afp.layup_speed_mm_s;
    const double mid = 0.5 * (a.s_mm + b.s_mm);
    const bool slow = std::any_of(events.begin(), events.end(), [&](const auto& e) {
      return std::abs(mid - e.first) < afp.cut_add_zone_mm;
    });
    return slow ? std::min(afp.layup_speed_mm_s, afp.cut_add_feed_mm_s) : afp.layup_speed_mm_s;
  }

  void WriteCourse(const PlyCourse& c) {
    const int n = static_cast<int>(plan_->courses.size());
    Code(d_.m.course_start, c.number,
         "COURSE " + std::to_string(c.number) + " of " + std::to_string(n));
    Rapid(c.points.front(), d_.m.head_retract, "approach");
    Code(d_.m.head_lower, std::nullopt);
    const auto events = CourseEvents(c);
    std::uint64_t laid = 0;
    // Tow numbers as the head numbers them (PlyTow::tow); P0 only when the band is the head.
    const std::uint64_t all = process::BandTows(plan_->band);
    for (const PlyPoint& p : c.points) {
      // The plunge onto the first point at the lay-up speed, then each move at its zone's.
      Feed(p, &p == &c.points.front() ? scene_.head.afp.layup_speed_mm_s
                                      : FeedOf(*(&p - 1), p, events));
      const auto it = events.find(p.s_mm);
      if (it == events.end()) continue;
      std::uint64_t cut = 0, add = 0;
      for (int t : it->second.cut) cut |= std::uint64_t{1} << (t - 1);
      for (int t : it->second.add) add |= std::uint64_t{1} << (t - 1);
      if (cut != 0 && (laid & ~cut) == 0 && add == 0 && &p == &c.points.back()) {
        Code(d_.m.tow_cut, 0);
      } else {
        for (int t : it->second.cut) Code(d_.m.tow_cut, t);
      }
      laid &= ~cut;
      if (laid == 0 && add == all && plan_->band.count == plan_->layout.tows) {
        Code(d_.m.tow_add, 0);
      } else {
        for (int t : it->second.add) Code(d_.m.tow_add, t);
      }
      laid |= add;
    }
    if (laid != 0) Code(d_.m.tow_cut, 0);
    Code(d_.m.head_retract, std::nullopt);
    Rapid(c.points.back(), -1, "leave");
    Code(d_.m.course_end, std::nullopt);
  }

  std::span<const PlyPlan* const> plans_;
  const PlyPlan* plan_;
  const scene::Scene& scene_;
  const program::Dialect& d_;
  program::ProgramWriter w_;
  detail::PoseWords pose_;
  program::Block b_;
  double feed_ = 0.0;
};

}  // namespace

void WritePlyProgram(const PlyPlan& plan, const scene::Scene& scene,
                     const program::Dialect& dialect, std::ostream& out) {
  const PlyPlan* one[] = {&plan};
  PlyWriter(one, scene, dialect, out).Write();
}

void WritePlyProgram(std::span<const PlyPlan* const> plans, const scene::Scene& scene,
                     const program::Dialect& dialect, std::ostream& out,
                     const std::string& laminate) {
  PlyWriter(plans, scene, dialect, out).Write(laminate);
}

void WritePlyTowsCsv(const PlyPlan& plan, std::ostream& out) {
  std::string text =
      "course,tow,segment,s_start_mm,s_end_mm,s_mm,left_x,left_y,left_z,right_x,right_y,"
      "right_z\n";
  for (const PlyCourse& c : plan.courses) {
    for (const PlyTow& t : c.tows) {
      const std::size_t i = static_cast<std::size_t>(t.tow - plan.band.first + 1);
      for (std::size_t g = 0; g < t.laid.size(); ++g) {
        const TowSegment& seg = t.laid[g];
        for (const PlyPoint& p : c.points) {
          if (p.s_mm < seg.start_mm || p.s_mm > seg.end_mm) continue;
          text +=
              std::to_string(c.number) + ',' + std::to_string(t.tow) + ',' + std::to_string(g + 1);
          const Eigen::Vector3d& l = p.boundary[i - 1];
          const Eigen::Vector3d& r = p.boundary[i];
          for (double v :
               {seg.start_mm, seg.end_mm, p.s_mm, l.x(), l.y(), l.z(), r.x(), r.y(), r.z()}) {
            text += ',';
            text += PlyNum(v);
          }
          text += '\n';
        }
      }
    }
  }
  out << text;
}

}  // namespace stitchsim::planner
