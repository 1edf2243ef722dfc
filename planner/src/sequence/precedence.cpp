// The precedence network of an AFP programme (sequence/precedence.h, docs/sequence.md).
#include "stitchsim/planner/sequence/precedence.h"

#include <algorithm>

#include "grid.h"

namespace stitchsim::planner {
namespace {

// Grid cell: twice the median quad extent in (u, v), so a quad meets a few cells.
double CellSize(const std::vector<CourseFootprint>& fp) {
  std::vector<double> ext;
  for (const auto& f : fp)
    for (std::size_t i = 0; i < f.quads.size(); i += 7) {
      const auto& q = f.quads[i];
      Eigen::Vector2d lo = q.uv[0], hi = q.uv[0];
      for (int k = 1; k < 4; ++k) {
        lo = lo.cwiseMin(q.uv[k]);
        hi = hi.cwiseMax(q.uv[k]);
      }
      ext.push_back((hi - lo).maxCoeff());
    }
  if (ext.empty()) return 1.0;
  std::nth_element(ext.begin(), ext.begin() + static_cast<long>(ext.size() / 2), ext.end());
  const double m = ext[ext.size() / 2];
  return m > 0.0 ? 2.0 * m : 1.0;
}

// Ply (index into program.plies) of every course.
std::vector<int> PlyOfCourse(const program::AfpProgram& p) {
  std::vector<int> out(p.courses.size(), -1);
  for (std::size_t i = 0; i < p.plies.size(); ++i)
    for (const int c : p.plies[i].courses) out[static_cast<std::size_t>(c)] = static_cast<int>(i);
  return out;
}

// The overlap queries of a network being built: one grid per set, so that a course can be
// tested against any set (course-level moves query earlier sets). A course whose footprint is
// incomplete (a tow walk left the surface) is taken to overlap every course of another ply: it
// can never join or move.
class SetOverlaps {
 public:
  SetOverlaps(const geom::Surface& surface, const std::vector<CourseFootprint>& footprints,
              const std::vector<int>& ply_of, double min_overlap_mm2)
      : surface_(surface),
        footprints_(footprints),
        ply_of_(ply_of),
        min_overlap_mm2_(min_overlap_mm2),
        cell_(CellSize(footprints)) {}

  /// Opens a new, empty set (the next in laying order).
  void AddSet() {
    grids_.emplace_back(surface_, footprints_, cell_);
    has_unknown_.push_back(0);
  }
  /// Puts course `c` into set `set`'s grid.
  void Insert(int c, std::size_t set) {
    grids_[set].Insert(c);
    if (Unknown(c)) has_unknown_[set] = 1;
  }
  /// True when `c` overlaps a course of another ply in `set` (more than the minimum area, or
  /// either footprint incomplete); `*blocker` the first such course found, if any.
  bool Overlaps(int c, std::size_t set, int* blocker) {
    if (Unknown(c) || has_unknown_[set]) return true;
    bool found = false;
    grids_[set].Query(
        c, [&](int other) { return PlyOf(other) == PlyOf(c); },
        [&](int other, double area) {
          if (area > min_overlap_mm2_ || Unknown(other)) {
            if (!found && blocker != nullptr) *blocker = other;
            found = true;
          }
        });
    return found;
  }

 private:
  bool Unknown(int c) const { return !footprints_[static_cast<std::size_t>(c)].ok; }
  int PlyOf(int c) const { return ply_of_[static_cast<std::size_t>(c)]; }

