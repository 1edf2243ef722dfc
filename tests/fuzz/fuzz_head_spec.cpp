// Fuzz target: the head-spec loader (models/heads/*.yaml). LoadHeadSpec takes a path, so each
// input is written to a scratch file first.
// Properties: only "head-*" diagnostics; a spec comes back exactly when no error was reported.

#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "stitchsim/scene/head_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stitchsim;
  const auto path = fuzz::WriteScratch("head.yaml", data, size);
  DiagnosticSink sink;
  const auto head = scene::LoadHeadSpec(path, sink);
  fuzz::RequireCodes(sink, {"head-"});
  fuzz::Require(head.has_value() == !sink.HasErrors(),
                "a head spec came back with errors, or none without one", &sink);
  return 0;
}
