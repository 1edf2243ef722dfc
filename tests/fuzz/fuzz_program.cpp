// Fuzz target: the programme reader (streaming parse) and the modal state tracker, as
// `stitchsim check` runs them, then the writer on whatever parsed clean.
// Properties: only located "gcode-*" diagnostics; a clean parse survives write -> parse ->
// write as a fixed point (docs/program-format.md section 8).

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_support.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::fuzz {
namespace {

void CheckStreaming(const std::string& text) {
  BoundedDiagnosticSink sink(64);
  std::istringstream in(text);
  const program::CheckSummary summary =
      program::CheckProgram(in, program::Dialect::Default(), "fuzz.nc", sink);
  RequireCodes(sink, {"gcode-"});
  for (const Diagnostic& d : sink.Diagnostics()) {
    Require(d.location.line >= 1 && d.location.line <= summary.lines + 1,
            "diagnostic line outside the programme: " + FormatDiagnostic(d), &sink);
    Require(d.location.column >= 1, "diagnostic without a column: " + FormatDiagnostic(d), &sink);
  }
  Require(summary.ok == !sink.HasErrors(), "CheckSummary::ok disagrees with the sink", &sink);
}

void CheckRoundTrip(const std::string& text) {
  const program::Dialect& dialect = program::Dialect::Default();
  DiagnosticSink sink;
  const auto blocks = program::ParseString(text, dialect, "fuzz.nc", sink);
  RequireCodes(sink, {"gcode-"});
  if (sink.HasErrors()) return;
  // The first write may round decimals beyond the dialect's; from then on it is a fixed point.
  const std::string written = program::WriteProgramString(blocks, dialect);
  DiagnosticSink again;
  const auto reparsed = program::ParseString(written, dialect, "rt.nc", again);
  Require(!again.HasErrors(), "the writer's text does not parse:\n" + written, &again);
  Require(reparsed.size() == blocks.size(), "block count changed by write -> parse");
  const std::string rewritten = program::WriteProgramString(reparsed, dialect);
  Require(rewritten == written, "write -> parse -> write is not a fixed point:\n" + written);
}

}  // namespace
}  // namespace stitchsim::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  stitchsim::fuzz::CheckStreaming(text);
  stitchsim::fuzz::CheckRoundTrip(text);
  return 0;
}
