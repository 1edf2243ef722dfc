// Course reversal and the writer of a reordered AFP programme (afp_program.h).
#include <algorithm>
#include <cmath>
#include <ostream>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/afp_program.h"
#include "stitchsim/program/tool_pose.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::program {
namespace {

Eigen::Isometry3d TurnedRound(const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d r = pose;
  r.linear() = pose.linear() * Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return r;
}

std::uint64_t TowMask(int tow_count) {
  return tow_count >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << tow_count) - 1;
}

// The modal state the writer has put in force so far (what it must change, and only that).
struct Written {
  LengthUnit units = LengthUnit::kMillimetre;
  Motion motion = Motion::kNone;
  std::optional<double> feed;
  bool head_retracted = true;
  std::uint64_t tows = 0;
  std::optional<Eigen::Vector3d> angles_rad;  // last A B C written (continuity hint)
};

class Writer {
 public:
  Writer(std::ostream& out, const AfpProgram& p, const Dialect& d, const AfpWriteOptions& o)
      : out_(out), w_(out, d), p_(p), d_(d), o_(o), order_(EulerOrderOf(d)) {}
  void Prologue();
  void Visit(const CourseVisit& v, const std::vector<OffPartBlock>& offpart, int previous_ply);
  void Tail(const std::vector<OffPartBlock>& offpart);

 private:
  void Raw(std::string_view line) {
    w_.Flush();
    out_ << line << '\n';
  }
  void Simple(const Block& b) { w_.Write(b); }
  void Pose(Block& b, const Eigen::Isometry3d& pose);
  void OffPart(const std::vector<OffPartBlock>& blocks, const AfpCourse* next);
  void Reversed(const AfpCourse& c);
  void Tows(std::uint64_t to);
  void Head(bool retracted);

  std::ostream& out_;
  ProgramWriter w_;
  const AfpProgram& p_;
  const Dialect& d_;
  const AfpWriteOptions& o_;
  geom::EulerOrder order_;
  Written s_;
};

void Writer::Pose(Block& b, const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d t = pose.translation();
  const Eigen::Vector3d a =
      geom::EulerFromRotation(order_, pose.linear(), s_.angles_rad ? &*s_.angles_rad : nullptr);
  s_.angles_rad = a;
  b[Axis::kX] = t.x();
  b[Axis::kY] = t.y();
  b[Axis::kZ] = t.z();
  b[Axis::kA] = a.x() * 180.0 / kPi;
  b[Axis::kB] = a.y() * 180.0 / kPi;
  b[Axis::kC] = a.z() * 180.0 / kPi;
}

void Writer::Prologue() {
  w_.WriteMark();
  ProgramHeader h = p_.header;
  h.lines.clear();
  for (const auto& e : o_.header_extra) {  // a key already there takes the new value
    auto it = std::find_if(h.entries.begin(), h.entries.end(),
                           [&](const auto& x) { return x.first == e.first; });
    if (it != h.entries.end()) {
      it->second = e.second;
    } else {
      h.entries.push_back(e);
    }
  }
  w_.WriteHeader(h);
  for (int l = 1; l <= p_.prologue_last_line; ++l) {
    const std::string_view line = p_.Line(l);
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos) continue;
    // The header is written above, from the reader's entries (whatever spacing they had).
    const auto& header_lines = p_.header.lines;
    if (line.substr(i, 1) == "%" ||
        std::find(header_lines.begin(), header_lines.end(), l) != header_lines.end())
      continue;
    Raw(line);
  }
  // The prologue's own modal state is not tracked: state what the off-part moves rely on.
  Block b;
  b.units = LengthUnit::kMillimetre;
  Simple(b);
  s_.units = LengthUnit::kMillimetre;
}

void Writer::Head(bool retracted) {
  if (s_.head_retracted == retracted) return;
  Block b;
  b.m_codes.push_back(retracted ? d_.m.head_retract : d_.m.head_lower);
  Simple(b);
  s_.head_retracted = retracted;
}

