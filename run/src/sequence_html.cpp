// `stitchsim sequence --html`: the page's data and the page (sequence_html.h).
#include "stitchsim/run/sequence_html.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "html_assets.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/html_report.h"
#include "stitchsim/run/sequence_report.h"

namespace stitchsim::run {
namespace {

using nlohmann::json;

// A coordinate for the page, mm rounded to 0.01 (the page draws, it does not measure).
double PageMm(double v) { return std::round(v * 100.0) / 100.0; }

json PagePoints(const std::vector<Eigen::Vector3d>& points) {
  json out = json::array();
  for (const Eigen::Vector3d& p : points)
    out.push_back(json::array({PageMm(p.x()), PageMm(p.y()), PageMm(p.z())}));
  return out;
}

// Index of each course of `program` in `original` by (ply, number); -1 when absent.
std::vector<int> CoursesIn(const program::AfpProgram& program,
                           const program::AfpProgram& original) {
  std::map<std::pair<int, int>, int> index;
  for (std::size_t c = 0; c < original.courses.size(); ++c)
    index[{original.courses[c].ply, original.courses[c].number}] = static_cast<int>(c);
  std::vector<int> out;
  for (const auto& c : program.courses) {
    const auto it = index.find({c.ply, c.number});
    out.push_back(it == index.end() ? -1 : it->second);
  }
  return out;
}

// The programme's stretches with their course mapped into `original` (by ply and number), and
// its visits in laying order (original course index, the lay-up's start as this programme lays
// it: the other end for a course laid backwards).
json PagePath(const program::AfpProgram& program, const program::AfpProgram& original,
              const Eigen::Vector3d& start) {
  const std::vector<int> map = CoursesIn(program, original);
  json stretches = json::array();
  for (const OffPartStretch& s : OffPartStretches(program, start))
    stretches.push_back(
        json{{"course", s.course < 0 ? -1 : map[static_cast<std::size_t>(s.course)]},
             {"length_mm", s.length_mm},
             {"points", PagePoints(s.points)}});
  json visits = json::array();
  for (std::size_t c = 0; c < program.courses.size(); ++c) {
    const Eigen::Vector3d start = program.courses[c].stations.front().pose.translation();
    visits.push_back(json{{"course", map[c]}, {"start", PagePoints({start}).at(0)}});
  }
  return json{{"stretches", std::move(stretches)}, {"visits", std::move(visits)}};
}

}  // namespace

std::vector<OffPartStretch> OffPartStretches(const program::AfpProgram& program,
                                             const Eigen::Vector3d& start) {
  // Lay-up line ranges in line order: a move ending on a line in (first, last] is a lay-up move.
  std::vector<std::pair<int, int>> layups;  // (layup_first_line, course)
  for (std::size_t c = 0; c < program.courses.size(); ++c)
    layups.emplace_back(program.courses[c].layup_first_line, static_cast<int>(c));
  std::sort(layups.begin(), layups.end());
  std::vector<OffPartStretch> out;
  const auto& path = program.tool_path;
  std::size_t next = 0;  // the next lay-up not yet begun
  OffPartStretch cur;
  if (!path.empty() && path.front().point != start) {  // from the start to the first point
    cur.points = {start, path.front().point};
    cur.length_mm = (path.front().point - start).norm();
  }
  auto close = [&](int course) {
    cur.course = course;
    if (cur.points.size() >= 2) out.push_back(std::move(cur));
    cur = OffPartStretch{};
  };
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int line = path[i].line;
    while (next < layups.size() && layups[next].first < line) {
      // The lay-up `next` has begun before this move: the stretch so far led into it.
      close(layups[next].second);
      ++next;
    }
    const bool in_layup =
        next > 0 &&
        line <= program.courses[static_cast<std::size_t>(layups[next - 1].second)].layup_last_line;
    if (in_layup) continue;
    if (cur.points.empty()) cur.points.push_back(path[i - 1].point);
    cur.points.push_back(path[i].point);
    cur.length_mm += (path[i].point - path[i - 1].point).norm();
  }
  while (next < layups.size()) close(layups[next++].second);
  close(-1);
  return out;
}

std::optional<program::AfpProgram> ReadBackSequenced(const SequenceInputs& inputs,
                                                     const SequenceRun& run) {
  std::stringstream text;
  WriteSequencedProgram(inputs, run, text);
  DiagnosticSink sink;
  return program::ReadAfpProgram(text, program::Dialect::Default(), inputs.program.file_name, sink);
}

void FillPlyFlown(const program::AfpProgram& original, const program::AfpProgram& sequenced,
                  const Eigen::Vector3d& start, SequenceOutcome& o) {
  std::map<int, std::size_t> ply_index;
  for (std::size_t p = 0; p < o.plies.size(); ++p) ply_index[o.plies[p].ply] = p;
  auto add = [&](const program::AfpProgram& prog, bool after) {
    for (const OffPartStretch& s : OffPartStretches(prog, start)) {
      const auto& course =
          s.course >= 0 ? prog.courses[static_cast<std::size_t>(s.course)] : prog.courses.back();
      PlyOutcome& ply = o.plies[ply_index.at(course.ply)];
      (after ? ply.flown_after_mm : ply.flown_before_mm) += s.length_mm;
    }
  };
  add(original, false);
  add(sequenced, true);
}

json SequencePageData(const SequenceRun& run, const program::AfpProgram& program) {
  json courses = json::array();
  for (const auto& c : program.courses) {
    std::vector<Eigen::Vector3d> points;
    for (const auto& st : c.stations) points.push_back(st.pose.translation());
    courses.push_back(json{{"ply", c.ply}, {"course", c.number}, {"points", PagePoints(points)}});
  }
  return json{
      {"stitchsim_sequence_page", 1},
      {"report", SequenceReportJson(run.outcome, program)},
      {"courses", std::move(courses)},
      {"before", PagePath(program, program, run.start_mm)},
      {"after", run.sequenced ? PagePath(*run.sequenced, program, run.start_mm) : json(nullptr)}};
}

std::string SequenceHtmlPage(const SequenceRun& run, const program::AfpProgram& program,
                             std::string& error) {
  return HtmlPageOf(SequenceTemplateHtml(), SequenceJs(), {}, SequencePageData(run, program),
                    error);
}

}  // namespace stitchsim::run
