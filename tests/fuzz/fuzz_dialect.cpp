// Fuzz target: the dialect loader (models/dialect/*.yaml as text).
// Properties: only "dialect-*" diagnostics; a loaded dialect is valid, and a fixed programme
// written in it reads back clean and is a write -> parse -> write fixed point.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::fuzz {
namespace {

using program::Axis;
using program::Block;

// A short programme touching every word kind the writer emits.
std::vector<Block> SampleBlocks(const program::Dialect& dialect) {
  std::vector<Block> blocks(4);
  blocks[0].units = LengthUnit::kMillimetre;
  blocks[0].absolute = true;
  blocks[0].comment = "fuzz";
  blocks[1].motion = program::Motion::kRapid;
  for (std::size_t i = 0; i < program::kAxisCount; ++i) {
    blocks[1].axes[i] = 10.25 * static_cast<double>(i) - 31.5;
  }
  blocks[1].tool = dialect.tools.empty() ? 1 : dialect.tools.front().number;
  blocks[1].m_codes = {dialect.m.tool_change};
  blocks[2].block_number = 20;
  blocks[2].motion = program::Motion::kFeed;
  blocks[2].feed = 1500.125;
  blocks[2][Axis::kX] = 123.456789;
  blocks[2][Axis::kDrive] = 4.98;
  blocks[2].m_codes = {dialect.m.stitch_on};
  blocks[3].m_codes = {dialect.m.stitch_off, dialect.m.program_end};
  return blocks;
}

void CheckDialectInUse(const program::Dialect& dialect) {
  DiagnosticSink valid;
  Require(program::ValidateDialect(dialect, "fuzz.yaml", valid),
          "LoadDialectFromString returned a dialect ValidateDialect rejects", &valid);
  const std::string written = program::WriteProgramString(SampleBlocks(dialect), dialect);
  DiagnosticSink sink;
  const auto blocks = program::ParseString(written, dialect, "rt.nc", sink);
  Require(!sink.HasErrors(),
          "a programme written in a valid dialect does not read back:\n" + written, &sink);
  Require(program::WriteProgramString(blocks, dialect) == written,
          "write -> parse -> write is not a fixed point in this dialect:\n" + written);
}

}  // namespace
}  // namespace stitchsim::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stitchsim;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  DiagnosticSink sink;
  const auto dialect = program::LoadDialectFromString(text, "fuzz.yaml", sink);
  fuzz::RequireCodes(sink, {"dialect-"});
  fuzz::Require(dialect.has_value() == !sink.HasErrors(),
                "a dialect came back with errors, or none without one", &sink);
  if (dialect) fuzz::CheckDialectInUse(*dialect);
  return 0;
}
