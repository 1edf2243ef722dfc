#pragma once
// File helpers shared by every folder: whole-or-nothing writes and bundled data lookup.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace stitchsim {

/// Writes `contents` to a temporary file beside `path`, then renames it over `path`, so
/// readers see the old file or the whole new one. Returns an error message, or empty.
std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view contents);

/// Writes several files as a set: every one goes to a temporary file first, and only when all
/// were written are they renamed into place; on failure none is (temporaries removed).
std::string WriteFilesAtomically(
    const std::vector<std::pair<std::filesystem::path, std::string>>& files);

/// Reads a whole file; nullopt if it cannot be opened.
std::optional<std::string> ReadFile(const std::filesystem::path& path);

/// The folder holding models/ and scenes/: $STITCHSIM_DATA_DIR, else the source tree.
std::filesystem::path DataDir();

}  // namespace stitchsim
