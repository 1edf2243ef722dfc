// `stitchsim check`: parses a programme and tracks its modal state, streaming, and reports
// every problem as file:line:col: error[code]: message. Exit 0 when clean, 2 otherwise.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "cli_common.h"
#include "commands.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/program/modal_state.h"

namespace stitchsim::app {
namespace {

// A huge broken file must not flood the terminal or memory; the first errors are the
// useful ones (later ones often follow from them).
constexpr std::size_t kMaxDiagnostics = 200;

struct CheckArgs {
  std::string program;
  std::string dialect;
};

int RunCheck(const CheckArgs& a) {
  std::optional<program::Dialect> custom;
  if (!a.dialect.empty()) {
    DiagnosticSink sink;
    custom = program::LoadDialect(a.dialect, sink);
    if (PrintDiagnostics(sink) || !custom) return kExitBadInput;
  }
  const program::Dialect& dialect = custom ? *custom : program::Dialect::Default();

  if (!ProgramInputOk(a.program)) return kExitBadInput;
  std::ifstream in(a.program, std::ios::binary);
  if (!in) {
    PrintError("io-missing-file", "cannot open programme " + a.program);
    return kExitBadInput;
  }

  BoundedDiagnosticSink sink(kMaxDiagnostics);
  const program::CheckSummary summary = program::CheckProgram(in, dialect, a.program, sink);
  if (!summary.ok) {
    PrintDiagnostics(sink);
    if (sink.Dropped() > 0) {
      std::cerr << "stitchsim: " << sink.Dropped() << " further diagnostics not shown\n";
    }
    return kExitBadInput;
  }
  // The typed header keys (stitch length, stitch count) as verify reads them: a malformed
  // value is an error here too, not only when the programme is run.
  const std::optional<program::ProgramIdentity> id =
      program::ReadIdentity(summary.header, a.program, sink);
  if (summary.moves == 0) {
    // Parses, but there is nothing to run: no block moves the machine. (A file with no
    // blocks at all is gcode-empty-program, reported by the reader above.)
    sink.Error("program-no-moves", SourceLocation{a.program, 0, 0},
               "the programme has no moves (no block with axis words)");
  }
  if (PrintDiagnostics(sink)) return kExitBadInput;  // warnings alone still pass

  std::string header;
  if (id->scene) header += ", scene " + *id->scene;
  if (id->head) header += ", head " + *id->head;
  for (const char* key : {"path", "mode"}) {
    if (auto v = summary.header.Find(key))
      header += std::string(", ") + key + " " + std::string(*v);
  }
  std::printf("%s: ok: %d lines, %llu blocks, %llu moves%s\n", a.program.c_str(), summary.lines,
              static_cast<unsigned long long>(summary.blocks),
              static_cast<unsigned long long>(summary.moves), header.c_str());
  return kExitOk;
}

}  // namespace

void AddCheckCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Parse a programme and check its modal state (exit 0 clean, 2 on any error)");
  cmd->add_option("program", args->program, "Programme file (.nc)")->required();
  cmd->add_option("--dialect", args->dialect,
                  "Dialect YAML file (default: the built-in dialect, models/dialect/default.yaml)");
  cmd->callback([args, &exit_code] { exit_code = RunCheck(*args); });
}

}  // namespace stitchsim::app
