#pragma once
// The documented limits on what one input may ask of stitchsim (docs/limits.md). Inputs
// beyond them are refused up front with a diagnostic, so a small file cannot make the tool
// run for hours or take gigabytes. One place, so the docs and the code agree.

#include <cstdint>

namespace stitchsim::limits {

/// Scene, head spec, dialect and user-library YAML files.
inline constexpr std::uint64_t kMaxYamlFileBytes = 2u << 20;  // 2 MiB (yaml-cpp: ~90x in memory)
/// Nodes of one YAML document counted with its aliases expanded: an alias past it is refused
/// (ten levels of ten aliases stand for ten billion). Only aliases can reach it: a 2 MiB file
/// without them holds at most about two million nodes (`{a,b,...}`: a key and a null each).
inline constexpr std::uint64_t kMaxYamlNodes = 4'000'000;
/// Largest magnitude of a length read from a scene (sizes, radii, coordinates, offsets) and
/// of an STL vertex coordinate a scene names, in millimetres: 1 km.
inline constexpr double kMaxLengthMm = 1e6;
/// URDF and MJCF model files.
inline constexpr std::uint64_t kMaxModelFileBytes = 32u << 20;  // 32 MiB
/// STL meshes (surface and constraints); a binary STL of this size holds ~670,000 triangles.
inline constexpr std::uint64_t kMaxStlFileBytes = 32u << 20;  // 32 MiB
/// Paths in one scene.
inline constexpr int kMaxScenePaths = 10'000;
/// Stitches the stitch planner writes for one path (the benches use 1 million).
inline constexpr long kMaxStitchesPerPath = 2'000'000;
/// Points of one AFP course (held in memory, ~300 bytes each: a 2.5 km course at 5 mm).
inline constexpr long kMaxAfpPointsPerCourse = 500'000;
/// Stitches of one raster programme (the full-size wing cover has 1.66 million).
inline constexpr long kMaxRasterStitches = 20'000'000;
/// Trace samples the executor takes on one programme line; a line needing more is a finding
/// on that line (`program.line_sampling`), not checked further.
inline constexpr double kMaxSamplesPerLine = 200'000;
/// Lines of one programme (the reader's counter is an int).
inline constexpr int kMaxProgramLines = 2'000'000'000;

}  // namespace stitchsim::limits
