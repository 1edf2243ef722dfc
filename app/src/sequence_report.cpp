// The report of `stitchsim sequence` (sequence_run.h, docs/sequence.md "Report").
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>

#include "cli_common.h"
#include "sequence_run.h"

namespace stitchsim::app {
namespace {

using nlohmann::json;

json CostsJson(const Costs& c) { return json{{"axes", c[0]}, {"time_s", c[1]}, {"tool_mm", c[2]}}; }

Costs Sum(const Costs& a, const Costs& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }

double Reduction(double before, double after) {
  return before > 0.0 ? 100.0 * (before - after) / before : 0.0;
}

// Signed change in per cent, for people ("-10.5 %" is a reduction).
double Change(double before, double after) { return -Reduction(before, after); }

}  // namespace

void WriteSequenceJson(const SequenceOutcome& o, const program::AfpProgram& program,
                       std::ostream& out) {
  json j;
  j["stitchsim_sequence"] = 1;
  j["program"] = o.program_file;
  j["scene"] = o.scene_file;
  j["output"] = o.output_file;
  j["cost"] = MeasureName(o.measure);
  j["solver"] = o.solver;
  j["bidirectional"] = o.bidirectional;
  j["return_home"] = o.return_home;
  j["course_level"] = o.course_level;
  j["seconds"] = o.seconds;
  json sets = json::array();
  for (std::size_t k = 0; k < o.sets.size(); ++k) {
    const SetOutcome& s = o.sets[k];
    sets.push_back(json{
        {"set", k + 1},
        {"plies", s.plies},
        {"courses", s.courses.size()},
        {"solver", s.solver},
        {"seconds", s.seconds},
        {"iterations", s.iterations},
        {"kept_original", s.kept_original},
        {"original_cost", s.original_cost},
        {"cost", s.cost},
        {"optimum", s.optimum ? json(*s.optimum) : json(nullptr)},
        {"gap_pct", s.optimum && *s.optimum > 0.0 ? json(100.0 * (s.cost - *s.optimum) / *s.optimum)
                                                  : json(nullptr)},
        {"offpart_before", CostsJson(s.offpart_before)},
        {"offpart_after", CostsJson(s.offpart_after)}});
  }
  j["sets"] = sets;
  json totals;
  totals["offpart_before"] = CostsJson(o.offpart_before);
  totals["offpart_after"] = CostsJson(o.offpart_after);
  totals["layup"] = CostsJson(o.layup);
  totals["total_before"] = CostsJson(Sum(o.offpart_before, o.layup));
  totals["total_after"] = CostsJson(Sum(o.offpart_after, o.layup));
  totals["flown_tool_mm"] = json{{"offpart_before", o.flown_offpart_before_mm},
                                 {"offpart_after", o.flown_offpart_after_mm},
                                 {"layup", o.layup[2]},
                                 {"total_before", o.flown_offpart_before_mm + o.layup[2]},
                                 {"total_after", o.flown_offpart_after_mm + o.layup[2]}};
  j["totals"] = totals;
  json order = json::array();
  for (const auto& v : o.after) {
    const auto& c = program.courses[static_cast<std::size_t>(v.course)];
    order.push_back(json{{"ply", c.ply},
                         {"course", c.number},
                         {"reversed", v.reversed},
                         {"set", o.set_of_course[static_cast<std::size_t>(v.course)] + 1}});
  }
  j["order"] = order;
  out << j.dump(1) << '\n';
}

void PrintSequenceSummary(const SequenceOutcome& o) {
  std::printf("%s: %zu courses in %zu precedence sets; cost %s, solver %s%s%s -> %s (%.2f s)\n",
              o.program_file.c_str(), o.after.size(), o.sets.size(), MeasureName(o.measure),
              o.solver.c_str(), o.bidirectional ? ", bidirectional" : "",
              o.return_home ? ", return home" : "", o.output_file.c_str(), o.seconds);
  for (std::size_t k = 0; k < o.sets.size(); ++k) {
    const SetOutcome& s = o.sets[k];
    std::string plies;
    for (const int p : s.plies) plies += (plies.empty() ? "" : ",") + std::to_string(p);
    std::printf("  set %zu (plies %s, %zu courses): off-part %s %.4g -> %.4g (%+.1f %%)%s\n", k + 1,
                plies.c_str(), s.courses.size(), MeasureName(o.measure),
                s.offpart_before[static_cast<std::size_t>(o.measure)],
                s.offpart_after[static_cast<std::size_t>(o.measure)],
                Change(s.offpart_before[static_cast<std::size_t>(o.measure)],
                       s.offpart_after[static_cast<std::size_t>(o.measure)]),
                s.kept_original ? " (programme order kept: the solver found nothing cheaper)" : "");
    if (s.optimum)
      std::printf("    set cost %.6g, optimum %.6g (exact): %.3f %% above\n", s.cost, *s.optimum,
                  *s.optimum > 0.0 ? 100.0 * (s.cost - *s.optimum) / *s.optimum : 0.0);
  }
  for (std::size_t mi = 0; mi < 3; ++mi) {
    const Measure m = kMeasures[mi];
    const double tb = o.offpart_before[mi] + o.layup[mi], ta = o.offpart_after[mi] + o.layup[mi];
    std::printf("  %-5s off-part %.6g -> %.6g%s%s (%+.1f %%), total %.6g -> %.6g (%+.1f %%)\n",
                MeasureName(m), o.offpart_before[mi], o.offpart_after[mi],
                *MeasureUnit(m) != '\0' ? " " : "", MeasureUnit(m),
                Change(o.offpart_before[mi], o.offpart_after[mi]), tb, ta, Change(tb, ta));
  }
  const double fb = o.flown_offpart_before_mm, fa = o.flown_offpart_after_mm, l = o.layup[2];
  std::printf(
      "  flown tool path: off-part %.1f -> %.1f mm (%+.1f %%), total %.1f -> %.1f mm "
      "(%+.1f %%)\n",
      fb, fa, Change(fb, fa), fb + l, fa + l, Change(fb + l, fa + l));
}

bool ReadOrderFile(const std::string& file, const program::AfpProgram& program,
                   std::vector<program::CourseVisit>& order) {
  std::ifstream in(file);
  if (!in) {
    PrintError("io-missing-file", "cannot read order file " + file);
    return false;
  }
  const json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("order") || !j.at("order").is_array()) {
    PrintError("sequence-bad-order", file + ": not JSON with an \"order\" array");
    return false;
  }
  std::map<std::pair<int, int>, int> index;
  for (std::size_t c = 0; c < program.courses.size(); ++c)
    index[{program.courses[c].ply, program.courses[c].number}] = static_cast<int>(c);
  std::vector<char> seen(program.courses.size(), 0);
  const json& arr = j.at("order");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json& e = arr.at(i);
    const std::string where = file + ": order[" + std::to_string(i) + "]";
    if (!e.is_object() || !e.contains("ply") || !e.contains("course") ||
        !e.at("ply").is_number_integer() || !e.at("course").is_number_integer() ||
        (e.contains("reversed") && !e.at("reversed").is_boolean())) {
      PrintError("sequence-bad-order", where + ": wants {ply, course, reversed}");
      return false;
    }
    const auto it = index.find({e.at("ply").get<int>(), e.at("course").get<int>()});
    if (it == index.end() || seen[static_cast<std::size_t>(it->second)]) {
      PrintError("sequence-bad-order", where + ": " +
                                           (it == index.end() ? "no such course in the programme"
                                                              : "course given twice"));
      return false;
    }
    seen[static_cast<std::size_t>(it->second)] = 1;
    order.push_back({it->second, e.value("reversed", false)});
  }
  if (order.size() != program.courses.size()) {
    PrintError("sequence-bad-order", file + ": " + std::to_string(order.size()) + " of " +
                                         std::to_string(program.courses.size()) +
                                         " courses given; every course exactly once");
    return false;
  }
  return true;
}

}  // namespace stitchsim::app