  const geom::Surface& surface_;
  const std::vector<CourseFootprint>& footprints_;
  const std::vector<int>& ply_of_;
  double min_overlap_mm2_;
  double cell_;
  std::vector<detail::QuadGrid> grids_;
  std::vector<char> has_unknown_;
};

// The seed's ply-level rule: plies in programme order, each joining the last set when none of
// its courses overlaps a course of another ply there, else opening a new set.
void JoinPliesIntoSets(const program::AfpProgram& program, SetOverlaps& overlaps,
                       PrecedenceNetwork& net) {
  for (std::size_t pi = 0; pi < program.plies.size(); ++pi) {
    const auto& courses = program.plies[pi].courses;
    bool joins = !net.sets.empty();
    for (std::size_t k = 0; joins && k < courses.size(); ++k) {
      int blocker = -1;
      if (overlaps.Overlaps(courses[k], net.sets.size() - 1, &blocker)) {
        joins = false;
        net.blocker_of_course[static_cast<std::size_t>(courses[k])] = blocker;
      }
    }
    if (!joins) {
      net.sets.emplace_back();
      overlaps.AddSet();
    }
    PrecedenceSet& set = net.sets.back();
    set.plies.push_back(static_cast<int>(pi));
    for (const int c : courses) {
      set.courses.push_back(c);
      net.set_of_course[static_cast<std::size_t>(c)] = static_cast<int>(net.sets.size()) - 1;
      overlaps.Insert(c, net.sets.size() - 1);
    }
  }
}

// Course-level precedence, in programme order: a course of set k moves to set j + 1, j the
// latest earlier set holding a course (of another ply) it overlaps, when j + 1 < k. Moved
// courses count where they now are for the courses after them, so two moved courses keep
// their stacking. The sets are then rebuilt from set_of_course (empty ones dropped).
void MoveCoursesEarlier(const std::vector<int>& ply_of, SetOverlaps& overlaps,
                        PrecedenceNetwork& net) {
  const std::size_t n = net.set_of_course.size();
  std::vector<int> order(n);
  for (std::size_t c = 0; c < n; ++c) order[c] = static_cast<int>(c);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return net.set_of_course[static_cast<std::size_t>(a)] <
           net.set_of_course[static_cast<std::size_t>(b)];
  });
  for (const int c : order) {
    const int k = net.set_of_course[static_cast<std::size_t>(c)];
    int target = 0;
    for (int j = k - 1; j >= 0; --j) {
      int blocker = -1;
      if (overlaps.Overlaps(c, static_cast<std::size_t>(j), &blocker)) {
        target = j + 1;
        net.blocker_of_course[static_cast<std::size_t>(c)] = blocker;
        break;
      }
    }
    if (target >= k) continue;
    net.set_of_course[static_cast<std::size_t>(c)] = target;
    overlaps.Insert(c, static_cast<std::size_t>(target));
  }
  for (auto& s : net.sets) s.courses.clear();
  for (std::size_t c = 0; c < n; ++c)
    net.sets[static_cast<std::size_t>(net.set_of_course[c])].courses.push_back(static_cast<int>(c));
  for (auto& s : net.sets) {
    s.plies.clear();
    for (const int c : s.courses) {
      const int p = ply_of[static_cast<std::size_t>(c)];
      if (std::find(s.plies.begin(), s.plies.end(), p) == s.plies.end()) s.plies.push_back(p);
    }
  }
  net.sets.erase(std::remove_if(net.sets.begin(), net.sets.end(),
                                [](const PrecedenceSet& s) { return s.courses.empty(); }),
                 net.sets.end());
  for (std::size_t k = 0; k < net.sets.size(); ++k)
    for (const int c : net.sets[k].courses)
      net.set_of_course[static_cast<std::size_t>(c)] = static_cast<int>(k);
}

}  // namespace

PrecedenceNetwork BuildPrecedence(const geom::Surface& surface, const program::AfpProgram& program,
                                  const std::vector<CourseFootprint>& footprints,
                                  const PrecedenceOptions& options) {
  PrecedenceNetwork net;
  const std::size_t n = program.courses.size();
  net.set_of_course.assign(n, -1);
  net.blocker_of_course.assign(n, -1);
  const std::vector<int> ply_of = PlyOfCourse(program);
  SetOverlaps overlaps(surface, footprints, ply_of, options.min_overlap_mm2);
  JoinPliesIntoSets(program, overlaps, net);
  if (options.course_level) MoveCoursesEarlier(ply_of, overlaps, net);
  return net;
}

bool RespectsPrecedence(const geom::Surface& surface, const program::AfpProgram& program,
                        const std::vector<CourseFootprint>& footprints,
                        const std::vector<program::CourseVisit>& order, double min_overlap_mm2,
                        int* first_violation) {
  // Lay the courses in `order`; a course laid now that overlaps one already laid which the
  // programme lays after it (another ply) would put material under what the design has on top.
  const std::vector<int> ply_of = PlyOfCourse(program);
  detail::QuadGrid laid(surface, footprints, CellSize(footprints));
  std::vector<int> laid_unknown;  // laid courses whose footprint is incomplete
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int c = order[i].course;
    bool bad = false;
    auto skip = [&](int other) {
      return other < c ||
             ply_of[static_cast<std::size_t>(other)] == ply_of[static_cast<std::size_t>(c)];
    };
    if (!footprints[static_cast<std::size_t>(c)].ok) {
      // Unknown footprint: it must keep its place among the courses of other plies.
      for (std::size_t j = 0; j < i && !bad; ++j) bad = !skip(order[j].course);
      laid_unknown.push_back(c);
    } else {
      laid.Query(c, skip, [&](int, double area) { bad = bad || area > min_overlap_mm2; });
      for (const int u : laid_unknown) bad = bad || !skip(u);
    }
    if (bad) {
      if (first_violation != nullptr) *first_violation = static_cast<int>(i);
      return false;
    }
    laid.Insert(c);
  }
  return true;
}

}  // namespace stitchsim::planner
