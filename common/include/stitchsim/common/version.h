#pragma once
// The stitchsim version, from the CMake project version (the one place it is written).

#include <string_view>

namespace stitchsim {

/// "0.1.0": the version of the build (CMakeLists.txt `project(... VERSION ...)`).
std::string_view ToolVersion();

}  // namespace stitchsim
