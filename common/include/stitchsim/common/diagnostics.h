#pragma once
// Diagnostics for untrusted input (scenes, models, programmes): collected by a sink, never
// printed from inside a library. Format: "file:line:col: error[CODE]: message".

#include <cstddef>
#include <string>
#include <vector>

namespace stitchsim {

enum class Severity { kError, kWarning, kNote };

/// Where in an input a diagnostic points. line/column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

/// One finding about bad input. `code` is stable and kebab-case (e.g. "scene-unknown-key").
struct Diagnostic {
  Severity severity = Severity::kError;
  std::string code;
  SourceLocation location;
  std::string message;
};

/// "file:line:col: error[code]: message" (line/col omitted when unknown).
std::string FormatDiagnostic(const Diagnostic& d);

/// Collects diagnostics; libraries report here and the caller decides what to print.
class DiagnosticSink {
 public:
  virtual ~DiagnosticSink() = default;
  virtual void Report(Diagnostic d);

  void Error(std::string code, SourceLocation where, std::string message);
  void Warning(std::string code, SourceLocation where, std::string message);

  bool HasErrors() const { return error_count_ > 0; }
  std::size_t ErrorCount() const { return error_count_; }
  const std::vector<Diagnostic>& Diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
  std::size_t error_count_ = 0;
};

/// Stops collecting after `limit` diagnostics (keeps huge bad inputs from flooding memory).
class BoundedDiagnosticSink : public DiagnosticSink {
 public:
  explicit BoundedDiagnosticSink(std::size_t limit) : limit_(limit) {}
  void Report(Diagnostic d) override;
  std::size_t Dropped() const { return dropped_; }

 private:
  std::size_t limit_;
  std::size_t dropped_ = 0;
};

}  // namespace stitchsim
