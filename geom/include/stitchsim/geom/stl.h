#pragma once
// STL reading (ASCII and binary) into a welded triangle mesh.

#include <filesystem>
#include <string>

#include "stitchsim/geom/surface.h"

namespace stitchsim::geom {

/// Reads an STL file. On failure returns false and sets `error` (no partial mesh).
/// Vertices closer than `weld_tol` (file units) are merged; coordinates are multiplied by
/// `scale_to_mm`.
bool ReadStl(const std::filesystem::path& path, double scale_to_mm, TriangleMesh& mesh,
             std::string& error, double weld_tol = 1e-9);

/// Writes a binary STL (used by tests and `stitchsim` exports).
bool WriteStl(const std::filesystem::path& path, const TriangleMesh& mesh, std::string& error);

}  // namespace stitchsim::geom
