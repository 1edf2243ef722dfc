#pragma once
// How run functions report back instead of printing: a step's `Status` (ok, or an error with a
// stable code and a message, or an error already in the caller's DiagnosticSink), a whole
// run's `RunStatus` (its values are the CLI's exit codes), and problems without a file
// position put into a sink. The CLI prints errors as "stitchsim: error[code]: message", as it
// always has.

#include <string>
#include <utility>

#include "stitchsim/common/diagnostics.h"

namespace stitchsim::run {

/// A step that writes files or draws: ok, or why not.
struct Status {
  bool ok = true;
  std::string code;     ///< stable kebab-case code ("io-write"); empty when ok or in the sink
  std::string message;  ///< what went wrong; empty when ok or in the sink

  static Status Ok() { return {}; }
  /// An error the caller reports: `code` and `message`.
  static Status Error(std::string code, std::string message) {
    return {false, std::move(code), std::move(message)};
  }
  /// An error already in the DiagnosticSink the caller passed.
  static Status InSink() { return {false, {}, {}}; }
};

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
