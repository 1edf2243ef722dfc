// Fuzz target: the trace file reader (`stitchsim recheck`). TraceFileReader takes a path, so
// each input is written to a scratch file first.
// Properties: a bad file is an error naming the file and a byte offset, never a crash or a
// hang; a file that reads replays records whose body indices are in the header's table.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "stitchsim/trace/trace_file.h"

namespace stitchsim::fuzz {
namespace {

// Checks what a trace that reads hands to its sink.
class CheckingSink : public trace::TraceSink {
 public:
  explicit CheckingSink(const trace::CellDescription& cell) : bodies_(cell.bodies.size()) {}
  void OnLine(const trace::LineRecord&) override {}
  void OnSample(const trace::TraceSample& s) override {
    const trace::SampleCollision& c = s.collision;
    for (const trace::Contact& k : c.contacts) {
      Require(InTable(k.body_a) && InTable(k.body_b), "contact body outside the table");
    }
    Require(c.clearance_body_a == -1 || InTable(c.clearance_body_a), "clearance body outside");
  }

 private:
  bool InTable(int i) const { return i >= 0 && static_cast<std::size_t>(i) < bodies_; }
  std::size_t bodies_;
};

void RequireWhere(const std::string& error, const std::string& path) {
  Require(error.rfind(path + ": ", 0) == 0, "a trace error without the file: " + error);
}

}  // namespace
}  // namespace stitchsim::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stitchsim;
  const auto path = fuzz::WriteScratch("run.trace", data, size);
  std::string error;
  const auto reader = trace::TraceFileReader::Open(path, error);
  if (!reader) {
    fuzz::RequireWhere(error, path.string());
    return 0;
  }
  fuzz::CheckingSink sink(reader->Header().cell);
  trace::TraceFileSummary summary;
  if (!reader->Replay(sink, summary, error)) {
    fuzz::RequireWhere(error, path.string());
    fuzz::Require(error.find(": byte ") != std::string::npos, "a bad record without its offset");
  }
  return 0;
}
