#pragma once
// Dialect validation shared by ValidateDialect and the YAML loader (which knows where each
// key was written and so can point diagnostics at it).

#include <functional>
#include <string>
#include <string_view>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/program/dialect.h"

namespace stitchsim::program::detail {

/// Maps a key path such as "letters.drive" or "m_codes.stitch_on" to where it was written.
using KeyLocator = std::function<SourceLocation(std::string_view key_path)>;

bool ValidateDialectAt(const Dialect& dialect, const KeyLocator& locate, DiagnosticSink& sink);

}  // namespace stitchsim::program::detail