// M62 / M63 lines from the written mask to `to` (one tow per line: P is read once per line);
// M63 P0 when every tow goes.
void Writer::Tows(std::uint64_t to) {
  const std::uint64_t mask = TowMask(o_.tow_count);
  to &= mask;
  const std::uint64_t from = s_.tows & mask;
  if (to == 0 && from != 0) {
    Block b;
    b.m_codes.push_back(d_.m.tow_cut);
    b.param = 0;
    Simple(b);
  } else {
    for (int t = 1; t <= o_.tow_count; ++t) {
      const std::uint64_t bit = std::uint64_t{1} << (t - 1);
      if (((from ^ to) & bit) == 0) continue;
      Block b;
      b.m_codes.push_back((to & bit) != 0 ? d_.m.tow_add : d_.m.tow_cut);
      b.param = t;
      Simple(b);
    }
  }
  s_.tows = to;
}

// The off-part blocks, in mm, then the lay-up's entry state (units, mode, feed, head, E, W)
// when the next course is laid as written.
void Writer::OffPart(const std::vector<OffPartBlock>& blocks, const AfpCourse* next) {
  if (!blocks.empty() && s_.units != LengthUnit::kMillimetre) {
    Block u;
    u.units = LengthUnit::kMillimetre;
    Simple(u);
    s_.units = LengthUnit::kMillimetre;
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const OffPartBlock& o = blocks[i];
    Block b;
    Pose(b, o.pose);
    b.motion = o.motion;
    if (o.head_retracted != s_.head_retracted)
      b.m_codes.push_back(o.head_retracted ? d_.m.head_retract : d_.m.head_lower);
    s_.head_retracted = o.head_retracted;
    if (o.motion == Motion::kFeed && o.feed_mm_per_min && s_.feed != o.feed_mm_per_min) {
      b.feed = *o.feed_mm_per_min;
      s_.feed = o.feed_mm_per_min;
    }
    if (o.motion == Motion::kFeed && !s_.feed) {
      b.motion = Motion::kRapid;  // no feed known yet: a rapid cannot miss one
    }
    if (next != nullptr && i + 1 == blocks.size()) {
      if (next->entry.rail_mm) b[Axis::kRail] = *next->entry.rail_mm;
      if (next->entry.rotator_deg) b[Axis::kRotator] = *next->entry.rotator_deg;
    }
    b.comment = o.comment;
    s_.motion = b.motion;
    Simple(b);
  }
}

void Writer::Reversed(const AfpCourse& c) {
  const std::vector<LayupStation> st = ReversedStations(c, o_.tow_count);
  for (std::size_t k = 0; k < st.size(); ++k) {
    if (k > 0) {
      const LayupStation& from = st[k - 1];
      Block b;
      Pose(b, st[k].pose);
      b.motion = from.motion;
      if (from.motion == Motion::kFeed && from.feed_mm_per_min > 0.0 &&
          s_.feed != from.feed_mm_per_min) {
        b.feed = from.feed_mm_per_min;
        s_.feed = from.feed_mm_per_min;
      }
      s_.motion = b.motion;
      Simple(b);
    }
    // The state the move leaving this station needs (the last station: everything cut).
    Tows(k + 1 < st.size() ? st[k].tows : 0);
    if (k + 1 < st.size()) Head(st[k].head_retracted);
  }
}

