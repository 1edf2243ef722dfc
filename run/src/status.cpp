#include "stitchsim/run/status.h"

namespace stitchsim::run {

void ToolError(DiagnosticSink& sink, std::string code, std::string message) {
  sink.Error(std::move(code), {"stitchsim", 0, 0}, std::move(message));
}

bool Forward(const DiagnosticSink& from, DiagnosticSink& to) {
  for (const Diagnostic& d : from.Diagnostics()) to.Report(d);
  return from.HasErrors();
}

}  // namespace stitchsim::run
