#pragma once
// File helpers shared by every folder: bounded reads of regular files, whole-or-nothing
// writes, path containment, and bundled data lookup.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace stitchsim {

/// Why an input file could not be read.
enum class FileProblem { kNone, kMissing, kNotRegular, kTooLarge, kUnreadable };

/// A whole input file, or why it could not be read (then `text` is empty).
struct FileText {
  std::string text;
  FileProblem problem = FileProblem::kNone;
  std::string error;  ///< e.g. "x.stl: is a directory, not a regular file"
  bool ok() const { return error.empty(); }
};

/// Reads a regular file of at most `max_bytes`. A directory, FIFO or device is refused
/// without blocking (open with O_NONBLOCK, then fstat), as is a larger file.
FileText ReadRegularFile(const std::filesystem::path& path, std::uint64_t max_bytes);

/// Empty when `path` can be streamed as a programme (a regular file, or a pipe or FIFO);
/// else why not (missing, a directory, a device, ...). Never blocks.
std::string CheckStreamInput(const std::filesystem::path& path);

/// Reads a whole regular file (limits::kMaxModelFileBytes at most); nullopt if it cannot.
std::optional<std::string> ReadFile(const std::filesystem::path& path);

/// True when `path` (made absolute, symlinks resolved) lies inside `root` (likewise).
bool IsInsideFolder(const std::filesystem::path& path, const std::filesystem::path& root);

/// One output being written. A regular (or new) target gets a unique temporary file beside
/// it (mkstemp, so a planted name or link is never followed), renamed over the target by
/// Commit(); destroyed uncommitted, or on SIGINT/SIGTERM/SIGHUP, the temporary is removed.
/// A symlink is followed to its regular target, which is replaced (the link stays). A FIFO
/// or character device (e.g. /dev/stdout) is written through; a directory, socket or block
/// device is refused.
class OutputFile {
 public:
  /// Opens the output for `target`; nullptr and `error` set when it cannot be.
  static std::unique_ptr<OutputFile> Open(const std::filesystem::path& target, std::string& error);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& Stream();
  /// Flushes and moves the file into place; returns an error message, or empty. After an
  /// error the temporary is gone.
  std::string Commit();

 private:
  OutputFile() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes `contents` whole or not at all (OutputFile). Returns an error message, or empty.
std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view contents);

/// Writes several files as a set: every one goes to a temporary file first, and only when all
/// were written are they renamed into place; on failure none is (temporaries removed).
std::string WriteFilesAtomically(
    const std::vector<std::pair<std::filesystem::path, std::string>>& files);

/// Empty when the named outputs (pairs of option name and path; empty paths skipped) are all
/// different files; else a message naming the two options that share one.
std::string CheckDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& outputs);

/// The folder holding models/ and scenes/: $STITCHSIM_DATA_DIR, else the source tree.
std::filesystem::path DataDir();

/// The documented models folder (DataDir()/models): scenes may name files in it.
std::filesystem::path ModelsDir();

}  // namespace stitchsim
