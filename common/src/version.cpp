#include "stitchsim/common/version.h"

namespace stitchsim {

// STITCHSIM_VERSION is set on this file only (common/CMakeLists.txt), from PROJECT_VERSION.
std::string_view ToolVersion() { return STITCHSIM_VERSION; }

}  // namespace stitchsim
