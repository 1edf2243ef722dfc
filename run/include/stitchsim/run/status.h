#pragma once
// What a run function that writes files or draws reports back instead of printing: ok, or an
// error with a stable code and a message (the CLI prints it as
// "stitchsim: error[code]: message"), or an error already reported into the caller's
// DiagnosticSink.

#include <string>
#include <utility>

namespace stitchsim::run {

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

}  // namespace stitchsim::run
