#include "cli_common.h"

#include <iostream>

#include "stitchsim/common/files.h"
#include "stitchsim/planner/plan_status.h"

namespace stitchsim::app {

scene::LoadOptions& SceneLoadOptions() {
  static scene::LoadOptions options;
  return options;
}

void AddScenePathFlag(CLI::App& cmd) {
  cmd.add_flag("--allow-outside-paths", SceneLoadOptions().allow_outside_paths,
               "Let the scene and head spec name files outside their folders and the models "
               "folder (default: refused, docs/scene-format.md)");
}

bool OutputsDistinct(const std::vector<std::pair<std::string, std::string>>& outputs) {
  const std::string err = CheckDistinctOutputs(outputs);
  if (err.empty()) return true;
  PrintError("io-same-output", err);
  return false;
}

bool ProgramInputOk(const std::string& path) {
  const std::string err = CheckStreamInput(path);
  if (err.empty()) return true;
  PrintError("io-missing-file", err);
  return false;
}

bool PrintDiagnostics(const DiagnosticSink& sink) {
  for (const auto& d : sink.Diagnostics()) std::cerr << FormatDiagnostic(d) << '\n';
  return sink.HasErrors();
}

void PrintError(const std::string& code, const std::string& message) {
  std::cerr << "stitchsim: error[" << code << "]: " << message << '\n';
}

std::optional<program::Dialect> DialectOption(const std::string& file) {
  if (file.empty()) return program::Dialect::Default();
  DiagnosticSink sink;
  auto dialect = program::LoadDialect(file, sink);
  if (PrintDiagnostics(sink) || !dialect) return std::nullopt;
  return dialect;
}

int WriteProgramAndCsv(const std::string& program, const std::string& csv,
                       const std::function<void(std::ostream&)>& write_program,
                       const std::function<void(std::ostream&)>& write_csv) {
  std::string err;
  auto program_out = OutputFile::Open(program, err);
  std::unique_ptr<OutputFile> csv_out;
  if (program_out && !csv.empty()) csv_out = OutputFile::Open(csv, err);
  if (!program_out || (!csv.empty() && !csv_out)) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  write_program(program_out->Stream());
  if (csv_out) write_csv(csv_out->Stream());
  if (!program_out->Stream().flush() || (csv_out && !csv_out->Stream().flush())) {
    PrintError("io-write", "write failed for " + program + (csv_out ? " or " + csv : ""));
    return kExitBadInput;
  }
  if (err = program_out->Commit(); err.empty() && csv_out) err = csv_out->Commit();
  if (!err.empty()) {
    PrintError("io-write", err);
    return kExitBadInput;
  }
  return kExitOk;
}

std::optional<LoadedScene> LoadSceneAndRobot(const std::filesystem::path& scene_file) {
  DiagnosticSink sink;
  std::optional<LoadedScene> out = run::LoadScene(scene_file, SceneLoadOptions(), sink);
  if (PrintDiagnostics(sink)) return std::nullopt;
  return out;
}

const scene::PathSpec* PathOrReport(const scene::Scene& scene, const std::string& file,
                                    const std::string& name) {
  const planner::PathChoice choice = planner::ChoosePath(scene, name);
  if (!choice.status.Ok()) PrintError(choice.status.code, file + ": " + choice.status.message);
  return choice.path;
}

int PrintRunOutcome(const DiagnosticSink& sink, const run::Status& status) {
  const bool sink_errors = PrintDiagnostics(sink);
  if (status.ok && !sink_errors) return kExitOk;
  if (!status.code.empty()) PrintError(status.code, status.message);
  return status.code == "internal" ? kExitInternal : kExitBadInput;
}

}  // namespace stitchsim::app
