#include "stitchsim/common/diagnostics.h"

#include <utility>

namespace stitchsim {

std::string FormatDiagnostic(const Diagnostic& d) {
  std::string out = d.location.file.empty() ? std::string("<input>") : d.location.file;
  if (d.location.line > 0) {
    out += ":" + std::to_string(d.location.line);
    if (d.location.column > 0) out += ":" + std::to_string(d.location.column);
  }
  switch (d.severity) {
    case Severity::kError:
      out += ": error[";
      break;
    case Severity::kWarning:
      out += ": warning[";
      break;
    case Severity::kNote:
      out += ": note[";
      break;
  }
  out += d.code + "]: " + d.message;
  return out;
}

void DiagnosticSink::Report(Diagnostic d) {
  if (d.severity == Severity::kError) ++error_count_;
  diagnostics_.push_back(std::move(d));
}

void DiagnosticSink::Error(std::string code, SourceLocation where, std::string message) {
  Report({Severity::kError, std::move(code), std::move(where), std::move(message)});
}

void DiagnosticSink::Warning(std::string code, SourceLocation where, std::string message) {
  Report({Severity::kWarning, std::move(code), std::move(where), std::move(message)});
}

void BoundedDiagnosticSink::Report(Diagnostic d) {
  if (Diagnostics().size() >= limit_) {
    ++dropped_;
    if (d.severity == Severity::kError && !HasErrors()) DiagnosticSink::Report(std::move(d));
    return;
  }
  DiagnosticSink::Report(std::move(d));
}

}  // namespace stitchsim
