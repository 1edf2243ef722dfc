#pragma once
// The user code library of the raster planner (docs/raster.md): named blocks of user M codes
// inserted at events (e.g. needle cooling every N stitches). Read from YAML through the scene
// YAML reader: unknown keys, bad values and codes outside the dialect's user range are
// `library-...` diagnostics at their file:line:col.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/program/dialect.h"

namespace stitchsim::planner {

/// A named block of user codes inserted at an event (e.g. needle cooling M110).
struct UserCodeBlock {
  enum class Event { kEveryStitches, kRowStart, kBeforeJump };
  std::string name;
  Event event = Event::kEveryStitches;
  long every_stitches = 0;   ///< kEveryStitches: after every this many stitches (per programme)
  std::vector<int> m_codes;  ///< user macros, inside the dialect's user range
  std::optional<int> param;  ///< P word, if any
};

struct UserCodeLibrary {
  std::vector<UserCodeBlock> blocks;
};

/// Parses a code library from YAML text; `file_name` names it in diagnostics.
std::optional<UserCodeLibrary> ParseUserCodeLibrary(std::string_view yaml,
                                                    const std::string& file_name,
                                                    const program::Dialect& dialect,
                                                    DiagnosticSink& sink);
/// Reads and parses a code library file (a regular file within the YAML size limit).
std::optional<UserCodeLibrary> LoadUserCodeLibrary(const std::filesystem::path& file,
                                                   const program::Dialect& dialect,
                                                   DiagnosticSink& sink);

}  // namespace stitchsim::planner
