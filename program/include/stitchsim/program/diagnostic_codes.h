#pragma once
// Every diagnostic code the programme reader and modal state tracker report. Codes are
// stable: tools and tests match on them. docs/program-format.md explains each one.

#include <span>
#include <string_view>

namespace stitchsim::program {

/// All "gcode-*" codes, in the order the documentation lists them.
std::span<const std::string_view> AllProgramDiagnosticCodes();

/// All "dialect-*" codes the dialect loader reports.
std::span<const std::string_view> AllDialectDiagnosticCodes();

}  // namespace stitchsim::program
