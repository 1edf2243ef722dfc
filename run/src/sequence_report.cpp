// The report of `stitchsim sequence` and its order reader (sequence_report.h).
#include "stitchsim/run/sequence_report.h"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>

namespace stitchsim::run {
namespace {

using nlohmann::json;

json SequenceCostsJson(const Costs& c) {
  return json{{"axes", c[0]}, {"time_s", c[1]}, {"tool_mm", c[2]}, {"timed_s", c[3]}};
}

Costs SumOfCosts(const Costs& a, const Costs& b) {
  Costs sum{};
  for (std::size_t m = 0; m < sum.size(); ++m) sum[m] = a[m] + b[m];
  return sum;
}

json OptionalJson(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

json SequenceSetJson(std::size_t k, const SetOutcome& s) {
  return json{{"set", k + 1},
              {"plies", s.plies},
              {"courses", s.courses.size()},
              {"solver", s.solver},
              {"status", planner::ToString(s.status)},
              {"seconds", s.seconds},
              {"iterations", s.iterations},
              {"kept_original", s.kept_original},
              {"original_cost", s.original_cost},
              {"cost", s.cost},
              {"optimum", OptionalJson(s.optimum)},
              {"bound", OptionalJson(s.bound)},
              {"bound_method", s.bound ? json(s.bound_method) : json(nullptr)},
              {"bound_seconds", s.bound_seconds},
              {"gap", OptionalJson(s.gap)},
              {"offpart_before", SequenceCostsJson(s.offpart_before)},
              {"offpart_after", SequenceCostsJson(s.offpart_after)}};
}

json SequencePlyJson(const PlyOutcome& p) {
  return json{{"ply", p.ply},
              {"comment", p.comment},
              {"courses", p.courses},
              {"offpart_before", SequenceCostsJson(p.offpart_before)},
              {"offpart_after", SequenceCostsJson(p.offpart_after)},
              {"flown_tool_mm", json{{"offpart_before", p.flown_before_mm},
                                     {"offpart_after", p.flown_after_mm},
                                     {"layup", p.layup_mm},
                                     {"total_before", p.flown_before_mm + p.layup_mm},
                                     {"total_after", p.flown_after_mm + p.layup_mm}}}};
}

json SequenceTotalsJson(const SequenceOutcome& o) {
  json totals;
  totals["offpart_before"] = SequenceCostsJson(o.offpart_before);
  totals["offpart_after"] = SequenceCostsJson(o.offpart_after);
  totals["layup"] = SequenceCostsJson(o.layup);
  // The sets' bounds and costs in the chosen measure, each set from where it began as laid.
  double bound = 0.0, cost = 0.0;
  bool bounded = true;
  for (const SetOutcome& s : o.sets) {
    bounded = bounded && s.bound.has_value();
    bound += s.bound.value_or(0.0);
    cost += s.cost;
  }
  totals["bound"] = bounded ? json(bound) : json(nullptr);
  totals["cost"] = cost;
  totals["total_before"] = SequenceCostsJson(SumOfCosts(o.offpart_before, o.layup));
  totals["total_after"] = SequenceCostsJson(SumOfCosts(o.offpart_after, o.layup));
  totals["flown_tool_mm"] = json{{"offpart_before", o.flown_offpart_before_mm},
                                 {"offpart_after", o.flown_offpart_after_mm},
                                 {"layup", o.layup[2]},
                                 {"total_before", o.flown_offpart_before_mm + o.layup[2]},
                                 {"total_after", o.flown_offpart_after_mm + o.layup[2]}};
  return totals;
}

// One entry of an order file mapped onto the programme's courses; error set when malformed,
// unknown or given twice.
std::optional<int> OrderEntryCourse(const json& e, const std::string& where,
                                    const std::map<std::pair<int, int>, int>& index,
                                    const std::vector<char>& seen, SequenceError& error) {
  if (!e.is_object() || !e.contains("ply") || !e.contains("course") ||
      !e.at("ply").is_number_integer() || !e.at("course").is_number_integer() ||
      (e.contains("reversed") && !e.at("reversed").is_boolean())) {
    error = {"sequence-bad-order", where + ": wants {ply, course, reversed}"};
    return std::nullopt;
  }
  const auto it = index.find({e.at("ply").get<int>(), e.at("course").get<int>()});
  if (it == index.end() || seen[static_cast<std::size_t>(it->second)]) {
    error = {"sequence-bad-order",
             where + ": " +
                 (it == index.end() ? "no such course in the programme" : "course given twice")};
    return std::nullopt;
  }
  return it->second;
}

}  // namespace

json SequenceReportJson(const SequenceOutcome& o, const program::AfpProgram& program) {
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
  j["precedence"] = o.precedence;
  j["joined_saving"] = o.joined_saving;
  j["kept_programme"] = o.kept_programme;
  j["seconds"] = o.seconds;
  json sets = json::array();
  for (std::size_t k = 0; k < o.sets.size(); ++k) sets.push_back(SequenceSetJson(k, o.sets[k]));
  j["sets"] = sets;
  j["totals"] = SequenceTotalsJson(o);
  json order = json::array();
  for (const auto& v : o.after) {
    const auto& c = program.courses[static_cast<std::size_t>(v.course)];
    order.push_back(json{{"ply", c.ply},
                         {"course", c.number},
                         {"reversed", v.reversed},
                         {"set", o.set_of_course[static_cast<std::size_t>(v.course)] + 1}});
  }
  j["order"] = order;
  json plies = json::array();
  for (const PlyOutcome& p : o.plies) plies.push_back(SequencePlyJson(p));
  j["plies"] = plies;
  return j;
}

void WriteSequenceJson(const SequenceOutcome& o, const program::AfpProgram& program,
                       std::ostream& out) {
  out << SequenceReportJson(o, program).dump(1) << '\n';
}

std::optional<std::vector<program::CourseVisit>> ReadOrderFile(const std::string& file,
                                                               const program::AfpProgram& program,
                                                               SequenceError& error) {
  std::ifstream in(file);
  if (!in) {
    error = {"io-missing-file", "cannot read order file " + file};
    return std::nullopt;
  }
  const json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("order") || !j.at("order").is_array()) {
    error = {"sequence-bad-order", file + ": not JSON with an \"order\" array"};
    return std::nullopt;
  }
  std::map<std::pair<int, int>, int> index;
  for (std::size_t c = 0; c < program.courses.size(); ++c)
    index[{program.courses[c].ply, program.courses[c].number}] = static_cast<int>(c);
  std::vector<char> seen(program.courses.size(), 0);
  std::vector<program::CourseVisit> order;
  const json& arr = j.at("order");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json& e = arr.at(i);
    const std::string where = file + ": order[" + std::to_string(i) + "]";
    const std::optional<int> course = OrderEntryCourse(e, where, index, seen, error);
    if (!course) return std::nullopt;
    seen[static_cast<std::size_t>(*course)] = 1;
    order.push_back({*course, e.value("reversed", false)});
  }
  if (order.size() != program.courses.size()) {
    error = {"sequence-bad-order", file + ": " + std::to_string(order.size()) + " of " +
                                       std::to_string(program.courses.size()) +
                                       " courses given; every course exactly once"};
    return std::nullopt;
  }
  return order;
}

}  // namespace stitchsim::run