void Writer::Visit(const CourseVisit& v, const std::vector<OffPartBlock>& offpart,
                   int previous_ply) {
  const AfpCourse& c = p_.courses[static_cast<std::size_t>(v.course)];
  if (c.ply != previous_ply) {
    for (const auto& ply : p_.plies)
      if (ply.number == c.ply) Raw(p_.Line(ply.line));
  }
  Raw(p_.Line(c.begin_line));
  OffPart(offpart, v.reversed ? nullptr : &c);
  if (v.reversed) {
    Reversed(c);
  } else {
    // Restore the lay-up's entry state, then copy its lines as written.
    const LayupEntry& e = c.entry;
    if (e.units != s_.units) {
      Block u;
      u.units = e.units;
      Simple(u);
    }
    Block m;
    if (e.motion != Motion::kNone && e.motion != s_.motion) m.motion = e.motion;
    if (e.feed_mm_per_min && e.feed_mm_per_min != s_.feed) {
      // F is in the programme unit in force.
      m.feed = e.units == LengthUnit::kInch ? *e.feed_mm_per_min / 25.4 : *e.feed_mm_per_min;
    }
    if (m.motion != Motion::kNone || m.feed) Simple(m);
    Head(e.head_retracted);
    for (int l = c.layup_first_line; l <= c.layup_last_line; ++l) Raw(p_.Line(l));
    const LayupStation& last = c.stations.back();
    s_.units = e.units;
    s_.motion = last.motion;
    s_.feed = last.feed_mm_per_min > 0.0 ? std::optional<double>(last.feed_mm_per_min) : s_.feed;
    s_.head_retracted = last.head_retracted;
    s_.tows = 0;
    s_.angles_rad.reset();
  }
  Raw(p_.Line(c.end_line));
}

void Writer::Tail(const std::vector<OffPartBlock>& offpart) {
  OffPart(offpart, nullptr);
  Block end;
  end.m_codes.push_back(d_.m.program_end);
  Simple(end);
  w_.WriteMark();
  w_.Flush();
}

}  // namespace

Eigen::Isometry3d LayupStartPose(const AfpCourse& course, bool reversed) {
  return reversed ? TurnedRound(course.stations.back().pose) : course.stations.front().pose;
}

Eigen::Isometry3d LayupEndPose(const AfpCourse& course, bool reversed) {
  return reversed ? TurnedRound(course.stations.front().pose) : course.stations.back().pose;
}

int MirrorTow(int tow, int tow_count) { return tow_count + 1 - tow; }

std::uint64_t MirrorTows(std::uint64_t tows, int tow_count) {
  std::uint64_t out = 0;
  for (int t = 1; t <= tow_count && t <= 64; ++t)
    if ((tows >> (t - 1)) & 1U) out |= std::uint64_t{1} << (MirrorTow(t, tow_count) - 1);
  return out;
}

std::vector<LayupStation> ReversedStations(const AfpCourse& course, int tow_count) {
  const std::size_t n = course.stations.size();
  std::vector<LayupStation> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const LayupStation& f = course.stations[n - 1 - k];
    LayupStation& r = out[k];
    r.source_line = f.source_line;
    r.pose = TurnedRound(f.pose);
    if (k + 1 < n) {
      // Backwards from station k to k + 1 is forwards from n - 2 - k to n - 1 - k.
      const LayupStation& move = course.stations[n - 2 - k];
      r.tows = MirrorTows(move.tows, tow_count);
      r.head_retracted = move.head_retracted;
      r.motion = move.motion;
      r.feed_mm_per_min = move.feed_mm_per_min;
    } else {
      r.tows = 0;
      r.head_retracted = f.head_retracted;
      r.motion = f.motion;
      r.feed_mm_per_min = f.feed_mm_per_min;
    }
  }
  return out;
}

void WriteAfpProgram(std::ostream& out, const AfpProgram& program, const Dialect& dialect,
                     std::span<const CourseVisit> order, const OffPartSource& offpart,
                     const AfpWriteOptions& options) {
  Writer w(out, program, dialect, options);
  w.Prologue();
  int ply = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    w.Visit(order[i], offpart(i), ply);
    ply = program.courses[static_cast<std::size_t>(order[i].course)].ply;
  }
  w.Tail(offpart(order.size()));
}

}  // namespace stitchsim::program
