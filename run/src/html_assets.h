#pragma once
// Files embedded in the binary at build time (run/CMakeLists.txt): three.js and its orbit
// controls from Debian's libjs-three, and the HTML report's template and scripts (run/html/).

#include <string_view>

namespace stitchsim::run {

std::string_view ThreeJs();
std::string_view OrbitControlsJs();
std::string_view ReportTemplateHtml();
std::string_view ReportJs();
std::string_view AfpViewJs();
std::string_view SequenceTemplateHtml();  ///< `sequence --html`'s page (html/sequence.html)
std::string_view SequenceJs();            ///< and its script (html/sequence.js)

}  // namespace stitchsim::run
