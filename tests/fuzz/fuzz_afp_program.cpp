// Fuzz target: an AFP programme read back by course (program/afp_program.h, what `stitchsim
// sequence` runs first), then written again with every other course laid backwards.
// Properties: only located "gcode-*" / "sequence-*" diagnostics inside the programme; a
// programme that reads clean has courses of at least two stations; reversing a course twice
// gives its masks back; the written programme reads back clean with the same courses and
// laying moves (the writer restores each lay-up's entry state, whatever the input was).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_support.h"
#include "stitchsim/program/afp_program.h"

namespace stitchsim::fuzz {
namespace {

constexpr int kTows = 16;

std::optional<program::AfpProgram> Read(const std::string& text, const char* name,
                                        DiagnosticSink& sink) {
  std::istringstream in(text);
  return program::ReadAfpProgram(in, program::Dialect::Default(), name, sink);
}

void Check(const std::string& text) {
  BoundedDiagnosticSink sink(64);
  const auto p = Read(text, "fuzz.nc", sink);
  RequireCodes(sink, {"gcode-", "sequence-"});
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  for (const Diagnostic& d : sink.Diagnostics())
    Require(d.location.line >= 1 && d.location.line <= lines + 1,
            "diagnostic line outside the programme: " + FormatDiagnostic(d), &sink);
  Require(p.has_value() == !sink.HasErrors(), "a result despite errors, or none without", &sink);
  if (!p) return;
  // A tow the head does not have cannot be mirrored: `sequence` refuses such a programme
  // (sequence-tow-beyond-head) before writing; so does this property.
  for (const auto& course : p->courses)
    for (const auto& st : course.stations)
      if ((st.tows >> kTows) != 0 && (st.tows >> kTows) != (~std::uint64_t{0} >> kTows)) return;
  std::vector<program::CourseVisit> order;
  for (std::size_t c = 0; c < p->courses.size(); ++c) {
    const auto& course = p->courses[c];
    Require(course.stations.size() >= 2, "a course with fewer than two stations");
    Require(course.layup_first_line <= course.layup_last_line, "lay-up lines out of order");
    program::AfpCourse twice = course;
    twice.stations = program::ReversedStations(course, kTows);
    const auto back = program::ReversedStations(twice, kTows);
    for (std::size_t k = 0; k + 1 < back.size(); ++k)
      Require(back[k].tows ==
                  program::MirrorTows(program::MirrorTows(course.stations[k].tows, kTows), kTows),
              "reversing twice changed a tow mask");
    order.push_back({static_cast<int>(c), c % 2 == 1});
  }
  std::ostringstream out;
  // The least off-part motion there is: a rapid onto each lay-up start.
  const program::OffPartSource onto = [&](std::size_t i) {
    std::vector<program::OffPartBlock> b;
    if (i < order.size()) {
      program::OffPartBlock to;
      to.pose = program::LayupStartPose(p->courses[static_cast<std::size_t>(order[i].course)],
                                        order[i].reversed);
      b.push_back(to);
    }
    return b;
  };
  program::WriteAfpProgram(out, *p, program::Dialect::Default(), order, onto,
                           program::AfpWriteOptions{kTows, {{"fuzz", "1"}}});
  DiagnosticSink again;
  const auto q = Read(out.str(), "written.nc", again);
  Require(q.has_value(), "the written programme does not read back:\n" + out.str(), &again);
  Require(q->courses.size() == p->courses.size(), "course count changed by write -> read");
  // The same moves lay tows (a lay-up whose last line also moves away is read with that move;
  // laid backwards the move comes first, before any tow, and reads as approach).
  auto laying = [](const program::AfpCourse& c) {
    int n = 0;
    for (std::size_t k = 0; k + 1 < c.stations.size(); ++k) n += c.stations[k].tows != 0 ? 1 : 0;
    return n;
  };
  for (std::size_t i = 0; i < order.size(); ++i)
    Require(laying(q->courses[i]) == laying(p->courses[static_cast<std::size_t>(order[i].course)]),
            "laying moves changed by write -> read:\n" + out.str());
}

}  // namespace
}  // namespace stitchsim::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stitchsim::fuzz::Check(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
