#pragma once
// Shared pieces of the stitchsim subcommands: exit codes, diagnostics output, scene loading.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/status.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFindings = 1;  ///< well-formed input the cell cannot run
inline constexpr int kExitBadInput = 2;  ///< malformed input, missing file, ...
inline constexpr int kExitInternal = 3;  ///< a bug: an exception nothing else caught

/// Scene loading options shared by every subcommand (`--allow-outside-paths`).
scene::LoadOptions& SceneLoadOptions();
/// Adds `--allow-outside-paths` to a subcommand that reads a scene.
void AddScenePathFlag(CLI::App& cmd);

/// Refuses (io-same-output, printed; false) two output options naming one file, before
/// anything runs. Pairs of option name and path; empty paths are not given.
bool OutputsDistinct(const std::vector<std::pair<std::string, std::string>>& outputs);

/// Refuses (io-missing-file, printed; false) a programme path that is not a regular file or a
/// pipe (a directory, a device).
bool ProgramInputOk(const std::string& path);

/// Prints every diagnostic to stderr; returns true if any was an error.
bool PrintDiagnostics(const DiagnosticSink& sink);

/// Prints a run function's diagnostics, then its error as PrintError does; the exit code:
/// kExitOk, kExitInternal for an "internal" error, else kExitBadInput.
int PrintRunOutcome(const DiagnosticSink& sink, const run::Status& status);

/// Prints "stitchsim: error[code]: message" for a problem that has no file position.
void PrintError(const std::string& code, const std::string& message);

/// The dialect of a --dialect option: the built-in one when `file` is empty, else the file;
/// nullopt (diagnostics printed) when the file is bad.
std::optional<program::Dialect> DialectOption(const std::string& file);

/// Writes a programme and, when `csv` is not empty, a CSV beside it, through temporaries
/// renamed as a set only when both were written: both or neither. kExitOk, or kExitBadInput
/// with io-write printed.
int WriteProgramAndCsv(const std::string& program, const std::string& csv,
                       const std::function<void(std::ostream&)>& write_program,
                       const std::function<void(std::ostream&)>& write_csv);

using run::LoadedScene;

/// The scene's path named `name` (the first path when empty); reported (plan-unknown-path,
/// with the names there are; `file` names the scene) and nullptr when there is none.
const scene::PathSpec* PathOrReport(const scene::Scene& scene, const std::string& file,
                                    const std::string& name);

/// Loads the scene and the cell URDF it names; prints diagnostics; nullopt on any error.
std::optional<LoadedScene> LoadSceneAndRobot(const std::filesystem::path& scene_file);

}  // namespace stitchsim::app
