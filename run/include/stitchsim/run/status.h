#pragma once
// How a run ended, and the problems without a file position that a run reports into a sink
// (the CLI prints them as "stitchsim: error[code]: message", as it always has).

#include <string>

#include "stitchsim/common/diagnostics.h"

namespace stitchsim::run {

/// A run's outcome; the values are the CLI's exit codes.
enum class RunStatus {
  kOk = 0,        ///< ran; no error finding
  kFindings = 1,  ///< ran; the cell cannot run the programme (error findings)
  kBadInput = 2,  ///< malformed input, missing or unwritable file (diagnostics in the sink)
  kInternal = 3,  ///< a bug (e.g. a chunk that cannot be reproduced)
};

/// Reports a problem that has no file position: FormatDiagnostic prints it as
/// "stitchsim: error[code]: message".
void ToolError(DiagnosticSink& sink, std::string code, std::string message);

/// Copies every diagnostic of `from` into `to` (a bounded local sink into the caller's);
/// true when `from` holds an error.
bool Forward(const DiagnosticSink& from, DiagnosticSink& to);

}  // namespace stitchsim::run
