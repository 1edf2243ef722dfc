#pragma once
// `verify --html`: one self-contained HTML file (docs/report-format.md, "HTML report"): the
// report, the snapshots, and the data the page's 3D view and plots draw (the cell's bodies
// and meshes, the part, the stitches by verdict, the AFP laid tows, the robot's poses along the
// programme, every rule's values along it), with three.js embedded at build time.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/run/pose_track.h"
#include "stitchsim/run/status.h"
#include "stitchsim/verify/report.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

/// What the page shows.
struct HtmlInputs {
  const verify::Report* report = nullptr;      ///< not owned; the run's report
  const verify::Verifier* verifier = nullptr;  ///< not owned; finished, with stitch marks
  const LoadedScene* scene = nullptr;          ///< not owned; the scene and its robot
  const PoseTrack* poses = nullptr;            ///< not owned; line-end poses, thinned
  /// Snapshot PNGs (file name, file bytes), in the order shown.
  std::vector<std::pair<std::string, std::string>> snapshots;
};

/// Bounds that keep a whole-wing page under 50 MB and quick to open.
struct HtmlLimits {
  std::size_t max_stitches = 300000;  ///< stitch points drawn (flagged ones first)
  std::size_t max_poses = 60000;      ///< thinned line-end poses (finding lines always kept)
  std::size_t max_faces = 300000;     ///< mesh faces of the cell and part together
  std::size_t max_findings = 5000;    ///< findings listed (the report keeps 200 a rule)
  /// AFP laid tows: floats of the strips' stations (fraction, tool, normal, tow edges), ~4
  /// bytes each before base64; past it stations merge and strips become one ribbon.
  std::size_t max_laid_values = 4000000;
};

/// The page's data (the JSON the page reads); `error` set and null on failure.
nlohmann::json HtmlData(const HtmlInputs& in, const HtmlLimits& limits, std::string& error);

/// The page: the template with three.js, the app and `data` put in. Throws nothing; returns
/// "" with `error` set when an asset cannot be embedded safely.
std::string HtmlPage(const nlohmann::json& data, std::string& error);

/// The same for any page: `page_template` with its markers (<!--STITCHSIM:THREE-->, ORBIT,
/// APP, DATA, and AFP unless `afp_js` is empty) replaced by three.js, its orbit controls,
/// `app_js`, `data` and `afp_js`.
std::string HtmlPageOf(std::string_view page_template, std::string_view app_js,
                       std::string_view afp_js, const nlohmann::json& data, std::string& error);

/// Writes the page whole or not at all. Errors: "html" (the data cannot be made), "internal"
/// (an asset cannot be embedded: a bug), "io-write" (the file).
Status WriteHtmlReportFile(const std::string& path, const HtmlInputs& in);

}  // namespace stitchsim::run
