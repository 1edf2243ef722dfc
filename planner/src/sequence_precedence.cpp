// The precedence network of an AFP programme (sequence_precedence.h, docs/sequence.md).
#include "stitchsim/planner/sequence_precedence.h"

#include <algorithm>

#include "sequence_grid.h"

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

}  // namespace

PrecedenceNetwork BuildPrecedence(const geom::Surface& surface, const program::AfpProgram& program,
                                  const std::vector<CourseFootprint>& footprints,
                                  const PrecedenceOptions& options) {
  PrecedenceNetwork net;
  const std::size_t n = program.courses.size();
  net.set_of_course.assign(n, -1);
  net.blocker_of_course.assign(n, -1);
  const std::vector<int> ply_of = PlyOfCourse(program);
  const double cell = CellSize(footprints);
  // One grid per set (course-level moves query earlier sets).
  std::vector<detail::QuadGrid> grids;
  // A course whose footprint is incomplete (a tow walk left the surface) is taken to overlap
  // every course of another ply: it can never join or move.
  auto unknown = [&](int c) { return !footprints[static_cast<std::size_t>(c)].ok; };
  std::vector<char> set_has_unknown;
  auto overlaps_set = [&](int c, std::size_t set, int* blocker) {
    if (unknown(c) || set_has_unknown[set]) return true;
    bool found = false;
    grids[set].Query(
        c,
        [&](int other) {
          return ply_of[static_cast<std::size_t>(other)] == ply_of[static_cast<std::size_t>(c)];
        },
        [&](int other, double area) {
          if (area > options.min_overlap_mm2 || unknown(other)) {
            if (!found && blocker != nullptr) *blocker = other;
            found = true;
          }
        });
    return found;
  };
  for (std::size_t pi = 0; pi < program.plies.size(); ++pi) {
    const auto& courses = program.plies[pi].courses;
    bool joins = !net.sets.empty();
    for (std::size_t k = 0; joins && k < courses.size(); ++k) {
      int blocker = -1;
      if (overlaps_set(courses[k], net.sets.size() - 1, &blocker)) {
        joins = false;
        net.blocker_of_course[static_cast<std::size_t>(courses[k])] = blocker;
      }
    }
    if (!joins) {
      net.sets.emplace_back();
      grids.emplace_back(surface, footprints, cell);
      set_has_unknown.push_back(0);
    }
    PrecedenceSet& set = net.sets.back();
    set.plies.push_back(static_cast<int>(pi));
    for (const int c : courses) {
      set.courses.push_back(c);
      net.set_of_course[static_cast<std::size_t>(c)] = static_cast<int>(net.sets.size()) - 1;
      grids.back().Insert(c);
      if (unknown(c)) set_has_unknown.back() = 1;
    }
  }
  if (options.course_level) {
    // In programme order: a course of set k moves to set j + 1, j the latest earlier set holding
    // a course (of another ply) it overlaps, when j + 1 < k. Moved courses count where they
    // now are for the courses after them, so two moved courses keep their stacking.
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
        if (overlaps_set(c, static_cast<std::size_t>(j), &blocker)) {
          target = j + 1;
          net.blocker_of_course[static_cast<std::size_t>(c)] = blocker;
          break;
        }
      }
      if (target >= k) continue;
      net.set_of_course[static_cast<std::size_t>(c)] = target;
      grids[static_cast<std::size_t>(target)].Insert(c);
      if (unknown(c)) set_has_unknown[static_cast<std::size_t>(target)] = 1;
    }
    for (auto& s : net.sets) s.courses.clear();
    for (std::size_t c = 0; c < n; ++c)
      net.sets[static_cast<std::size_t>(net.set_of_course[c])].courses.push_back(
          static_cast<int>(c));
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
