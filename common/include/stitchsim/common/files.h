#pragma once
// File helpers shared by every folder: whole-or-nothing writes and bundled data lookup.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace stitchsim {

/// Writes `contents` to a temporary file beside `path`, then renames it over `path`, so
/// readers see the old file or the whole new one. Returns an error message, or empty.
std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view contents);

/// Reads a whole file; nullopt if it cannot be opened.
std::optional<std::string> ReadFile(const std::filesystem::path& path);

/// The folder holding models/ and scenes/: $STITCHSIM_DATA_DIR, else the source tree.
std::filesystem::path DataDir();

}  // namespace stitchsim
